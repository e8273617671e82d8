#include "pipeline/piece_agreement.h"

#include <cstdint>
#include <limits>
#include <vector>

#include "common/error.h"
#include "common/hash.h"

namespace sm::app {
namespace {

std::vector<double> asDoubles(const std::string& s) {
  return std::vector<double>(s.begin(), s.end());
}

std::string asText(const std::vector<double>& v) {
  std::string s;
  for (double c : v) s += char(c);
  return s;
}

}  // namespace

void checkPiecesAgree(const std::string& source, const std::string& what,
                      const std::string& description, bool holds, const std::string& pieces,
                      comm::Communicator& comm) {
  // 52 bits of the description's hash: exact in a double, so that ranks compare it by min and max.
  const double signature =
      double(hashBytes(description.data(), description.size()) & ((uint64_t(1) << 52) - 1));
  const double lo = comm::minOf(comm, holds ? signature : std::numeric_limits<double>::infinity());
  const double hi = comm::maxOf(comm, holds ? signature : -1.0);
  if (hi < 0 || lo == hi) return;
  // On a mismatch, rank 0 learns what each holder holds (who it is, a NUL, what it holds) and
  // every rank throws its words.
  const std::string mine =
      holds ? concat("rank ", comm.rank(), " (", pieces, ")", '\0', description) : std::string();
  std::vector<std::vector<double>> toRank(comm.size());
  toRank[0] = asDoubles(mine);
  const std::vector<std::vector<double>> all = comm::exchangeValues(comm, toRank);
  std::string message;
  if (comm.rank() == 0) {
    std::string first, firstHolds, other;
    for (const auto& d : all) {
      const std::string text = asText(d);
      if (text.empty()) continue;
      const size_t cut = text.find('\0');
      const std::string who = text.substr(0, cut), held = text.substr(cut + 1);
      if (first.empty()) {
        first = concat(who, " has ", held);
        firstHolds = held;
      } else if (other.empty() && held != firstHolds) {
        other = concat(who, " has ", held);
      }
    }
    message = concat(source, ": the pieces do not hold the same ", what, ": ", first, "; ", other);
  }
  throw Error(comm::broadcastString(comm, message));
}

}  // namespace sm::app
