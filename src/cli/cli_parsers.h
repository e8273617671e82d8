// Parsers for option values (sizes, vectors, ranges, enums) with one-line errors naming the option.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cli/cli_checks.h"
#include "compositor/deep_compositor.h"
#include "render/render_settings.h"
#include "vk/context.h"

namespace sm::app {

std::pair<int, int> parseSize(const std::string& option, const std::string& value);  // "WxH"
glm::dvec3 parseVec3(const std::string& option, const std::string& value);           // "x,y,z"
std::pair<double, double> parseRange(const std::string& option,
                                     const std::string& value);  // "lo,hi"
// A whole number in 1 .. hi, else an error naming the option, `what` it counts and hiText.
int64_t parseCount(const std::string& option, const std::string& value, const char* what,
                   int64_t hi, const char* hiText);
double parsePositive(const std::string& option, const std::string& value);  // > 0, finite
vk::Tracer parseTracer(const std::string& value);                      // auto | query | pipeline
comp::ListMode parseListMode(const std::string& value);                // two-pass | drop | merge
comp::Encoding parseEncoding(const std::string& value);                // float | rgba8
comp::PixelOwnership parsePixelOwnership(const std::string& value);    // interleaved | ranges
comp::CompositeMethod parseCompositeMethod(const std::string& value);  // deep | single
render::Integration parseIntegration(const std::string& value);        // sampled | exact
// "px,py,pz,nx,ny,nz" (the plane through p keeping the side n points into) or "AXIS>V" / "AXIS<V"
// (x, y or z: the side of the plane AXIS = V where the coordinate is greater or less than V).
scene::ClipPlane parseClipPlane(const std::string& option, const std::string& value);
// The 6-number form of a plane, with enough digits to read back the same doubles.
std::string formatClipPlane(const scene::ClipPlane& plane);
// "V:A,V:A,..." opacity control points in data values (scene::setOpacityPoints checks them).
std::vector<scene::OpacityPoint> parseOpacityPoints(const std::string& option,
                                                    const std::string& value);
std::string formatOpacityPoints(const std::vector<scene::OpacityPoint>& points);  // exact
// "r,g,b" or "r,g,b,opacity", each in [0, 1] (opacity 1 when not given).
glm::vec4 parseNanColor(const std::string& option, const std::string& value);
render::Shading parseShading(const std::string& option, const std::string& value);  // "ka,kd,ks,n"

}  // namespace sm::app
