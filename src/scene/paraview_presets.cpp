#include "scene/paraview_presets.h"

#include <algorithm>
#include <cctype>

#include <nlohmann/json.hpp>

namespace sm::scene {
namespace {

std::string lowered(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// Parsed once: an in-situ caller builds its transfer function every frame.
const std::vector<nlohmann::json>& presets() {
  static const std::vector<nlohmann::json> parsed = [] {
    std::vector<nlohmann::json> v;
    for (const char* text : paraViewPresetTexts()) v.push_back(nlohmann::json::parse(text));
    return v;
  }();
  return parsed;
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

const std::vector<std::string>& paraViewPresetNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const nlohmann::json& m : presets()) v.push_back(m["Name"].get<std::string>());
    return v;
  }();
  return names;
}

const nlohmann::json* findParaViewPreset(const std::string& name) {
  const std::vector<std::string>& names = paraViewPresetNames();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return &presets()[i];
  const std::string lower = lowered(name);
  for (size_t i = 0; i < names.size(); ++i)
    if (lowered(names[i]) == lower) return &presets()[i];
  return nullptr;
}

std::vector<std::string> closestNames(const std::string& name,
                                      const std::vector<std::string>& candidates, size_t most) {
  const std::string lower = lowered(name);
  // Ranked by edit distance; a name that holds the other ("viridis" in "Viridis (matplotlib)")
  // ranks as if one edit away.
  std::vector<std::pair<size_t, std::string>> ranked;
  for (const std::string& c : candidates) {
    const std::string lc = lowered(c);
    size_t d = editDistance(lower, lc);
    if (!lower.empty() &&
        (lc.find(lower) != std::string::npos || lower.find(lc) != std::string::npos))
      d = std::min<size_t>(d, 1);
    ranked.emplace_back(d, c);
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (const auto& [d, c] : ranked) {
    // Beyond half the name's length the suggestion would be noise.
    if (out.size() >= most || d > std::max<size_t>(3, lower.size() / 2)) break;
    out.push_back(c);
  }
  return out;
}

}  // namespace sm::scene
