#include "io/vtk_xml_names.h"

#include "common/error.h"
#include "io/mesh_io.h"
#include "io_core/array_plan.h"

namespace sm::io {

std::string xmlEscape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      default:
        r += c;
    }
  }
  return r;
}

std::string arrayName(const mesh::Field& f, uint64_t s) {
  return f.numSteps() > 1 || splitStepName(f.name).step ? concat(f.name, "@t", s) : f.name;
}

std::string arrayName(const mesh::CellField& f, uint64_t s) {
  return f.steps.size() > 1 || splitStepName(f.name).step ? concat(f.name, "@t", s) : f.name;
}

std::string dataArray(const char* type, const std::string& name, uint32_t components) {
  std::string s = concat("type=\"", type, "\" Name=\"", xmlEscape(name), "\"");
  if (components > 1) s += concat(" NumberOfComponents=\"", components, "\"");
  return s;
}

}  // namespace sm::io
