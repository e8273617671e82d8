// Parsers for option values (sizes, vectors, ranges, enums) with one-line errors naming the option.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include <glm/vec3.hpp>

#include "app/cli_checks.h"
#include "compositor/deep_compositor.h"
#include "render/render_settings.h"

namespace sm::app {

std::pair<int, int> parseSize(const std::string& option, const std::string& value);  // "WxH"
glm::dvec3 parseVec3(const std::string& option, const std::string& value);           // "x,y,z"
std::pair<double, double> parseRange(const std::string& option,
                                     const std::string& value);  // "lo,hi"
// A whole number in 1 .. hi, else an error naming the option, `what` it counts and hiText.
int64_t parseCount(const std::string& option, const std::string& value, const char* what,
                   int64_t hi, const char* hiText);
double parsePositive(const std::string& option, const std::string& value);  // > 0, finite
comp::ListMode parseListMode(const std::string& value);                // two-pass | drop | merge
comp::Encoding parseEncoding(const std::string& value);                // float | rgba8
comp::PixelOwnership parsePixelOwnership(const std::string& value);    // interleaved | ranges
comp::CompositeMethod parseCompositeMethod(const std::string& value);  // deep | single
render::Integration parseIntegration(const std::string& value);        // sampled | exact
render::Shading parseShading(const std::string& option, const std::string& value);  // "ka,kd,ks,n"

}  // namespace sm::app
