#include "pipeline/step_source.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "common/error.h"
#include "common/log.h"
#include "io/mesh_io.h"
#include "prep/prepare.h"

namespace sm::app {
namespace {

mesh::Range finiteRange(const std::vector<float>& values) {
  mesh::Range r;
  for (float v : values)
    if (std::isfinite(v)) r.extend(v);
  return r;
}

}  // namespace

StepSource::StepSource(const std::string& path, const RankShare& share, comm::Communicator& comm)
    : path_(path), share_(share), comm_(comm), numPoints_(share.mesh.numPoints()) {}

bool StepSource::collective(const std::string& field) const {
  if (!share_.stream || !share_.stream->cells) return false;
  const std::vector<std::string>& cells = share_.stream->cellFields;
  return std::find(cells.begin(), cells.end(), field) != cells.end();
}

uint64_t StepSource::numSteps(const std::string& field) const {
  if (share_.stream) {
    for (const io::FieldStepCount& f : share_.stream->fieldSteps)
      if (f.name == field) return f.steps;
    return 0;
  }
  const mesh::Field* f = share_.mesh.findField(field);
  return f ? f->numSteps() : 0;
}

void StepSource::warnNonFinite(const char* what, const std::string& field, uint64_t step,
                               const std::vector<float>& values,
                               std::span<const uint32_t> origins) const {
  if (step == 0) return;  // loading warned about it
  const uint64_t n = mesh::nonFiniteCells(values, origins);
  if (n == 0) return;
  {  // once per step: the range pass and the frame read the same step
    std::lock_guard<std::mutex> lock(warnedMutex_);
    if (!warned_.insert({field, step}).second) return;
  }
  log::warning(path_, ": ", what, " '", field, "' step ", step, " has ", n,
               " non-finite values; they render transparent");
}

std::vector<float> StepSource::readCells(const std::string& field, uint64_t step, unsigned threads,
                                         const io::StopRequested& stop) const {
  const StepStream& s = *share_.stream;
  if (s.cells->numCells() == 0) return {};  // no pieces: reads nothing (but averages, collectively)
  io::ReadOptions o = s.read;
  if (threads) o.threads = threads;
  o.stopRequested = stop;
  // Every cell of the pieces, then this rank's elements among them: a file that changed since it
  // was loaded shows in the count.
  const std::vector<float> all = io::readCellFieldStep(path_, field, step, o);
  if (all.size() != s.fileCellCount)
    throw FileError(path_, "cell data '", field, "' step ", step, " has ", all.size(),
                    " values; the pieces read had ", s.fileCellCount, " cells when loaded");
  std::vector<float> mine(s.fileCells.size());
  for (size_t i = 0; i < mine.size(); ++i) mine[i] = all[s.fileCells[i]];
  warnNonFinite("cell data", field, step, mine, s.fileCells);
  return mine;
}

std::vector<float> StepSource::scalarsFromCells(const prep::PreparedRank& rank,
                                                std::span<const float> cells) const {
  std::vector<float> points = share_.stream->cells->toPoints(cells, comm_);
  if (rank.numVertices() == 0) return {};
  return prep::gatherScalars(rank, points);
}

std::vector<float> StepSource::read(const std::string& field, uint64_t step, unsigned threads,
                                    const io::StopRequested& stop) const {
  const StepStream& s = *share_.stream;
  if (collective(field)) return s.cells->toPoints(readCells(field, step, threads, stop), comm_);
  io::ReadOptions o = s.read;
  if (threads) o.threads = threads;
  o.stopRequested = stop;
  std::vector<float> v = io::readFieldStep(path_, field, step, o, s.filePoints);
  warnNonFinite("field", field, step, v);
  if (v.size() != numPoints_)  // the file changed since it was loaded
    throw FileError(path_, "field '", field, "' step ", step, " has ", v.size(), " values for ",
                    numPoints_, " points");
  return v;
}

mesh::Range StepSource::range(const std::string& field, uint64_t step) const {
  if (collective(field)) {
    // Step 0 was averaged at load and is in the mesh (on the ranks with points); a later step is
    // averaged now, by every rank, with or without points.
    if (step > 0) return finiteRange(read(field, step));
    return numPoints_ ? mesh::fieldRange(*share_.mesh.findField(field), 0) : mesh::Range{};
  }
  if (numPoints_ == 0 || step >= numSteps(field)) return {};
  if (!share_.stream) return mesh::fieldRange(*share_.mesh.findField(field), step);
  return finiteRange(read(field, step));
}

std::vector<float> StepSource::scalars(const prep::PreparedRank& rank, const std::string& field,
                                       uint64_t step, unsigned threads,
                                       const io::StopRequested& stop) const {
  if (collective(field)) return scalarsFromCells(rank, readCells(field, step, threads, stop));
  if (rank.numVertices() == 0) return {};
  const uint64_t n = numSteps(field);
  if (n == 0) {
    std::string names;
    if (share_.stream)
      for (const auto& f : share_.stream->fieldSteps) names += (names.empty() ? "" : ", ") + f.name;
    else
      for (const auto& f : share_.mesh.fields) names += (names.empty() ? "" : ", ") + f.name;
    throw Error("--field: ", path_, " has no point field '", field,
                "' (it has: ", names.empty() ? std::string("none") : names, ")",
                mesh::cellArrayHint(share_.mesh.cellArrays, field));
  }
  if (step >= n)
    throw Error("--time: field '", field, "' has ", n, " time steps (0 .. ", n - 1, "), not step ",
                step);
  if (!share_.stream) return prep::gatherScalars(rank, share_.mesh.findField(field)->steps[step]);
  return prep::gatherScalars(rank, read(field, step, threads, stop));
}

}  // namespace sm::app
