#include "viewer/render_args.h"

#include <cstdio>

#include "cli/cli_parsers.h"

namespace sm::view {
namespace {

std::string exact(double v) {
  return formatNumber("%.17g", v);
}

std::string vec(const glm::dvec3& v) {
  return exact(v.x) + "," + exact(v.y) + "," + exact(v.z);
}

}  // namespace

std::string formatNumber(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::vector<std::string> renderArgs(const ViewState& state, int width, int height,
                                    const FrameLook& look) {
  const FieldInfo& f = look.field;
  std::vector<std::string> args = {"--size=" + std::to_string(width) + "x" + std::to_string(height),
                                   "--eye=" + vec(state.eye),
                                   "--at=" + vec(state.at),
                                   "--up=" + vec(state.up),
                                   "--fovy=" + exact(state.fovyDeg),
                                   "--field=" + f.name,
                                   "--time=" + std::to_string(state.step),
                                   "--colormap=" + look.colormap,
                                   "--range=" + exact(f.range.first) + "," + exact(f.range.second),
                                   "--opacity-scale=" + exact(state.opacityScale),
                                   "--step=" + exact(state.dt),
                                   "--unit-distance=" + exact(look.transferFunction.unitDistance)};
  if (state.parallel) args.push_back("--parallel-scale=" + exact(state.parallelScale));
  if (look.legend) args.push_back("--legend");
  if (look.sampled) args.push_back("--integration=sampled");
  if (look.transferFunction.scale == scene::ScalarScale::Log) args.push_back("--log-scale");
  if (!look.opacityPoints.empty())
    args.push_back("--opacity=" + app::formatOpacityPoints(look.opacityPoints));
  for (const scene::ClipPlane& p : look.clipPlanes)
    args.push_back("--clip=" + app::formatClipPlane(p));
  return args;
}

}  // namespace sm::view
