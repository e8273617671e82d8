#include "cli/cli_checks.h"

#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <vector>

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

namespace {
std::set<const CLI::Option*>& emptyAllowed() {
  static std::set<const CLI::Option*> options;
  return options;
}
}  // namespace

CLI::Option* allowEmptyValue(CLI::Option* option) {
  emptyAllowed().insert(option);
  return option;
}

std::vector<std::string> parserArguments(int argc, const char* const* argv) {
  int end = 1;  // arguments after "--" are not options
  while (end < argc && std::string_view(argv[end]) != "--") ++end;
  std::vector<std::string> args;
  for (int i = argc - 1; i >= 1; --i) {
    const std::string_view a = argv[i];
    if (i < end && a.size() > 3 && a.rfind("--", 0) == 0 && a.find('=') == a.size() - 1) {
      args.emplace_back();
      args.emplace_back(a.substr(0, a.size() - 1));
    } else {
      args.emplace_back(a);
    }
  }
  return args;
}

void refuseEmptyValues(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() == 0 || o->get_type_size() == 0 || emptyAllowed().count(o)) continue;  // flags
    for (const std::string& r : o->results())
      if (r.empty()) throw CLI::ValidationError(o->get_name(), "must not be empty");
  }
  for (const CLI::App* sub : app.get_subcommands()) refuseEmptyValues(*sub);
}

}  // namespace sm::app
