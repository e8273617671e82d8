// make_format_files FORMAT FOLDER: writes the test files of FORMAT (cgns, exodus, gmsh) into
// FOLDER with that format's own writer and prints their paths, one per line.
#include <filesystem>
#include <iostream>
#include <string>

#include "format_files.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_format_files cgns|exodus|gmsh FOLDER\n";
    return 2;
  }
  const std::string format = argv[1], folder = argv[2];
  std::filesystem::create_directories(folder);
  try {
    std::vector<std::string> files;
    if (format == "cgns")
      files = sm::test::writeCgnsFiles(folder);
    else if (format == "exodus")
      files = sm::test::writeExodusFiles(folder);
    else if (format == "gmsh")
      files = sm::test::writeGmshFiles(folder);
    else {
      std::cerr << "make_format_files: unknown format '" << format << "'\n";
      return 2;
    }
    for (const std::string& f : files) std::cout << f << "\n";
  } catch (const std::exception& e) {
    std::cerr << "make_format_files: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
