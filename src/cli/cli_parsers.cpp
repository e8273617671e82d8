#include "cli/cli_parsers.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/error.h"
#include "common/setting_error.h"

namespace sm::app {
namespace {

std::string expected(size_t count, char sep) {
  return count == 1 ? std::string("a finite number")
                    : concat(count, " finite numbers separated by '", sep, "'");
}

std::vector<double> numbers(const std::string& option, const std::string& value, char sep,
                            size_t count) {
  std::vector<double> out;
  // getline drops an empty last item: "64x64x" would read as two numbers.
  if (!value.empty() && value.back() == sep)
    throw SettingError(optionKey(option), "'", value, "' is not ", expected(count, sep));
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, sep)) {
    char* end = nullptr;
    double d = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(d))
      throw SettingError(optionKey(option), "'", value, "' is not ", expected(count, sep));
    out.push_back(d);
  }
  if (out.size() != count)
    throw SettingError(optionKey(option), "'", value, "' is not ", expected(count, sep));
  return out;
}

}  // namespace

std::pair<int, int> parseSize(const std::string& option, const std::string& value) {
  auto v = numbers(option, value, 'x', 2);
  if (v[0] < 1 || v[1] < 1 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) ||
      v[0] > 16384 || v[1] > 16384)
    throw SettingError(optionKey(option), "'", value, "' is not an image size WxH (1 .. 16384)");
  return {int(v[0]), int(v[1])};
}

glm::dvec3 parseVec3(const std::string& option, const std::string& value) {
  auto v = numbers(option, value, ',', 3);
  return {v[0], v[1], v[2]};
}

std::pair<double, double> parseRange(const std::string& option, const std::string& value) {
  auto v = numbers(option, value, ',', 2);
  if (!(v[0] < v[1])) throw SettingError(optionKey(option), "'", value, "' needs LO < HI");
  // Scalars are float on the device: a range beyond float maps every value to one end.
  if (!(std::abs(v[0]) <= 3.4e38 && std::abs(v[1]) <= 3.4e38))
    throw SettingError(optionKey(option), "'", value, "' must lie within float range (+-3.4e38)");
  return {v[0], v[1]};
}

scene::ClipPlane parseClipPlane(const std::string& option, const std::string& value) {
  const size_t cmp = value.find_first_of("<>");
  if (cmp != std::string::npos) {
    const std::string axis = value.substr(0, cmp), at = value.substr(cmp + 1);
    if (axis.size() != 1 || axis.find_first_of("xyz") != 0)
      throw SettingError(optionKey(option), "'", value,
                         "' is not AXIS>VALUE or AXIS<VALUE with AXIS x, y or z");
    const int a = axis[0] - 'x';
    scene::ClipPlane p;
    p.normal = glm::dvec3(0.0);
    p.normal[a] = value[cmp] == '>' ? 1.0 : -1.0;
    p.point = glm::dvec3(0.0);
    p.point[a] = numbers(option, at, ',', 1)[0];
    return p;
  }
  auto v = numbers(option, value, ',', 6);
  scene::ClipPlane p{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  if (p.normal == glm::dvec3(0.0))
    throw SettingError(optionKey(option), "'", value,
                       "' has a zero normal (PX,PY,PZ,NX,NY,NZ keeps the side N points to)");
  scene::checkClipPlanes(std::span(&p, 1));
  return p;
}

std::vector<scene::OpacityPoint> parseOpacityPoints(const std::string& option,
                                                    const std::string& value) {
  std::vector<scene::OpacityPoint> points;
  if (!value.empty() && value.back() == ',')  // which getline would drop
    throw SettingError(optionKey(option), "'", value,
                       "' ends in ',': VALUE:OPACITY points separated by ','");
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const size_t colon = item.find(':');
    if (colon == std::string::npos)
      throw SettingError(optionKey(option), "'", item, "' is not VALUE:OPACITY (in '", value, "')");
    const double v = numbers(option, item.substr(0, colon), ',', 1)[0];
    const double a = numbers(option, item.substr(colon + 1), ',', 1)[0];
    points.push_back({v, a});
  }
  if (points.empty())
    throw SettingError(optionKey(option), "'", value, "' has no VALUE:OPACITY points");
  scene::TransferFunction check;
  check.table.resize(2);
  scene::setOpacityPoints(check, points);  // the same checks as when applied
  return points;
}

