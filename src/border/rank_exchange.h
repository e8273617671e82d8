// What the border exchange needs of the ranks it runs on: their number and one all-to-all of
// doubles. The application's Collectives and the in-situ library's Group both provide it, over
// the compositor's Communicator (MPI under mpirun, threads in tests) or one process alone.
#pragma once

#include <vector>

namespace sm::comp {
class Communicator;
}

namespace sm::border {

class RankExchange {
 public:
  virtual ~RankExchange() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Collective. Every rank sends toRank[d] to rank d (toRank has size() entries, of any lengths)
  // and gets back, at [s], what rank s sent it.
  virtual std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& toRank) = 0;
};

// RankExchange::exchange over a Communicator: the lengths in one alltoallv, the values in another.
std::vector<std::vector<double>> exchangeThrough(comp::Communicator& comm,
                                                 const std::vector<std::vector<double>>& toRank);

}  // namespace sm::border
