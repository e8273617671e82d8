// Names and attributes shared by the .vtu and .pvtu writers (vtu_writer.cpp, pvtu_writer.cpp):
// an index must declare every array exactly as its pieces name it.
#pragma once

#include <cstdint>
#include <string>

#include "mesh/unstructured_mesh.h"

namespace sm::io {

std::string xmlEscape(const std::string& s);
// The array holding step s of f: NAME@t<s> when f has several steps, or when its name alone
// would read back as a step (a one-step field "p@t3" is written "p@t3@t0").
std::string arrayName(const mesh::Field& f, uint64_t s);
std::string arrayName(const mesh::CellField& f, uint64_t s);
// type="T" Name="NAME" [NumberOfComponents="N"]: a DataArray's (or PDataArray's) attributes.
std::string dataArray(const char* type, const std::string& name, uint32_t components = 1);

}  // namespace sm::io
