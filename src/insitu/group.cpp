#include "group.h"

#include <bit>
#include <numeric>
#include <string>
#include <vector>

#include "common/error.h"
#include "shellmarch/insitu.h"

namespace sm::insitu {
namespace {

// Order-preserving map of doubles to unsigned integers (NaN aside): the integer maximum of the
// mapped values is the mapped maximum, so one uint64 allreduce gives an exact double maximum.
uint64_t orderedBits(double v) {
  uint64_t b = std::bit_cast<uint64_t>(v);
  return (b >> 63) ? ~b : b | (uint64_t(1) << 63);
}
double fromOrderedBits(uint64_t b) {
  return std::bit_cast<double>((b >> 63) ? b & ~(uint64_t(1) << 63) : ~b);
}

}  // namespace

Group::Group(MPI_Comm comm) : comm_(std::make_unique<comp::MpiCommunicator>(comm)) {}

double Group::max(double v) {
  if (!comm_) return v;
  return fromOrderedBits(comm_->allreduceMax(orderedBits(v)));
}

double Group::min(double v) {
  return -max(-v);
}

double Group::sum(double v) {
  if (!comm_) return v;
  const int n = size();
  std::vector<double> all(n);
  std::vector<uint64_t> bytes(n, sizeof(double)), offsets(n);
  for (int r = 0; r < n; ++r) offsets[r] = uint64_t(r) * sizeof(double);
  comm_->gatherv(&v, sizeof v, all.data(), bytes, offsets, 0);
  comm_->broadcast(all.data(), all.size() * sizeof(double), 0);
  return std::accumulate(all.begin(), all.end(), 0.0);
}

uint64_t Group::sum(uint64_t v) {
  return comm_ ? comm_->allreduceSum(v) : v;
}

bool Group::same(uint64_t v) {
  if (!comm_) return true;
  return comm_->allreduceMax(v) == ~comm_->allreduceMax(~v);
}

std::vector<std::vector<double>> Group::exchange(const std::vector<std::vector<double>>& toRank) {
  return comm_ ? border::exchangeThrough(*comm_, toRank) : toRank;
}

void Group::agree(const std::function<void()>& local) {
  std::string message;
  bool failed = false;
  try {
    local();
  } catch (const std::exception& e) {
    message = e.what();
    failed = true;
  }
  if (!comm_) {
    if (failed) throw shellmarch::insitu::Error(message);
    return;
  }
  // The lowest failed rank speaks for all: size - rank is largest for it.
  const int n = size();
  const uint64_t key = comm_->allreduceMax(failed ? uint64_t(n - rank()) : 0);
  if (key == 0) return;
  const int first = n - int(key);
  uint64_t length = rank() == first ? message.size() : 0;
  comm_->broadcast(&length, sizeof length, first);
  std::string text(length, '\0');
  if (rank() == first) text = message;
  comm_->broadcast(text.data(), length, first);
  if (n == 1) throw shellmarch::insitu::Error(text);
  std::string what = concat("rank ", first, ": ", text);
  if (failed && rank() != first)
    what += concat(" (this rank, ", rank(), ", also failed: ", message, ")");
  throw shellmarch::insitu::Error(what);
}

void Group::runOrAbort(const std::function<void()>& fn) {
  if (comm_ && size() > 1)
    comp::runOrAbort(*comm_, fn);
  else
    fn();
}

}  // namespace sm::insitu
