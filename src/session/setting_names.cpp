#include "session/setting_names.h"

#include <cctype>
#include <map>

namespace sm::session {
namespace {

// Where the API's field is not the option's name in camelCase.
const std::map<std::string, std::string>& apiRenames() {
  static const std::map<std::string, std::string> renames = {
      {"size", "width/height"},   {"step", "sampleDistance"}, {"clip", "clipPlanes"},
      {"eye", "camera.eye"},      {"at", "camera.at"},        {"up", "camera.up"},
      {"fovy", "camera.fovyDeg"}, {"opacity", "table"},
  };
  return renames;
}

}  // namespace

std::string apiName(const std::string& key) {
  if (auto it = apiRenames().find(key); it != apiRenames().end()) return it->second;
  std::string name;
  bool upper = false;
  for (char c : key) {
    if (c == '-') {
      upper = true;
      continue;
    }
    name += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return name;
}

std::string pythonName(const std::string& key) {
  std::string name = key;
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

std::string apiMessage(const SettingError& e) {
  return apiName(e.key()) + ": " + e.detail();
}

std::string pythonMessage(const SettingError& e) {
  return pythonName(e.key()) + ": " + e.detail();
}

}  // namespace sm::session
