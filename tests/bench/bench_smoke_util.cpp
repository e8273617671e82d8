#include "bench_smoke_util.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "gen/generate.h"
#include "io/mesh_io.h"
#include "partition/partition.h"

namespace sm::test {

std::string writeTinyMesh(const std::string& dir) {
  mesh::UnstructuredMesh m = gen::cube(gen::CubeSplit::Tets5, 6);
  partition::assignMetisClusters(m, 2, 1);
  gen::addAnalyticFields(m, 1);
  const std::string path = dir + "/tiny.pvtu";
  io::writePvtu(path, m);
  return path;
}

namespace {
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q.append("'\\''");
    else
      q.push_back(c);
  }
  q.push_back('\'');
  return q;
}
}  // namespace

int runTool(const std::vector<std::string>& args, const std::string& dir, const std::string& name,
            std::string& log) {
  std::string logPath = dir;
  logPath.append("/").append(name).append(".log");
  std::string cmd = quote(SHELLMARCH_EXE);
  for (const auto& a : args) cmd.append(" ").append(quote(a));
  cmd.append(" > ").append(quote(logPath)).append(" 2>&1");
  int status = std::system(cmd.c_str());
  std::ifstream in(logPath);
  std::stringstream ss;
  ss << in.rdbuf();
  log = ss.str();
  return status;
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

std::vector<std::string> missingKeys(const nlohmann::json& j,
                                     const std::vector<std::string>& paths) {
  std::vector<std::string> missing;
  for (const std::string& p : paths) {
    const nlohmann::json* at = &j;
    std::stringstream ss(p);
    std::string key;
    bool found = true;
    while (found && std::getline(ss, key, '.')) {
      if (at->is_array() && !key.empty() && std::isdigit(static_cast<unsigned char>(key[0]))) {
        size_t i = std::stoul(key);
        found = i < at->size();
        if (found) at = &(*at)[i];
      } else {
        found = at->is_object() && at->contains(key);
        if (found) at = &(*at)[key];
      }
    }
    if (!found) missing.push_back(p);
  }
  return missing;
}

bool vtkAvailable() {
  return std::system("/usr/bin/python3 -c 'import vtkmodules.all' > /dev/null 2>&1") == 0;
}

}  // namespace sm::test