std::string formatOpacityPoints(const std::vector<scene::OpacityPoint>& points) {
  std::string out;
  char buf[64];
  for (const scene::OpacityPoint& p : points) {
    std::snprintf(buf, sizeof buf, "%.17g:%.17g", p.value, p.opacity);
    out += (out.empty() ? "" : ",") + std::string(buf);
  }
  return out;
}

std::string formatClipPlane(const scene::ClipPlane& plane) {
  std::string out;
  for (double d : {plane.point.x, plane.point.y, plane.point.z, plane.normal.x, plane.normal.y,
                   plane.normal.z}) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", d);
    out += (out.empty() ? "" : ",") + std::string(buf);
  }
  return out;
}

glm::vec4 parseNanColor(const std::string& option, const std::string& value) {
  const size_t count = size_t(std::count(value.begin(), value.end(), ',')) + 1;
  if (count != 3 && count != 4)
    throw SettingError(optionKey(option), "'", value,
                       "' is not R,G,B or R,G,B,OPACITY (numbers in [0, 1])");
  std::vector<double> v = numbers(option, value, ',', count);
  if (count == 3) v.push_back(1.0);
  for (double c : v)
    if (!(c >= 0.0 && c <= 1.0))
      throw SettingError(optionKey(option), "'", value, "' has ", c, ", outside [0, 1]");
  return glm::vec4(float(v[0]), float(v[1]), float(v[2]), float(v[3]));
}

render::Shading parseShading(const std::string& option, const std::string& value) {
  auto v = numbers(option, value, ',', 4);
  // Bounded above too: the coefficients scale colours, and huge ones overflow them to infinity.
  const auto coefficient = [](double c) { return c >= 0 && c <= 100; };
  if (!(coefficient(v[0]) && coefficient(v[1]) && coefficient(v[2]) && v[3] >= 1 && v[3] <= 1024))
    throw SettingError(optionKey(option), "'", value,
                       "' needs AMBIENT,DIFFUSE,SPECULAR in [0, 100] and a SHININESS in [1, 1024]");
  render::Shading s;
  s.enabled = true;
  s.ambient = v[0];
  s.diffuse = v[1];
  s.specular = v[2];
  s.shininess = v[3];
  return s;
}

double parsePositive(const std::string& option, const std::string& value) {
  double v = numbers(option, value, ',', 1)[0];
  if (!(v > 0)) throw SettingError(optionKey(option), value, " must be positive");
  return v;
}

int64_t parseCount(const std::string& option, const std::string& value, const char* what,
                   int64_t hi, const char* hiText) {
  char* end = nullptr;
  errno = 0;
  const long long n = std::strtoll(value.c_str(), &end, 10);
  if (value.empty() || *end || errno == ERANGE || n < 1 || n > hi)
    throw SettingError(optionKey(option), "'", value, "' is not a ", what, " (1 .. ", hiText, ")");
  return n;
}

comp::ListMode parseListMode(const std::string& value) {
  if (value == "two-pass") return comp::ListMode::TwoPass;
  if (value == "drop") return comp::ListMode::FixedDrop;
  if (value == "merge") return comp::ListMode::FixedMerge;
  throw SettingError("lists", "'", value, "' (use two-pass, drop or merge)");
}

vk::Tracer parseTracer(const std::string& value) {
  try {
    return vk::parseTracer("--tracer", value);
  } catch (const std::invalid_argument& e) {
    throw Error(e.what());
  }
}

comp::Encoding parseEncoding(const std::string& value) {
  if (value == "float") return comp::Encoding::Float;
  if (value == "rgba8") return comp::Encoding::Rgba8;
  throw SettingError("encoding", "'", value, "' (use float or rgba8)");
}

comp::PixelOwnership parsePixelOwnership(const std::string& value) {
  try {
    return comp::parseOwnership(value);
  } catch (const std::invalid_argument& e) {
    throw SettingError("pixel-ownership", e.what());
  }
}

comp::CompositeMethod parseCompositeMethod(const std::string& value) {
  if (value == "deep") return comp::CompositeMethod::Deep;
  if (value == "single") return comp::CompositeMethod::SingleFragment;
  throw SettingError("composite", "'", value, "' (use deep or single)");
}

render::Integration parseIntegration(const std::string& value) {
  if (value == "sampled") return render::Integration::Sampled;
  if (value == "exact") return render::Integration::ElementExact;
  throw SettingError("integration", "'", value, "' (use sampled or exact)");
}

}  // namespace sm::app
