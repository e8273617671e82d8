// Typed collectives over any Communicator: what the application, the border exchange and the
// in-situ library reduce and share across ranks. Free functions, so that every Communicator (MPI,
// in-process threads, one rank alone) offers them without implementing them again. All are
// collective: every rank of the group calls them in the same order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "comm/communicator.h"

namespace sm::comm {

// Exact and identical on every rank. The double reductions map values to order-preserving
// integers, so one integer allreduce gives the exact extreme (NaN aside).
double minOf(Communicator& comm, double v);
double maxOf(Communicator& comm, double v);
uint64_t maxOf(Communicator& comm, uint64_t v);
// Summed in rank order on every rank, so every rank gets the same bits.
double sumOf(Communicator& comm, double v);
uint64_t sumOf(Communicator& comm, uint64_t v);
// Whether every rank passed the same value.
bool allSame(Communicator& comm, uint64_t v);
// Every rank's value, in rank order, on every rank.
std::vector<double> allValues(Communicator& comm, double v);

// Every rank sends toRank[d] to rank d (toRank has size() entries, of any lengths) and gets back,
// at [s], what rank s sent it: the lengths in one alltoallv, the values in another.
std::vector<std::vector<double>> exchangeValues(Communicator& comm,
                                                const std::vector<std::vector<double>>& toRank);

// Rank 0's `text` on every rank (the others' `text` is ignored).
std::string broadcastString(Communicator& comm, std::string text);
// Rank 0's `names` on every rank. Names must not hold a newline (field and array names do not:
// VTK's XML attributes and legacy tokens cannot).
std::vector<std::string> broadcastNames(Communicator& comm, std::vector<std::string> names);

// `comm` when there are other ranks to exchange with, nullptr on one rank: the compositor skips
// its exchange entirely then.
inline Communicator* withPeers(Communicator& comm) {
  return comm.size() > 1 ? &comm : nullptr;
}

}  // namespace sm::comm
