// One input through each loader that reads other people's bytes, by the loader's ordinary entry
// point. Shared by the libFuzzer targets (tests/fuzz/fuzz_*.cpp) and the regression test that
// replays every committed input in the normal test suite (tests/reliability).
//
// An input may be accepted or rejected with the loader's documented error; anything else is a bug
// and throws FuzzBug: another exception type, a message that does not name the input or spans
// lines, a mesh or prepared rank that breaks its own invariants, a colour table outside [0, 1].
// Crashes, sanitizer reports and huge allocations are caught by the fuzzer's runtime instead.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/unstructured_mesh.h"

namespace sm::fuzz {

class FuzzBug : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

enum class Target { Vtu, Pvtu, LegacyVtk, Ugrid, Cache, Colormap, Su2, Gmsh, Cgns, Exodus };

// Target names as used for corpus and regression folders: "vtu", "pvtu", "legacy_vtk", "ugrid",
// "cache", "colormap", "su2", "gmsh", "cgns", "exodus".
const std::vector<std::string>& targetNames();
Target targetByName(const std::string& name);  // throws std::invalid_argument

// Runs one input; returns "" when it was accepted, else the message it was rejected with.
std::string runInput(Target target, std::span<const uint8_t> bytes);

// .pvtu inputs are bundles: the index, then each piece, separated by kPieceSeparator. The index
// is read as "fuzz/index.pvtu"; the k-th distinct piece path it asks for gets part k of the bundle
// (whatever its Source says), and a path beyond the bundle does not exist.
inline constexpr std::string_view kPieceSeparator = "\n===piece===\n";
// Reads a bundle as the .pvtu target does (throws sm::FileError for a rejected one). `opened`,
// when given, receives every path the reader asked for, the index first.
mesh::UnstructuredMesh readPvtuBundle(std::span<const uint8_t> bytes,
                                      std::vector<std::string>* opened = nullptr);

// CGNS and Exodus II inputs are read through their libraries, which open files: the input is
// written to a file of this process's own in the temporary folder and read from there.

// .ugrid inputs: the first byte picks the variant (ascii, b8, lb8, b8l, ...), the rest is the file.
const std::vector<std::string>& ugridVariants();  // "" for ascii, then the binary suffixes

}  // namespace sm::fuzz
