#include "pipeline/rank_share.h"

#include <algorithm>
#include <limits>
#include <tuple>

#include "common/check.h"
#include "common/error.h"
#include "common/log.h"
#include "partition/partition.h"
#include "pipeline/cell_data_share.h"
#include "pipeline/piece_agreement.h"

namespace sm::app {
namespace {

mesh::Bounds globalBounds(const mesh::Bounds& local, comm::Communicator& comm) {
  const double inf = std::numeric_limits<double>::infinity();
  mesh::Bounds b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = comm::minOf(comm, local.empty ? inf : local.lo[a]);
    b.hi[a] = comm::maxOf(comm, local.empty ? -inf : local.hi[a]);
  }
  b.empty = !(b.lo.x <= b.hi.x);
  if (b.empty) b = mesh::Bounds{};
  return b;
}

std::vector<int> clustersOfRank(const std::vector<int>& clusterToRank, int rank) {
  std::vector<int> mine;
  for (size_t c = 0; c < clusterToRank.size(); ++c)
    if (clusterToRank[c] == rank) mine.push_back(int(c));
  return mine;
}

// Reading for a stream: one step per field in memory, the step counts from the headers.
io::ReadOptions streamRead(const std::string& path, const ShareOptions& o, StepStream& stream) {
  stream.read = o.read;
  stream.read.step.reset();
  io::ReadOptions read = o.read;
  read.step = 0;
  stream.fieldSteps = io::listFieldSteps(path, stream.read);
  return read;
}

// The files of a rank's pieces, for messages.
std::string pieceNames(const std::string& path, const RankShare& s) {
  if (s.clusters.empty()) return {};
  const std::vector<std::string> files = io::pieceFiles(path);
  std::string names;
  for (int c : s.clusters) names += (names.empty() ? "" : ", ") + files.at(size_t(c));
  return names;
}

// The fields a rank's pieces hold, from their headers: a stream's listing, or the listing of a
// rank that loaded every step (empty for a rank without pieces).
std::vector<io::FieldStepCount> listedFields(const std::string& path, const io::ReadOptions& read,
                                             const RankShare& s) {
  if (s.stream) return s.stream->fieldSteps;
  if (s.clusters.empty()) return {};
  io::ReadOptions mine = read;
  mine.pieces = s.clusters;
  return io::listFieldSteps(path, mine);
}

// What a rank's pieces hold as fields, in words, by name (cell data said so, and a vector read as
// its magnitude): the same on every rank for pieces that agree, whatever the order the pieces
// list them in. Components count because a scalar in one rank's pieces and a vector's magnitude in
// another's render as one field with no error, when the index declares neither.
std::string describeFields(const RankShare& s, const std::vector<io::FieldStepCount>& listed) {
  auto componentsOf = [&](const std::string& name) {
    for (const io::FieldStepCount& f : listed)
      if (f.name == name) return f.components;
    return 0u;
  };
  std::vector<std::tuple<std::string, uint64_t, bool, uint32_t>> fields;
  if (s.stream)
    for (const io::FieldStepCount& f : listed)
      fields.emplace_back(f.name, f.steps, f.cellData, f.components);
  else
    for (const mesh::Field& f : s.mesh.fields)
      fields.emplace_back(f.name, f.numSteps(), false, componentsOf(f.name));
  std::sort(fields.begin(), fields.end());
  std::string text;
  for (const auto& [name, steps, cells, components] : fields)
    text += concat(text.empty() ? "" : ", ", "'", name, "'", cells ? " (cell data)" : "",
                   components > 1 ? concat(" (the magnitude of ", components, " components)") : "",
                   " with ", steps, steps == 1 ? " step" : " steps");
  return text.empty() ? "no fields" : text;
}

// The fields asked for that are cell data, in the order asked, the same on every rank: a rank
// without pieces holds none and asks the others (one collective per field asked for).
std::vector<std::string> agreedCellFields(const mesh::UnstructuredMesh& m,
                                          const std::vector<std::string>& asked,
                                          comm::Communicator& comm) {
  std::vector<std::string> names;
  for (const std::string& name : asked) {
    const bool mine = std::any_of(m.cellFields.begin(), m.cellFields.end(),
                                  [&](const mesh::CellField& f) { return f.name == name; });
    if (comm::maxOf(comm, mine ? 1.0 : 0.0) > 0.0) names.push_back(name);
  }
  return names;
}

// Flattens step 0 of each streamed cell field (type after type, as CellAverager takes values) and
// averages it onto the points over all ranks (collective: a rank without pieces takes part with no
// cells). Later steps are averaged by the same averager, whose first call found the shared points.
void averageFirstCellSteps(RankShare& s, const std::vector<std::string>& asked,
                           comm::Communicator& comm) {
  mesh::UnstructuredMesh& m = s.mesh;
  // The averager counts a polyhedron's tetrahedra once at a point by their origins, which the
  // stream took over: lent back for its construction.
  m.cellOrigin = s.stream->fileCells;
  s.stream->cells = std::make_shared<border::CellAverager>(m);
  std::vector<uint32_t>().swap(m.cellOrigin);
  SM_CHECK_EQ(s.stream->fileCells.size(), m.numCells());  // every element's origin kept
  s.stream->cellFields = agreedCellFields(m, asked, comm);
  for (const std::string& field : s.stream->cellFields) {
    std::vector<float> values;
    values.reserve(m.numCells());
    for (const mesh::CellField& f : m.cellFields)
      if (f.name == field && !f.steps.empty())
        for (const std::vector<float>& perType : f.steps[0])
          values.insert(values.end(), perType.begin(), perType.end());
    // Ranks agreed on what their pieces hold (readPieces); one rank's pieces agree by the weld.
    if (values.size() != m.numCells())
      throw FileError(m.source, "holds no cell data '", field, "' for its ", m.numCells(),
                      " cells");
    std::vector<float> points = s.stream->cells->toPoints(values, comm);
    if (!m.cellFields.empty()) m.fields.push_back({field, {std::move(points)}});
  }
  if (comm.rank() == 0 && !s.stream->cellFields.empty()) {
    std::string names;
    for (const std::string& n : s.stream->cellFields)
      names += (names.empty() ? "'" : ", '") + n + "'";
    log::info(m.source, ": cell data ", names, s.stream->cellFields.size() == 1 ? " is" : " are",
              " streamed: one step in memory, averaged onto the points over all ranks when its "
              "frame comes");
  }
  m.cellFields.clear();
}

// Reading options for a streamed share whose field is cell data: step 0's cell values stay with
// the cells, and where each came from is kept, for the later steps.
void readCellsAlone(io::ReadOptions& read) {
  read.cellDataOnPoints = false;
  read.cellOrigins = true;
}

// cellData: the field asked for is cell data, averaged onto the points with the other ranks' help
// (a point between two ranks' pieces takes the cells of both).
RankShare readPieces(const std::string& path, const ShareOptions& o, bool cellData,
                     comm::Communicator& comm) {
  std::vector<uint64_t> sizes = io::pieceCellCounts(path);
  std::vector<int> toRank = partition::assignClustersToRanks(sizes, comm.size());
  RankShare s;
  s.totalClusters = int(sizes.size());
  s.clusters = clustersOfRank(toRank, comm.rank());
  if (o.streamSteps) s.stream.emplace();
  if (!s.clusters.empty()) {
    io::ReadOptions read = o.read;
    read.pieces = s.clusters;
    if (s.stream) {
      ShareOptions mine = o;
      mine.read.pieces = s.clusters;
      read = streamRead(path, mine, *s.stream);
    }
    read.cellDataOnPoints = !cellData;
    if (s.stream && cellData) readCellsAlone(read);
    s.mesh = io::readMesh(path, read);
    if (s.stream) {
      s.stream->filePoints = std::move(s.mesh.pointOrigin);
      s.stream->fileCells = std::move(s.mesh.cellOrigin);
      s.stream->fileCellCount = s.mesh.fileCells;
    }
  } else {
    s.mesh.source = path;  // a rank with no clusters renders nothing, but takes part
  }
  // One rank reading every piece refuses pieces whose point fields differ (io::listFieldSteps);
  // ranks reading some each must come to the same answer. (A stream of cell data lists the
  // fields asked for, cell data marked so.)
  if (comm.size() > 1)
    checkPiecesAgree(path, s.stream && cellData ? "cell data" : "point fields",
                     describeFields(s, listedFields(path, o.read, s)), !s.clusters.empty(),
                     pieceNames(path, s), comm);
  if (cellData && s.stream)
    averageFirstCellSteps(s, o.read.fields, comm);
  else if (cellData)
    cellDataToPointsOverRanks(s.mesh, !s.clusters.empty(), pieceNames(path, s), comm);
  return s;
}

// Point i of the extraction is file point base[extracted[i]] (base empty: the identity).
std::vector<uint32_t> composePointMaps(const std::vector<uint32_t>& base,
                                       std::vector<uint32_t> extracted) {
  if (!base.empty())
    for (uint32_t& p : extracted) p = base[p];
  return extracted;
}

RankShare readWhole(const std::string& path, const ShareOptions& o, bool cellData,
                    comm::Communicator& comm) {
  RankShare s;
  io::ReadOptions read = o.read;
  if (o.streamSteps && io::readsStepsAlone(path)) read = streamRead(path, o, s.stream.emplace());
  // Streamed cell data needs the whole mesh on one rank (loadRankShare): the averages then need
  // no other rank.
  const bool streamCells = s.stream && cellData;
  SM_CHECK(!streamCells || comm.size() == 1);
  if (streamCells) readCellsAlone(read);
  mesh::UnstructuredMesh whole = io::readMesh(path, read);
  if (o.metisClusters > 0) partition::assignMetisClusters(whole, o.metisClusters);
  std::vector<uint64_t> sizes = partition::clusterSizes(whole);
  std::vector<int> toRank = partition::assignClustersToRanks(sizes, comm.size());
  s.totalClusters = int(sizes.size());
  s.clusters = clustersOfRank(toRank, comm.rank());
  if (comm.size() == 1) {
    if (s.stream) {
      s.stream->filePoints = std::move(whole.pointOrigin);
      s.stream->fileCells = std::move(whole.cellOrigin);
      s.stream->fileCellCount = whole.fileCells;
    }
    s.mesh = std::move(whole);
    if (streamCells) averageFirstCellSteps(s, o.read.fields, comm);
  } else {
    // The points no element uses (a quadratic cell's mid-edge nodes, a skipped cell's) go to the
    // rank of the first cluster with elements: ranges then count them on any number of ranks,
    // as they do on one.
    const auto first = std::find_if(sizes.begin(), sizes.end(), [](uint64_t n) { return n > 0; });
    const bool strays =
        first != sizes.end() && toRank[size_t(first - sizes.begin())] == comm.rank();
    partition::ExtractedClusters mine =
        partition::extractClustersWithPointMap(whole, s.clusters, strays);
    if (s.stream)
      s.stream->filePoints = composePointMaps(whole.pointOrigin, std::move(mine.originalPoint));
    s.mesh = std::move(mine.mesh);
    s.mesh.source = path;
  }
  return s;
}

}  // namespace

