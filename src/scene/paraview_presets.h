// ParaView's colour-map presets by the names ParaView gives them (`--colormap "Cool to Warm"`):
// the most used ones of ParaView's ColorMaps.json, kept in ParaView's preset format
// (paraview_presets_data.cpp, written by tools/make_paraview_presets.py).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace sm::scene {

// The presets, each a ParaView colour map as JSON text.
std::span<const char* const> paraViewPresetTexts();

// The presets' names, in the order of the file.
const std::vector<std::string>& paraViewPresetNames();

// The preset named `name`, spelled exactly or with another case; nullptr when there is none.
const nlohmann::json* findParaViewPreset(const std::string& name);

// Up to `most` of `candidates` closest to `name` (case ignored: edit distance, and names that
// contain it or that it contains first), for an error's suggestions.
std::vector<std::string> closestNames(const std::string& name,
                                      const std::vector<std::string>& candidates, size_t most = 3);

}  // namespace sm::scene
