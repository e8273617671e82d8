// The few collective operations the application needs (global bounds, ranges, sums), behind an
// interface so that the one-process run needs no MPI. The MPI implementation wraps the
// compositor's MPI communicator.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "border/rank_exchange.h"

namespace sm::comp {
class Communicator;
}

namespace sm::app {

// rank(), size() and exchange() (cell data's border sums) come from RankExchange.
class Collectives : public border::RankExchange {
 public:
  virtual double min(double v) = 0;
  virtual double max(double v) = 0;
  virtual double sum(double v) = 0;
  virtual uint64_t sum(uint64_t v) = 0;
  // Rank 0's `bytes` at `data` to every rank (the viewer's per-frame state).
  virtual void broadcast(void* data, uint64_t bytes) = 0;
  // As broadcast, sleeping instead of spinning while rank 0 keeps the others waiting
  // (comp::Communicator::broadcastPatiently); every rank must call this one.
  virtual void broadcastPatiently(void* data, uint64_t bytes) = 0;
  // The compositor's communicator (nullptr on one rank: no exchange).
  virtual comp::Communicator* communicator() = 0;
};

// Rank 0's `text` on every rank (collective; the others' `text` is ignored).
inline std::string broadcastString(Collectives& coll, std::string text) {
  uint64_t bytes = text.size();
  coll.broadcast(&bytes, sizeof bytes);
  text.resize(bytes);
  coll.broadcast(text.data(), bytes);
  return text;
}

// Rank 0's `names` on every rank (collective). Names must not hold a newline (field and array
// names do not: VTK's XML attributes and legacy tokens cannot).
inline std::vector<std::string> broadcastNames(Collectives& coll, std::vector<std::string> names) {
  std::string joined;
  for (const std::string& n : names) joined += n + '\n';
  joined = broadcastString(coll, std::move(joined));
  names.clear();
  for (size_t start = 0, end; (end = joined.find('\n', start)) != std::string::npos;
       start = end + 1)
    names.push_back(joined.substr(start, end - start));
  return names;
}

class SingleProcess final : public Collectives {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double min(double v) override { return v; }
  double max(double v) override { return v; }
  double sum(double v) override { return v; }
  uint64_t sum(uint64_t v) override { return v; }
  void broadcast(void*, uint64_t) override {}
  void broadcastPatiently(void*, uint64_t) override {}
  std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& toRank) override {
    return toRank;
  }
  comp::Communicator* communicator() override { return nullptr; }
};

}  // namespace sm::app
