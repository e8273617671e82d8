// Test files written by each format's own writer (libcgns, libexodusii, the gmsh API), so that
// the readers are tested on files the ecosystems produce, not only on files of our making.
// Every writer takes the folder and returns the paths written; `make_format_files` runs them for
// the scripts that compare shellmarch with VTK and meshio.
#pragma once

#include <string>
#include <vector>

namespace sm::test {

std::vector<std::string> writeCgnsFiles(const std::string& folder);
std::vector<std::string> writeExodusFiles(const std::string& folder);
// .msh (4.1 ASCII and binary, partitioned) and .su2 files, both written by gmsh.
std::vector<std::string> writeGmshFiles(const std::string& folder);

}  // namespace sm::test
