// Helpers of the bench smoke tests: a tiny mesh on disk and running the tool.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm::test {

// A cube of 5-tetrahedra cells in 2 clusters with the analytic fields, as .pvtu under dir.
std::string writeTinyMesh(const std::string& dir);

// Runs `shellmarch ARGS` with output to dir/NAME.log; returns the exit status (and the log's text
// in `log`).
int runTool(const std::vector<std::string>& args, const std::string& dir, const std::string& name,
            std::string& log);

nlohmann::json readJson(const std::string& path);

// The dotted paths (e.g. "meshes.0.stages.load.seconds") missing from j.
std::vector<std::string> missingKeys(const nlohmann::json& j,
                                     const std::vector<std::string>& paths);

// Whether /usr/bin/python3 imports VTK (the peers' results are checked only then).
bool vtkAvailable();

}  // namespace sm::test
