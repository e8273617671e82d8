// A setting the caller gave that cannot be used, keyed by the setting's neutral name: the command
// line's option without its dashes ("colormap", "step", "clip"). what() is the command line's
// text, "--colormap: <detail>"; the in-situ API and the Python module show the key by their own
// names for it (session/setting_names.h), so no layer below the front ends needs to know which
// front end asked.
#pragma once

#include <string>
#include <utility>

#include "common/error.h"

namespace sm {

class SettingError : public Error {
 public:
  template <typename... Args>
  SettingError(std::string key, Args&&... detail)
      : SettingError(Keyed{}, std::move(key), concat(std::forward<Args>(detail)...)) {}
  const std::string& key() const { return key_; }
  const std::string& detail() const { return detail_; }

 private:
  struct Keyed {};
  SettingError(Keyed, std::string key, std::string detail)
      : Error(printableLine("--" + key + ": " + detail)),
        key_(std::move(key)),
        detail_(printableLine(std::move(detail))) {}
  std::string key_, detail_;
};

// The key of a command-line option: "--colormap" -> "colormap".
inline std::string optionKey(const std::string& option) {
  return option.substr(option.find_first_not_of('-') == std::string::npos
                           ? option.size()
                           : option.find_first_not_of('-'));
}

}  // namespace sm