bool fieldsAreCellData(const std::string& path, const io::ReadOptions& read,
                       comm::Communicator& comm) {
  if (read.fields.empty()) return false;  // the same on every rank: no collective needed
  // Rank 0 reads the header and tells the others: one read instead of one per rank, and every
  // rank takes the same path through the collectives that follow.
  const double mine = comm.rank() == 0 && io::asksForCellData(path, read) ? 1.0 : 0.0;
  return comm::maxOf(comm, mine) > 0.0;
}

bool streamsCellData(const std::string& path, const ShareOptions& o, int ranks) {
  // Each rank averages its own elements' values with the other ranks' sums at the points they
  // share (its pieces, or the whole mesh on one rank); a whole mesh split among ranks after
  // reading keeps every step in memory.
  const bool pieces = io::readsByPiece(path) && o.metisClusters == 0;
  return io::readsStepsAlone(path) && (pieces || ranks == 1);
}

RankShare loadRankShare(const std::string& path, const ShareOptions& o, comm::Communicator& comm) {
  const bool cellData = o.cellData ? *o.cellData : fieldsAreCellData(path, o.read, comm);
  const bool pieces = io::readsByPiece(path) && o.metisClusters == 0;
  ShareOptions reading = o;
  if (cellData) reading.streamSteps = o.streamSteps && streamsCellData(path, o, comm.size());
  RankShare s =
      pieces ? readPieces(path, reading, cellData, comm) : readWhole(path, reading, cellData, comm);
  s.wholeBounds = globalBounds(s.mesh.bounds(), comm);
  scene::ElementSizeSum local = scene::elementSizeSum(s.mesh);
  s.elementSize.sum = comm::sumOf(comm, local.sum);
  s.elementSize.count = comm::sumOf(comm, local.count);
  s.wholeElements = s.elementSize.count;
  if (s.wholeElements == 0)
    throw Error(path, ": no tetrahedra, pyramids, wedges or hexahedra to render");
  return s;
}

}  // namespace sm::app
