#include "common/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>

#include "common/error.h"

namespace sm::log {
namespace {
std::atomic<Level> g_level{Level::Warning};
std::mutex g_mutex;
std::string g_prefix;

void emit(const char* kind, const std::string& line) {
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "%sshellmarch: %s%s\n", g_prefix.c_str(), kind, printableLine(line).c_str());
}
}  // namespace

void setLevel(Level l) {
  g_level = l;
}
Level level() {
  return g_level;
}
void setPrefix(const std::string& prefix) {
  std::lock_guard lock(g_mutex);
  g_prefix = prefix;
}
bool firstTime(const std::string& key) {
  static std::mutex mutex;
  static std::set<std::string> seen;
  std::lock_guard lock(mutex);
  return seen.insert(key).second;
}
void warningLine(const std::string& line) {
  emit("warning: ", line);
}
void infoLine(const std::string& line) {
  emit("", line);
}
void debugLine(const std::string& line) {
  emit("debug: ", line);
}

}  // namespace sm::log
