#include "scene/transfer_function.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "common/setting_error.h"
#include "scene/color_space.h"
#include "scene/colormap_data.h"
#include "scene/control_points.h"
#include "scene/paraview_presets.h"

namespace sm::scene {

double TransferFunction::coordinate(double s) const {
  if (!(hi > lo)) return 0.5;
  if (scale == ScalarScale::Log)  // s <= 0 lies below any positive range
    return s > 0.0 ? std::clamp(std::log(s / lo) / std::log(hi / lo), 0.0, 1.0) : 0.0;
  return std::clamp((s - lo) / (hi - lo), 0.0, 1.0);
}

double TransferFunction::valueAt(double x) const {
  if (!(hi > lo)) return lo;
  if (scale == ScalarScale::Log) return x <= 0.0 ? lo : x >= 1.0 ? hi : lo * std::pow(hi / lo, x);
  return lo + x * (hi - lo);
}

void checkScale(const TransferFunction& tf) {
  if (tf.scale == ScalarScale::Log && !(tf.lo > 0.0 && std::isfinite(tf.hi)))
    throw SettingError("log-scale", "a log scale needs a positive range, not ", tf.lo, " .. ",
                       tf.hi, ": give a range LO,HI with 0 < LO < HI");
}

glm::dvec4 TransferFunction::lookup(double s) const {
  if (!std::isfinite(s)) return glm::dvec4(glm::dvec3(nanColor), double(nanOpacity));
  if (table.empty()) return glm::dvec4(0.0);
  const double x = coordinate(s) * double(table.size() - 1);
  size_t i = std::min(size_t(x), table.size() - 1);
  size_t j = std::min(i + 1, table.size() - 1);
  double f = x - double(i);
  return glm::dvec4(table[i]) * (1.0 - f) + glm::dvec4(table[j]) * f;
}

double TransferFunction::extinction(double s) const {
  return lookup(s).a * opacityScale / unitDistance;
}

std::vector<std::string> builtinColormapNames() {
  std::vector<std::string> names;
  for (const auto& m : builtinColormaps()) names.emplace_back(m.name);
  names.emplace_back("grayscale");
  return names;
}

namespace {

std::vector<glm::vec4> rampOpacity(std::vector<glm::vec4> t) {
  for (size_t i = 0; i < t.size(); ++i) t[i].a = float(i) / float(t.size() - 1);
  return t;
}

TransferFunction fromBuiltin(const std::string& name, int entries) {
  TransferFunction tf;
  tf.table.resize(entries);
  if (name == "grayscale" || name == "greyscale") {
    for (int i = 0; i < entries; ++i) {
      float v = float(i) / float(entries - 1);
      tf.table[i] = glm::vec4(v, v, v, 0);
    }
    tf.table = rampOpacity(std::move(tf.table));
    return tf;
  }
  for (const auto& m : builtinColormaps()) {
    if (m.name != name) continue;
    for (int i = 0; i < entries; ++i) {
      double x = double(i) / double(entries - 1) * 255.0;
      int a = std::min(int(x), 255), b = std::min(a + 1, 255);
      double f = x - a;
      glm::dvec3 ca(m.rgb[3 * a], m.rgb[3 * a + 1], m.rgb[3 * a + 2]);
      glm::dvec3 cb(m.rgb[3 * b], m.rgb[3 * b + 1], m.rgb[3 * b + 2]);
      tf.table[i] = glm::vec4(glm::vec3(ca * (1 - f) + cb * f), 0);
    }
    tf.table = rampOpacity(std::move(tf.table));
    return tf;
  }
  throw SettingError("colormap", "no built-in colour map '", name, "'");
}

bool isBuiltin(const std::string& name) {
  const std::vector<std::string> names = builtinColormapNames();
  return name == "greyscale" || std::find(names.begin(), names.end(), name) != names.end();
}

std::string lowered(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string presetName(const nlohmann::json& map) {
  return map.is_object() && map.contains("Name") && map["Name"].is_string()
             ? map["Name"].get<std::string>()
             : std::string();
}

// The colour map `preset` names in a ParaView preset file (an array of maps, as ParaView exports
// them, or one map), or without a name the first, with a warning when there are others. By
// reference: a copy of a deeply nested document recurses as deep as it nests.
const nlohmann::json& choosePreset(const nlohmann::json& j, const std::string& src,
                                   const std::string& preset) {
  if (!j.is_array()) {
    if (preset.empty() || presetName(j) == preset) return j;
    throw FileError(src, "has no colour map named '", preset, "' (it holds '", presetName(j), "')");
  }
  if (j.empty()) throw FileError(src, "empty colour-map array");
  std::string names;
  for (const auto& m : j) names += (names.empty() ? "'" : ", '") + presetName(m) + "'";
  if (preset.empty()) {
    // Once per file: an in-situ caller builds its transfer function every frame.
    if (j.size() > 1 && log::firstTime("colormap presets " + src))
      log::warning(src, ": holds ", j.size(), " colour maps (", names,
                   "); rendering the first; name one as ", src, ":NAME");
    return j[0];
  }
  for (const auto& m : j)
    if (presetName(m) == preset) return m;
  throw FileError(src, "has no colour map named '", preset, "' (it holds ", names, ")");
}

// Values of an array member of a ParaView map, all finite numbers.
std::vector<double> numbers(const nlohmann::json& j, const char* key, const std::string& src) {
  std::vector<double> v;
  if (!j.contains(key)) return v;
  if (!j[key].is_array()) throw FileError(src, "\"", key, "\" is not an array");
  for (const auto& x : j[key]) {
    if (!x.is_number()) throw FileError(src, "\"", key, "\" holds a non-number");
    double d = x.get<double>();
    if (!std::isfinite(d)) throw FileError(src, "\"", key, "\" holds a non-finite number");
    v.push_back(d);
  }
  return v;
}

// Sorts nodes by x (stable: equal x keep their order, a jump) and rescales x from the nodes' own
// range to [0, 1], as ParaView fits a preset to the data's range.
template <class Node>
void normalise(std::vector<Node>& nodes) {
  std::stable_sort(nodes.begin(), nodes.end(), [](auto& a, auto& b) { return a.x < b.x; });
  const double x0 = nodes.front().x, x1 = nodes.back().x;
  for (auto& n : nodes) n.x = x1 > x0 ? (n.x - x0) / (x1 - x0) : 0.0;
}

std::vector<ColorNode> colorNodes(const nlohmann::json& j, const std::string& src) {
  std::vector<double> rgb = numbers(j, "RGBPoints", src);
  if (rgb.size() < 8 || rgb.size() % 4 != 0)
    throw FileError(src, "\"RGBPoints\" needs at least two (x, r, g, b) points");
  std::vector<ColorNode> nodes;
  for (size_t i = 0; i < rgb.size(); i += 4)
    nodes.push_back({rgb[i], glm::clamp(glm::dvec3(rgb[i + 1], rgb[i + 2], rgb[i + 3]), 0.0, 1.0)});
  normalise(nodes);
  return nodes;
}

std::vector<OpacityNode> opacityNodes(const nlohmann::json& j, const std::string& src) {
  std::vector<double> op = numbers(j, "Points", src);
  if (op.size() % 4 != 0)
    throw FileError(src, "\"Points\" must hold (x, opacity, midpoint, sharpness) quadruples");
  std::vector<OpacityNode> nodes;
  for (size_t i = 0; i < op.size(); i += 4) {
    // As --opacity refuses them: an opacity of 2 is a mistake, not a request for full opacity.
    if (!(op[i + 1] >= 0.0 && op[i + 1] <= 1.0))
      throw FileError(src, "\"Points\": opacity ", op[i + 1], " of point ", i / 4 + 1,
                      " is outside [0, 1]");
    if (!(op[i + 2] >= 0.0 && op[i + 2] <= 1.0 && op[i + 3] >= 0.0 && op[i + 3] <= 1.0))
      throw FileError(src, "\"Points\": point ", i / 4 + 1, " has midpoint ", op[i + 2],
                      " and sharpness ", op[i + 3], " (both must be in [0, 1])");
    nodes.push_back({op[i], op[i + 1], op[i + 2], op[i + 3]});
  }
  if (!nodes.empty()) normalise(nodes);
  return nodes;
}

bool hsvWrapOf(const nlohmann::json& j, const std::string& src) {
  if (!j.contains("HSVWrap")) return false;  // ParaView's maps leave VTK's HSVWrap off
  const nlohmann::json& w = j["HSVWrap"];
  if (w.is_boolean()) return w.get<bool>();
  if (w.is_number()) return w.get<double>() != 0.0;
  throw FileError(src, "\"HSVWrap\" is not a boolean");
}

// The table of one ParaView map (an object), sampled as vtkColorTransferFunction::GetTable and
// vtkPiecewiseFunction::GetTable sample theirs over the points' range.
TransferFunction fromParaViewMap(const nlohmann::json& j, const std::string& src, int entries) {
  if (!j.is_object()) throw FileError(src, "not a ParaView colour map (expected an object)");
  ColorSpace space = ColorSpace::RGB;
  if (j.contains("ColorSpace")) {
    if (!j["ColorSpace"].is_string()) throw FileError(src, "\"ColorSpace\" is not a string");
    space = parseColorSpace(j["ColorSpace"].get<std::string>(), src);
  }
  const bool hsvWrap = hsvWrapOf(j, src);
  const std::vector<ColorNode> colors = colorNodes(j, src);
  const std::vector<OpacityNode> opacities = opacityNodes(j, src);
  TransferFunction tf;
  tf.table.resize(entries);
  for (int i = 0; i < entries; ++i) {
    const double x = double(i) / double(entries - 1);
    // Without "Points" the opacity is a ramp over the range.
    const double a = opacities.empty() ? x : evaluateOpacity(opacities, x);
    tf.table[i] = glm::vec4(glm::vec3(evaluateColor(colors, x, space, hsvWrap)), float(a));
  }
  std::vector<double> nan = numbers(j, "NanColor", src);
  if (nan.size() >= 3) tf.nanColor = glm::vec3(nan[0], nan[1], nan[2]);
  // ParaView's lookup tables carry NanOpacity since 5.10; without it NaN stays transparent.
  if (j.contains("NanOpacity")) {
    const nlohmann::json& o = j["NanOpacity"];
    if (!o.is_number()) throw FileError(src, "\"NanOpacity\" is not a number");
    const double a = o.get<double>();
    if (!(a >= 0.0 && a <= 1.0)) throw FileError(src, "\"NanOpacity\" ", a, " is not in [0, 1]");
    tf.nanOpacity = float(a);
  }
  return tf;
}

}  // namespace

TransferFunction parseParaViewColormap(const std::string& text, const std::string& src, int entries,
                                       const std::string& preset) {
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(src, "not valid JSON: ", e.what());
  }
  return fromParaViewMap(choosePreset(parsed, src, preset), src, entries);
}

void setOpacityPoints(TransferFunction& tf, std::span<const OpacityPoint> points) {
  if (points.empty()) throw SettingError("opacity", "no opacity points");
  for (size_t i = 0; i < points.size(); ++i) {
    const OpacityPoint& p = points[i];
    if (!std::isfinite(p.value) || !(p.opacity >= 0.0 && p.opacity <= 1.0))
      throw SettingError("opacity", "point ", i + 1, " (", p.value, ":", p.opacity,
                         ") needs a finite value and an opacity in [0, 1]");
    if (i > 0 && p.value < points[i - 1].value)
      throw SettingError("opacity", "point ", i + 1, " (value ", p.value, ") comes before point ",
                         i, " (value ", points[i - 1].value,
                         "): give the points in increasing value");
  }
  auto at = [&](double v) {
    if (v < points.front().value) return points.front().opacity;
    if (v >= points.back().value) return points.back().opacity;
    size_t k = 0;  // points[k].value <= v < points[k + 1].value
    while (!(v < points[k + 1].value)) ++k;
    const double f = (v - points[k].value) / (points[k + 1].value - points[k].value);
    return points[k].opacity + f * (points[k + 1].opacity - points[k].opacity);
  };
  const size_t n = tf.table.size();
  for (size_t i = 0; i < n; ++i) {
    const double x = n > 1 ? double(i) / double(n - 1) : 0.0;
    tf.table[i].a = float(at(tf.valueAt(x)));
  }
}

TransferFunction makeTransferFunction(const std::string& colormap, int entries) {
  if (entries < 256) throw Error("transfer function: ", entries, " entries (at least 256)");
  if (fileExtension(colormap) == ".json")
    return parseParaViewColormap(readTextFile(colormap), colormap, entries);
  // FILE.json:NAME picks a map of a preset file that holds several (.JSON too, as for the file).
  const std::string lower = lowered(colormap);
  if (const size_t at = lower.rfind(".json:"); at != std::string::npos) {
    const std::string file = colormap.substr(0, at + 5), name = colormap.substr(at + 6);
    if (name.empty())
      throw SettingError("colormap", "'", colormap, "' names no colour map after ':'");
    return parseParaViewColormap(readTextFile(file), file, entries, name);
  }
  // The short names first, as they were; then ParaView's preset names, spelled as ParaView does
  // or in another case; then the short names in another case ("Viridis").
  if (isBuiltin(colormap)) return fromBuiltin(colormap, entries);
  if (const nlohmann::json* preset = findParaViewPreset(colormap))
    return fromParaViewMap(*preset, "ParaView preset '" + presetName(*preset) + "'", entries);
  for (const std::string& name : builtinColormapNames())
    if (lowered(name) == lower) return fromBuiltin(name, entries);
  std::vector<std::string> all = builtinColormapNames();
  all.insert(all.end(), paraViewPresetNames().begin(), paraViewPresetNames().end());
  std::string close;
  for (const std::string& n : closestNames(colormap, all))
    close += (close.empty() ? "'" : ", '") + n + "'";
  throw SettingError(
      "colormap", "unknown colour map '", colormap, "'",
      close.empty() ? std::string() : " (closest: " + close + ")",
      "; give a built-in name, a ParaView preset name (docs/TRANSFER_FUNCTIONS.md lists "
      "them) or a ParaView .json file");
}

}  // namespace sm::scene
