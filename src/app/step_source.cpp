#include "app/step_source.h"

#include <cmath>

#include "common/error.h"
#include "io/mesh_io.h"
#include "prep/prepare.h"

namespace sm::app {

StepSource::StepSource(const std::string& path, const RankShare& share)
    : path_(path), share_(share), numPoints_(share.mesh.numPoints()) {}

uint64_t StepSource::numSteps(const std::string& field) const {
  if (share_.stream) {
    for (const io::FieldStepCount& f : share_.stream->fieldSteps)
      if (f.name == field) return f.steps;
    return 0;
  }
  const mesh::Field* f = share_.mesh.findField(field);
  return f ? f->numSteps() : 0;
}

std::vector<float> StepSource::read(const std::string& field, uint64_t step,
                                    unsigned threads) const {
  const StepStream& s = *share_.stream;
  io::ReadOptions o = s.read;
  if (threads) o.threads = threads;
  std::vector<float> v = io::readFieldStep(path_, field, step, o, s.filePoints);
  if (v.size() != numPoints_)  // the file changed since it was loaded
    throw FileError(path_, "field '", field, "' step ", step, " has ", v.size(), " values for ",
                    numPoints_, " points");
  return v;
}

mesh::Range StepSource::range(const std::string& field, uint64_t step) const {
  if (numPoints_ == 0 || step >= numSteps(field)) return {};
  if (!share_.stream) return mesh::fieldRange(*share_.mesh.findField(field), step);
  mesh::Range r;
  for (float v : read(field, step))
    if (std::isfinite(v)) r.extend(v);
  return r;
}

std::vector<float> StepSource::scalars(const prep::PreparedRank& rank, const std::string& field,
                                       uint64_t step, unsigned threads) const {
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
  return prep::gatherScalars(rank, read(field, step, threads));
}

}  // namespace sm::app
