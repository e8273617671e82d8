#include "app/cli_checks.h"

#include <filesystem>
#include <string>

namespace sm::app {

CLI::Validator nonEmptyName() {
  return CLI::Validator(
      [](std::string& s) { return s.empty() ? std::string("must not be empty") : std::string(); },
      "NAME");
}

CLI::Validator writableFile() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        std::error_code ec;
        const std::filesystem::path p(path);
        if (std::filesystem::is_directory(p, ec)) return "'" + path + "' is a folder";
        const std::filesystem::path dir = p.parent_path();
        if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
          return "'" + path + "' is in a folder that does not exist ('" + dir.string() + "')";
        return {};
      },
      "FILE");
}

}  // namespace sm::app
