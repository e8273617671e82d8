// `generate --method grid`: checks what the mesh needs against the disk and memory first, then
// makes and writes its pieces on every core the process may use, each thread one piece at a time.
#include "cli/generate_grid.h"

#include <sys/statvfs.h>

#include <atomic>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include "common/error.h"
#include "common/parallel.h"
#include "common/progress.h"
#include "common/timer.h"
#include "gen/generate.h"
#include "gen/grid_mesh.h"
#include "io/mesh_io.h"

namespace sm::app {
namespace {

namespace fs = std::filesystem;

std::string gib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
  return text;
}

uint64_t availableMemory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  uint64_t kib = 0;
  while (in >> key >> kib) {
    if (key == "MemAvailable:") return kib * 1024;
    in.ignore(1 << 10, '\n');
  }
  return 0;  // unknown: not checked
}

uint64_t freeDiskBytes(fs::path folder) {
  std::error_code ec;
  while (!folder.empty() && !fs::exists(folder, ec)) folder = folder.parent_path();
  struct statvfs s {};
  if (statvfs(folder.empty() ? "." : folder.c_str(), &s) != 0) return 0;  // unknown
  return uint64_t(s.f_bavail) * uint64_t(s.f_frsize);
}

// Host memory while one piece is made and written: its ids and cluster ids, its points and their
// field values, the node-id tables (about twice the points), and zlib's output when compressing.
uint64_t pieceMemoryBytes(const gen::GridMesh& grid, const GridGenerateArgs& a) {
  const double pointsPerElement = double(grid.points()) / double(grid.elements());
  const double fields = 4.0 * a.steps;
  double perElement = 4.0 * 4.5 + 4.0 + pointsPerElement * (24.0 + 8.0 + 4.0 * fields);
  if (a.cellData) perElement += 2.0 * 4.0 * fields;  // cell fields, and the point fields before
  if (a.compress) perElement += 30.0;
  return uint64_t(perElement * double(grid.largestPieceElements()));
}

unsigned threadsThatFit(const gen::GridMesh& grid, const GridGenerateArgs& a) {
  const uint64_t piece = pieceMemoryBytes(grid, a), free = availableMemory();
  unsigned threads = std::min<unsigned>(hardwareThreads(), unsigned(grid.clusters()));
  while (free && threads > 1 && piece * threads > free) --threads;
  if (free && piece > free) {
    const uint64_t fitting = std::max<uint64_t>(1, free / (piece / grid.clusters() + 1));
    throw Error("--clusters: pieces of up to ", grid.largestPieceElements(),
                " elements need about ", gib(piece), " of memory each, ", gib(free),
                " available; use at least --clusters ", grid.elements() / fitting + 1);
  }
  return threads;
}

void checkDisk(const gen::GridMesh& grid, const GridGenerateArgs& a) {
  const uint64_t need = gridFileBytes(grid, a.steps, a.cellData);
  const uint64_t free = freeDiskBytes(fs::absolute(fs::path(a.out)).parent_path());
  if (free && need > free)
    throw Error(a.out, ": the mesh needs about ", gib(need), " on disk, ", gib(free),
                " free; about ", uint64_t(double(grid.elements()) * double(free) / double(need)),
                " --elements would fit");
}

// The names, steps and times every piece carries, without geometry.
mesh::UnstructuredMesh layout(const GridGenerateArgs& a, const gen::GridMesh& grid) {
  mesh::UnstructuredMesh m;
  gen::addAnalyticFields(m, a.steps, grid.bounds(), 1);
  if (a.cellData) mesh::pointFieldsToCells(m);
  return m;
}

// Pieces go to threads one at a time as they finish, largest cost first being unknown: the nested
// cluster and its host differ from the rest, so a static split would leave a thread idle.
void writePieces(const gen::GridMesh& grid, const GridGenerateArgs& a, unsigned threads) {
  io::WriteOptions options;
  options.compress = a.compress;
  options.threads = 1;
  io::PvtuPieceWriter writer(a.out, uint64_t(grid.clusters()), layout(a, grid), options);
  std::atomic<int> next{0};
  std::mutex mutex;
  std::exception_ptr failure;
  Progress progress("piece written", uint64_t(grid.clusters()));
  auto work = [&] {
    for (int k = next++; k < grid.clusters(); k = next++) {
      try {
        mesh::UnstructuredMesh piece = grid.piece(k);
        if (a.cellData) mesh::pointFieldsToCells(piece);
        writer.write(uint64_t(k), piece);
        std::lock_guard lock(mutex);
        progress.advance();
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        next = grid.clusters();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  writer.finish();
}

std::string summary(const gen::GridMesh& g, const GridGenerateArgs& a, double seconds) {
  std::string types;
  for (mesh::CellType t : mesh::kAllCellTypes)
    types +=
        concat(types.empty() ? "" : ", ", g.elementsOfType(t), " ", mesh::cellTypePluralName(t));
  const gen::ClusterShapeReport shapes = gen::clusterShapes(g);
  char rate[96];
  std::snprintf(rate, sizeof rate, "%.1f s, %.2f M elements/s; ", seconds,
                double(g.elements()) / seconds * 1e-6);
  char lines[160];
  std::snprintf(lines, sizeof lines,
                "%d random lines cross a cluster's boundary %.1f times on average, each cluster's "
                "at least %d times on one of its lines",
                shapes.lines, shapes.meanCrossings, shapes.fewestMostCrossings);
  const std::string nested =
      g.nestedCluster() < 0
          ? std::string("none nested")
          : concat("cluster ", g.nestedCluster(), " nested in cluster ", g.hostCluster(),
                   shapes.nestedEnclosed ? "" : " (NOT enclosed)");
  return concat("wrote ", a.out, ": ", g.elements(), " elements (", types, "), ", g.points(),
                " points, ", g.clusters(), " clusters, ", a.steps,
                a.steps == 1 ? " step" : " steps", a.cellData ? " of cell data" : "",
                ", grid method, ", rate, lines, "; ", nested);
}

}  // namespace

uint64_t gridFileBytes(const gen::GridMesh& grid, int steps, bool cellData) {
  const uint64_t fields = 4 * uint64_t(steps);
  uint64_t bytes = 0;
  for (mesh::CellType t : mesh::kAllCellTypes)  // Int64 ids and offset, UInt8 type, Int32 cluster
    bytes += grid.elementsOfType(t) * (8 * mesh::numVerts(t) + 8 + 1 + 4);
  bytes += cellData ? grid.elements() * 4 * fields : 0;
  // Pieces repeat the points on their borders: a tenth more is ample for these shapes.
  const uint64_t points = grid.points() + grid.points() / 10;
  bytes += points * (24 + (cellData ? 0 : 4 * fields));
  return bytes + uint64_t(grid.clusters()) * 4096;  // headers
}

std::string generateGridMesh(const GridGenerateArgs& a) {
  Timer timer;
  gen::GridMesh grid({a.elements, a.clusters, a.steps});
  const unsigned threads = threadsThatFit(grid, a);
  checkDisk(grid, a);
  writePieces(grid, a, threads);
  return summary(grid, a, timer.seconds());
}

}  // namespace sm::app
