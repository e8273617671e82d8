// Small helpers the format readers' tests share.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error.h"
#include "format_files.h"
#include "mesh/unstructured_mesh.h"

namespace sm::test {

// A folder of this process's own under the tests' output, removed with the object: ctest runs each
// test of a binary as a process of its own, two at a time, and each writes the files it reads.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : path_(std::string(SHELLMARCH_FORMATS_TEST_OUT) + "/" + name + "-" +
              std::to_string(::getpid())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// The files gmsh writes (writeGmshFiles: .msh and .su2), once per process for the tests of both.
inline const std::string& gmshFilesFolder() {
  static const ScratchFolder dir("gmsh-files");
  static const bool written = (writeGmshFiles(dir.path()), true);
  (void)written;
  return dir.path();
}

// The cluster ids of a mesh's elements of type `t`, sorted (readers need not keep an order).
inline std::vector<int32_t> clustersOf(const mesh::UnstructuredMesh& m, mesh::CellType t) {
  std::vector<int32_t> c = m.clusters[mesh::typeIndex(t)];
  std::sort(c.begin(), c.end());
  return c;
}

// `s` with the first `from` replaced by `to` (a damaged copy of a hand-written file).
inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

// `read()` must throw sm::FileError: one message that starts with `prefix` (the file) and holds
// `want` (the place and what is wrong).
template <typename Read>
void expectFileError(Read&& read, const std::string& want, const std::string& prefix) {
  try {
    read();
    ADD_FAILURE() << "read, wanted an error with: " << want;
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos)
        << e.what() << "; wanted " << want;
    EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
  }
}

}  // namespace sm::test
