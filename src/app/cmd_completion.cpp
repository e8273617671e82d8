// `shellmarch completion bash`: a bash completion script written from the command line's own
// definition (commands, options, which options take a value and which values they accept), so
// that it cannot fall behind the options. The build runs it to install
// share/bash-completion/completions/shellmarch (src/app/CMakeLists.txt).
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/commands.h"
#include "scene/transfer_function.h"

namespace sm::app {
namespace {

// Values an option accepts from a fixed set; other options with a value complete file names.
std::map<std::string, std::vector<std::string>> fixedValues() {
  std::vector<std::string> maps;
  for (const std::string& name : scene::builtinColormapNames())
    if (name.find(' ') == std::string::npos) maps.push_back(name);  // one shell word each
  return {
      {"--view", {"iso", "+x", "-x", "+y", "-y", "+z", "-z"}},
      {"--colormap", maps},
      {"--tracer", {"auto", "query", "pipeline"}},
      {"--integration", {"exact", "sampled"}},
      {"--lists", {"two-pass", "drop", "merge"}},
      {"--encoding", {"float", "rgba8"}},
      {"--pixel-ownership", {"interleaved", "ranges"}},
      {"--composite", {"deep", "single"}},
      {"--time", {"all"}},
      {"--body", {"capsule", "lander"}},
  };
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

// Every name of an option as typed: --long and -s.
std::vector<std::string> namesOf(const CLI::Option* o) {
  std::vector<std::string> names;
  for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
  for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  return names;
}

struct CommandWords {
  std::string path;  // "" (the program), "render", "bench render"
  std::vector<std::string> options, subcommands;
};

// Every command path under `cmd` with its options and subcommands; the options that take a value
// go to `valued`.
void collect(const CLI::App* cmd, const std::string& path, std::vector<CommandWords>& out,
             std::set<std::string>& valued) {
  CommandWords words{path, {}, {}};
  for (const CLI::Option* o : cmd->get_options()) {
    if (o->get_group().empty()) continue;  // hidden
    for (const std::string& n : namesOf(o)) {
      words.options.push_back(n);
      if (o->get_expected_max() != 0) valued.insert(n);  // not a flag
    }
  }
  std::vector<const CLI::App*> subs;
  for (const CLI::App* sub : cmd->get_subcommands({}))
    if (!sub->get_group().empty()) {
      words.subcommands.push_back(sub->get_name());
      subs.push_back(sub);
    }
  out.push_back(std::move(words));
  for (const CLI::App* sub : subs)
    collect(sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(), out, valued);
}

std::string bashScript(const CLI::App& app) {
  std::vector<CommandWords> commands;
  std::set<std::string> valued;
  collect(&app, "", commands, valued);
  std::string paths, options, subcommands, values;
  for (const CommandWords& c : commands) {
    if (!c.path.empty()) paths += (paths.empty() ? "\"" : "|\"") + c.path + "\"";
    options += "    \"" + c.path + "\") words=\"" + joined(c.options) + "\" ;;\n";
    subcommands += "    \"" + c.path + "\") words=\"" + joined(c.subcommands) + "\" ;;\n";
  }
  for (const auto& [option, list] : fixedValues())
    if (valued.count(option))
      values += "      " + option + ") COMPREPLY=($(compgen -W \"" + joined(list) +
                "\" -- \"$cur\")) ;;\n";
  return "# bash completion for shellmarch, written by `shellmarch completion bash` from its own\n"
         "# options. Source it, or install it as share/bash-completion/completions/shellmarch.\n"
         "_shellmarch() {\n"
         "  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}\n"
         "  local valued=\" " +
         joined({valued.begin(), valued.end()}) +
         " \"\n"
         "  local path=\"\" w i words=\"\"\n"
         "  COMPREPLY=()\n"
         "  # The command path typed so far (options and their values skipped).\n"
         "  for ((i = 1; i < COMP_CWORD; i++)); do\n"
         "    w=${COMP_WORDS[i]}\n"
         "    if [[ $valued == *\" $w \"* ]]; then ((i++)); continue; fi\n"
         "    case \"${path:+$path }$w\" in\n"
         "      " +
         paths +
         ") path=\"${path:+$path }$w\" ;;\n"
         "    esac\n"
         "  done\n"
         "  if [[ $valued == *\" $prev \"* ]]; then\n"
         "    case \"$prev\" in\n" +
         values +
         "      *) COMPREPLY=($(compgen -f -- \"$cur\")) ;;\n"
         "    esac\n"
         "    return 0\n"
         "  fi\n"
         "  if [[ $cur == -* ]]; then\n"
         "    case \"$path\" in\n" +
         options +
         "    esac\n"
         "    COMPREPLY=($(compgen -W \"$words\" -- \"$cur\"))\n"
         "    return 0\n"
         "  fi\n"
         "  case \"$path\" in\n" +
         subcommands +
         "  esac\n"
         "  COMPREPLY=($(compgen -W \"$words\" -- \"$cur\"))\n"
         "  # A command's operands are files (meshes, images).\n"
         "  [ -n \"$path\" ] && COMPREPLY+=($(compgen -f -- \"$cur\"))\n"
         "  return 0\n"
         "}\n"
         "complete -o filenames -F _shellmarch shellmarch\n";
}

}  // namespace

void registerCompletion(CLI::App& app) {
  auto* cmd = app.add_subcommand("completion", "Print a shell completion script (bash)");
  auto shell = std::make_shared<std::string>();
  cmd->add_option("shell", *shell, "The shell: bash")->required()->check(CLI::IsMember({"bash"}));
  cmd->callback([&app, shell] { std::fputs(bashScript(app).c_str(), stdout); });
}

}  // namespace sm::app
