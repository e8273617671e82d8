#include "pipeline/time_selection.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "common/error.h"

namespace sm::app {
namespace {

std::string stepsWord(uint64_t n) {
  return concat(n, n == 1 ? " time step" : " time steps");
}

// A whole number >= 0 (all of `text`), or nothing.
bool parseIndex(const std::string& text, uint64_t& out) {
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (*end || errno == ERANGE) return false;
  out = v;
  return true;
}

void checkExists(uint64_t step, uint64_t available) {
  if (step >= available)
    throw Error("--time: step ", step, " does not exist (the data has ", stepsWord(available),
                ": 0 .. ", available - 1, ")");
}

std::vector<uint64_t> stepRange(const std::string& text, uint64_t available) {
  std::vector<std::string> parts{""};
  for (char c : text) {
    if (c == ':')
      parts.emplace_back();
    else
      parts.back() += c;
  }
  uint64_t first = 0, last = 0, stride = 1;
  if (parts.size() > 3 || !parseIndex(parts[0], first) || !parseIndex(parts[1], last) ||
      (parts.size() == 3 && (!parseIndex(parts[2], stride) || stride == 0)))
    throw Error("--time: '", text, "' is not a range FIRST:LAST or FIRST:LAST:STRIDE of steps");
  if (first > last) throw Error("--time: '", text, "' starts after it ends");
  checkExists(last, available);
  std::vector<uint64_t> steps;
  for (uint64_t s = first; s <= last; s += stride) {
    steps.push_back(s);
    if (last - s < stride) break;
  }
  return steps;
}

// The nearest step's index on a rank with the times; kNoTimes on one without; kOutside when the
// value lies beyond them.
constexpr double kNoTimes = -3, kOutside = -2;

double nearestStep(double value, const std::vector<double>& times) {
  if (times.empty()) return kNoTimes;
  if (!(value >= times.front() && value <= times.back())) return kOutside;
  size_t best = 0;
  for (size_t k = 1; k < times.size(); ++k)
    if (std::fabs(times[k] - value) < std::fabs(times[best] - value)) best = k;
  return double(best);
}

uint64_t stepAtTime(const std::string& text, uint64_t available, const std::vector<double>& times,
                    comm::Communicator& comm) {
  const std::string number = text.substr(2);
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (number.empty() || std::isspace(static_cast<unsigned char>(number[0])) || *end ||
      !std::isfinite(value))
    throw Error("--time: '", text, "' is not t= followed by a time value");
  // Time values that do not name every step cannot say which step a time is.
  const bool usable = times.size() == available;
  const double found = comm::maxOf(comm, usable          ? nearestStep(value, times)
                                         : times.empty() ? kNoTimes
                                                         : -1);
  const double inf = std::numeric_limits<double>::infinity();
  if (found == -1 || found == kNoTimes)
    throw Error("--time: '", text, "': the data has no time values",
                found == -1 ? " for each of its steps" : "", "; give a step index (0 .. ",
                available - 1, ")");
  if (found == kOutside) {
    const double lo = comm::minOf(comm, times.empty() ? inf : times.front());
    const double hi = comm::maxOf(comm, times.empty() ? -inf : times.back());
    throw Error("--time: ", value, " is outside the data's times (", lo, " .. ", hi, ")");
  }
  return uint64_t(found);
}

}  // namespace

std::vector<uint64_t> selectSteps(const std::string& text, uint64_t available,
                                  const std::vector<double>& times, comm::Communicator& comm) {
  available = std::max<uint64_t>(available, 1);
  if (text == "all") {
    std::vector<uint64_t> all(available);
    for (uint64_t i = 0; i < all.size(); ++i) all[i] = i;
    return all;
  }
  if (text.rfind("t=", 0) == 0) return {stepAtTime(text, available, times, comm)};
  if (text.find(':') != std::string::npos) return stepRange(text, available);
  uint64_t step = 0;
  if (!parseIndex(text, step))
    throw Error("--time: '", text, "' is not a step index, FIRST:LAST[:STRIDE], t=TIME or 'all'");
  checkExists(step, available);
  return {step};
}

bool selectsSequence(const std::string& text) {
  return text == "all" || text.find(':') != std::string::npos;
}

}  // namespace sm::app
