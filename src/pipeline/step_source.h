// Where a rank's field steps come from while it renders a sequence: the file, one step at a time
// (a streamed share, see RankShare::stream), or the mesh in memory. Steps are handed out in the
// prepared vertex order, ready for the GPU. A streamed cell field is averaged onto the points with
// every rank's help: its steps are collective (collective(field)).
#pragma once

#include <cstdint>
#include <mutex>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "io_core/read_stop.h"
#include "pipeline/rank_share.h"
#include "prep/prepared_rank.h"

namespace sm::app {

class StepSource {
 public:
  // Call before preparation takes the points out of share.mesh; `share` and `comm` must outlive
  // the source.
  StepSource(const std::string& path, const RankShare& share, comm::Communicator& comm);

  // Steps of `field` on this rank (0 when its clusters lack the field).
  uint64_t numSteps(const std::string& field) const;
  // Whether this rank has points (its share's, counted before preparation took them out).
  bool hasPoints() const { return numPoints_ > 0; }
  // True when range() and scalars() of `field` are collective (a streamed cell field): every rank
  // calls them for the same steps in the same order, on the thread that makes MPI calls. The file
  // reads can run ahead on another thread: scalarsFromCells(rank, readCells(field, step)) is
  // scalars().
  bool collective(const std::string& field) const;

  // Range of one step over this rank's points (empty when it lacks the field or the step).
  mesh::Range range(const std::string& field, uint64_t step) const;
  // One step in `rank`'s vertex order (empty for a rank without vertices); throws naming --field
  // when the field is missing, as app::fieldStep does. Reads files only, so it may run on a
  // thread of its own while frames render. `threads` decompress and convert (0: the read
  // options' count); `stop` ends a read no longer wanted with io::ReadStopped.
  std::vector<float> scalars(const prep::PreparedRank& rank, const std::string& field,
                             uint64_t step, unsigned threads = 0,
                             const io::StopRequested& stop = {}) const;

  // A streamed cell field's step, one value per element of this rank (file reads only: any
  // thread), and the collective rest of scalars().
  std::vector<float> readCells(const std::string& field, uint64_t step, unsigned threads = 0,
                               const io::StopRequested& stop = {}) const;
  std::vector<float> scalarsFromCells(const prep::PreparedRank& rank,
                                      std::span<const float> cells) const;

 private:
  std::vector<float> read(const std::string& field, uint64_t step, unsigned threads = 0,
                          const io::StopRequested& stop = {}) const;
  // Loading warned about step 0's non-finite values; streamed steps warn here, once each.
  // `origins`: cell data's, so that a polyhedron's tetrahedra count once (mesh::nonFiniteCells).
  void warnNonFinite(const char* what, const std::string& field, uint64_t step,
                     const std::vector<float>& values,
                     std::span<const uint32_t> origins = {}) const;

  std::string path_;
  const RankShare& share_;
  comm::Communicator& comm_;
  mutable std::mutex warnedMutex_;  // the prefetch thread reads steps too
  mutable std::set<std::pair<std::string, uint64_t>> warned_;
  uint64_t numPoints_;
};

}  // namespace sm::app
