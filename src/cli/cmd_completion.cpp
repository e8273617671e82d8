// `shellmarch completion bash`: a bash completion script written from the command line's own
// definition (commands, options, which options take a value and which values they accept), so
// that it cannot fall behind the options. The build runs it to install
// share/bash-completion/completions/shellmarch (src/app/CMakeLists.txt).
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cli/command_words.h"
#include "cli/commands.h"
#include "cli/program.h"
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

// shellmarch-bench's command words under "bench" (its --completion-words lines).
void addBenchWords(std::vector<CommandWords>& commands, std::set<std::string>& valued) {
  const std::string cmd = "'" + siblingExecutable("shellmarch-bench") + "' --completion-words";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw Error("completion: cannot run ", cmd);
  std::string text;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
  if (pclose(pipe) != 0) throw Error("completion: ", cmd, " failed");
  std::vector<CommandWords> bench = decodeWords(text, valued);
  for (CommandWords& c : bench) {
    c.path = c.path.empty() ? "bench" : "bench " + c.path;
    auto same = std::find_if(commands.begin(), commands.end(),
                             [&](const CommandWords& o) { return o.path == c.path; });
    if (same != commands.end())
      *same = std::move(c);
    else
      commands.push_back(std::move(c));
  }
}

std::string bashScript(const CLI::App& app) {
  std::vector<CommandWords> commands;
  std::set<std::string> valued;
  collectWords(&app, "", commands, valued);
  // `bench` runs another executable: its commands are that one's.
  if (app.get_subcommands([](const CLI::App* s) { return s->get_name() == "bench"; }).size() == 1)
    addBenchWords(commands, valued);
  std::string paths, options, subcommands, values;
  for (const CommandWords& c : commands) {
    if (!c.path.empty()) paths += (paths.empty() ? "\"" : "|\"") + c.path + "\"";
    options += "    \"" + c.path + "\") words=\"" + joinWords(c.options) + "\" ;;\n";
    subcommands += "    \"" + c.path + "\") words=\"" + joinWords(c.subcommands) + "\" ;;\n";
  }
  for (const auto& [option, list] : fixedValues())
    if (valued.count(option))
      values += "      " + option + ") COMPREPLY=($(compgen -W \"" + joinWords(list) +
                "\" -- \"$cur\")) ;;\n";
  return "# bash completion for shellmarch, written by `shellmarch completion bash` from its own\n"
         "# options. Source it, or install it as share/bash-completion/completions/shellmarch.\n"
         "_shellmarch() {\n"
         "  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}\n"
         "  local valued=\" " +
         joinWords({valued.begin(), valued.end()}) +
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
