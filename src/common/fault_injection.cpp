#include "common/fault_injection.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include "common/error.h"

namespace sm::fault {
namespace {

struct Spec {
  std::string at, action, match;
  std::optional<int> rank;
  uint64_t frame = 0;
};

bool number(const std::string& text, uint64_t& out) {
  char* end = nullptr;
  out = std::strtoull(text.c_str(), &end, 10);
  return !text.empty() && text[0] != '-' && !*end;
}

std::optional<Spec> parse(const char* text) {
  Spec s;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const size_t eq = item.find('=');
    const std::string key = item.substr(0, eq), value = eq == item.npos ? "" : item.substr(eq + 1);
    uint64_t n = 0;
    if (key == "at" &&
        (value == "frame" || value == "write" || value == "read-ahead" || value == "range-pass"))
      s.at = value;
    else if (key == "action" && (value == "kill" || value == "throw" || value == "stall" ||
                                 value == "close" || value == "next-field"))
      s.action = value;
    else if (key == "match")
      s.match = value;
    else if (key == "rank" && number(value, n))
      s.rank = int(n);
    else if (key == "frame" && number(value, n))
      s.frame = n;
    else
      throw Error(
          "SHELLMARCH_FAULT: cannot use '", item,
          "' (at=frame|write|read-ahead|range-pass, action=kill|throw|stall|close|next-field, "
          "rank=R, "
          "frame=N, match=TEXT)");
  }
  if (s.at.empty() || s.action.empty()) throw Error("SHELLMARCH_FAULT: needs at= and action=");
  if ((s.action == "stall") != (s.at == "read-ahead"))
    throw Error("SHELLMARCH_FAULT: action=stall goes with at=read-ahead, and only it");
  if ((s.action == "close" || s.action == "next-field") != (s.at == "range-pass"))
    throw Error(
        "SHELLMARCH_FAULT: action=close or next-field goes with at=range-pass, and only it");
  return s;
}

const std::optional<Spec>& spec() {
  static const std::optional<Spec> s = [] {
    const char* text = std::getenv("SHELLMARCH_FAULT");
    return text && *text ? parse(text) : std::nullopt;
  }();
  return s;
}

int processRank() {
  for (const char* var : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* v = std::getenv(var)) return std::atoi(v);
  return 0;
}

void announce(const Spec& s, const std::string& where) {
  // The wall-clock time lets a test tell how long the other ranks took to end after it.
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  std::fprintf(stderr, "shellmarch: fault injection: %s on rank %d %s at %.3f s (epoch)\n",
               s.action.c_str(), processRank(), where.c_str(), now);
  std::fflush(stderr);
}

void fire(const Spec& s, const std::string& where) {
  if (s.rank && *s.rank != processRank()) return;
  announce(s, where);
  if (s.action == "kill") std::raise(SIGKILL);
  throw Error("injected fault on rank ", processRank(), " ", where);
}

}  // namespace

void atFrame(uint64_t frame) {
  const auto& s = spec();
  if (s && s->at == "frame" && s->frame == frame) fire(*s, concat("in frame ", frame));
}

void atWrite(const std::string& path) {
  const auto& s = spec();
  if (s && s->at == "write" && path.find(s->match) != std::string::npos)
    fire(*s, concat("while writing ", path));
}

void atReadAhead(const std::function<bool()>& stopped) {
  const auto& s = spec();
  if (!s || s->at != "read-ahead" || (s->rank && *s->rank != processRank())) return;
  announce(*s, "in a read ahead");
  // A minute, not forever: a reader that never stops it shows as a slow test, not a hung one.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!(stopped && stopped()) && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

RangePassInput atRangePass() {
  const auto& s = spec();
  if (!s || s->at != "range-pass" || (s->rank && *s->rank != processRank()))
    return RangePassInput::None;
  static bool announced = false;
  const bool first = !std::exchange(announced, true);
  if (first) announce(*s, "in a range pass");
  if (s->action == "close") return RangePassInput::Close;
  // One key press, as a user's: pressed at every pass, it would skip every field for ever.
  return first ? RangePassInput::NextField : RangePassInput::None;
}

}  // namespace sm::fault
