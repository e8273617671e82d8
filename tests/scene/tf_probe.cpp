// Prints what shellmarch makes of colour and opacity maps, for vtk_peers_test.py to compare with
// VTK's own vtkColorTransferFunction and vtkPiecewiseFunction:
//   tf_probe table MAP N            N rows "r g b a" of makeTransferFunction(MAP, N)
//   tf_probe color SPACE WRAP N     N rows "r g b" at x = i / (N - 1), nodes "x r g b midpoint
//                                   sharpness" on standard input
//   tf_probe opacity N              N values, nodes "x y midpoint sharpness" on standard input
//   tf_probe presets                the preset names, then each preset's JSON, one per line
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/error.h"
#include "scene/control_points.h"
#include "scene/paraview_presets.h"
#include "scene/transfer_function.h"

namespace {

using namespace sm::scene;

int usage() {
  std::cerr << "usage: tf_probe table MAP N | color SPACE WRAP N | opacity N | presets\n";
  return 2;
}

double at(int i, int n) {
  return n > 1 ? double(i) / double(n - 1) : 0.0;
}

}  // namespace

int main(int argc, char** argv) try {
  const std::vector<std::string> a(argv + 1, argv + argc);
  if (a.size() == 3 && a[0] == "table") {
    const TransferFunction tf = makeTransferFunction(a[1], std::stoi(a[2]));
    for (const glm::vec4& e : tf.table) std::printf("%.9g %.9g %.9g %.9g\n", e.r, e.g, e.b, e.a);
  } else if (a.size() == 4 && a[0] == "color") {
    const ColorSpace space = parseColorSpace(a[1], "tf_probe");
    std::vector<ColorNode> nodes;
    ColorNode c{};
    while (std::cin >> c.x >> c.rgb.r >> c.rgb.g >> c.rgb.b >> c.midpoint >> c.sharpness)
      nodes.push_back(c);
    const int n = std::stoi(a[3]);
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 rgb = evaluateColor(nodes, at(i, n), space, a[2] != "0");
      std::printf("%.17g %.17g %.17g\n", rgb.r, rgb.g, rgb.b);
    }
  } else if (a.size() == 2 && a[0] == "opacity") {
    std::vector<OpacityNode> nodes;
    OpacityNode o{};
    while (std::cin >> o.x >> o.y >> o.midpoint >> o.sharpness) nodes.push_back(o);
    const int n = std::stoi(a[1]);
    for (int i = 0; i < n; ++i) std::printf("%.17g\n", evaluateOpacity(nodes, at(i, n)));
  } else if (a.size() == 1 && a[0] == "presets") {
    for (const char* text : paraViewPresetTexts()) std::printf("%s\n", text);
  } else {
    return usage();
  }
  return 0;
} catch (const sm::Error& e) {
  std::cerr << "tf_probe: " << e.what() << "\n";
  return 1;
}
