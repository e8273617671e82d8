#include "pipeline/cell_data_share.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "border/border_exchange.h"
#include "common/error.h"
#include "pipeline/piece_agreement.h"

namespace sm::app {
namespace {

std::string describeCellFields(const mesh::UnstructuredMesh& m) {
  std::string text;
  for (const mesh::CellField& f : m.cellFields)
    text += concat(text.empty() ? "" : ", ", "'", f.name, "' with ", f.steps.size(),
                   f.steps.size() == 1 ? " step" : " steps");
  return text.empty() ? "no cell data asked for" : text;
}

uint64_t cellFieldSteps(const mesh::UnstructuredMesh& m) {
  uint64_t steps = 0;
  for (const mesh::CellField& f : m.cellFields) steps += f.steps.size();
  return steps;
}

// Every rank holding pieces must hold the same cell fields, or the rounds of the exchange would
// not pair up.
void checkSameCellFields(const mesh::UnstructuredMesh& m, bool holds, const std::string& pieces,
                         comm::Communicator& comm) {
  checkPiecesAgree(m.source, "cell data", describeCellFields(m), holds, pieces, comm);
}

}  // namespace

void cellDataToPointsOverRanks(mesh::UnstructuredMesh& m, bool holdsPieces,
                               const std::string& pieces, comm::Communicator& comm) {
  if (comm.size() == 1) {  // nothing to exchange: the rank's pieces are the whole mesh
    mesh::cellFieldsToPoints(m);
    return;
  }
  checkSameCellFields(m, holdsPieces, pieces, comm);
  const uint64_t columns = 1 + comm::maxOf(comm, cellFieldSteps(m));
  border::BorderExchange border(m, comm);
  // Column 0 is the counts, then every step of every field in the order of m.cellFields (a rank
  // without pieces has none of its own). They go in rounds of at most kBatch columns: few rounds,
  // each an exchange among all ranks, and memory bounded whatever the number of steps.
  constexpr uint64_t kBatch = 16;
  std::vector<std::pair<size_t, size_t>> stepOf{{0, 0}};  // column -> (field, step)
  for (size_t f = 0; f < m.cellFields.size(); ++f)
    for (size_t s = 0; s < m.cellFields[f].steps.size(); ++s) stepOf.push_back({f, s});
  std::vector<mesh::Field> fields;
  for (const mesh::CellField& cf : m.cellFields) fields.push_back({cf.name, {}});
  std::vector<double> uses;
  for (uint64_t first = 0; first < columns; first += kBatch) {
    const uint64_t last = std::min(columns, first + kBatch);
    std::vector<std::vector<double>> batch;
    for (uint64_t c = first; c < last; ++c) {
      if (c == 0)
        batch.push_back(mesh::cellUsesAtPoints(m));
      else if (c < stepOf.size())
        batch.push_back(mesh::cellSumsAtPoints(m, m.cellFields[stepOf[c].first], stepOf[c].second));
      else
        batch.emplace_back(m.numPoints(), 0.0);
    }
    border.addOtherRanks(batch, comm);
    for (uint64_t c = first; c < last; ++c) {
      std::vector<double>& v = batch[size_t(c - first)];
      if (c == 0)
        uses = std::move(v);
      else if (c < stepOf.size())
        fields[stepOf[c].first].steps.push_back(mesh::meansAtPoints(v, uses));
    }
  }
  for (mesh::Field& f : fields) m.fields.push_back(std::move(f));
  m.cellFields.clear();
}

}  // namespace sm::app
