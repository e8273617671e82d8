#include "cli/command_words.h"

#include <sstream>

namespace sm::app {
namespace {

// Every name of an option as typed: --long and -s.
std::vector<std::string> namesOf(const CLI::Option* o) {
  std::vector<std::string> names;
  for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
  for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  return names;
}

std::vector<std::string> splitWords(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

}  // namespace

std::string joinWords(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

void collectWords(const CLI::App* cmd, const std::string& path, std::vector<CommandWords>& out,
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
    collectWords(sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(), out, valued);
}

std::string encodeWords(const std::vector<CommandWords>& words,
                        const std::set<std::string>& valued) {
  std::string out;
  for (const CommandWords& c : words) {
    std::vector<std::string> mine;
    for (const std::string& o : c.options)
      if (valued.count(o)) mine.push_back(o);
    out += c.path + "\t" + joinWords(c.options) + "\t" + joinWords(c.subcommands) + "\t" +
           joinWords(mine) + "\n";
  }
  return out;
}

std::vector<CommandWords> decodeWords(const std::string& text, std::set<std::string>& valued) {
  std::vector<CommandWords> words;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    for (size_t start = 0;;) {
      const size_t tab = line.find('\t', start);
      fields.push_back(line.substr(start, tab - start));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    if (fields.size() != 4) continue;
    words.push_back({fields[0], splitWords(fields[1]), splitWords(fields[2])});
    for (const std::string& v : splitWords(fields[3])) valued.insert(v);
  }
  return words;
}

}  // namespace sm::app
