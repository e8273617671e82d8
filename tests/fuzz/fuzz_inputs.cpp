#include "fuzz_inputs.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <unistd.h>

#include "common/error.h"
#include "common/hash.h"
#include "common/log.h"
#include "io/mesh_io.h"
#include "io/readers.h"
#include "prep/cache.h"
#include "prep/memory_report.h"
#include "prep/prepare.h"
#include "scene/transfer_function.h"

namespace sm::fuzz {
namespace {

// Readers and preparation warn about what they fix; thousands of executions a second must not
// print, and a fuzzer's output should hold only its findings.
struct Quiet {
  Quiet() { log::setLevel(log::Level::Quiet); }
};
const Quiet quiet;

[[noreturn]] void bug(const std::string& what) {
  throw FuzzBug(what);
}

// Messages are printed as one line after "shellmarch: error: " and must say which input is at
// fault; raw bytes of a hostile file must not reach a terminal.
void checkMessage(const std::string& msg, const std::string& prefix) {
  if (msg.rfind(prefix, 0) != 0) bug("message does not start with '" + prefix + "': " + msg);
  for (unsigned char c : msg)
    if (c < 0x20 || c == 0x7f) bug("message holds a control character: " + msg);
}

// What every later stage assumes of a mesh a reader returned.
void checkMesh(const mesh::UnstructuredMesh& m) {
  const uint64_t np = m.numPoints();
  for (const glm::dvec3& p : m.points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      bug("the mesh has a non-finite point");
  for (size_t t = 0; t < mesh::kAllCellTypes.size(); ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    if (m.cells[t].size() % nv != 0) bug("a cell array is not a whole number of cells");
    if (m.clusters[t].size() != m.cells[t].size() / nv) bug("cluster ids do not match cells");
    for (uint32_t v : m.cells[t])
      if (v >= np) bug("a cell refers to a point the mesh does not have");
    for (int32_t c : m.clusters[t])
      if (c < 0) bug("a negative cluster id");
  }
  for (const mesh::Field& f : m.fields)
    for (const auto& step : f.steps)
      if (step.size() != np) bug("field '" + f.name + "' has a step of the wrong length");
}

// Small meshes go on through preparation (what `render` does next with a file): connectivity,
// shell and compaction meet whatever geometry the reader let through.
std::string prepare(mesh::UnstructuredMesh m, const std::string& name) {
  if (m.numCells() == 0 || m.numCells() > 4096) return "";
  const std::vector<float> scalars =
      m.fields.empty() ? std::vector<float>() : m.fields.front().steps.front();
  try {
    prep::PrepResult r = prep::prepareRank(m, prep::makeGlobalFrame(m.bounds()), {});
    if (r.rank.positions.size() != 3 * r.rank.numVertices()) bug("prepared positions mismatch");
    if (!scalars.empty()) prep::gatherScalars(r.rank, scalars);
  } catch (const FuzzBug&) {
    throw;
  } catch (const Error& e) {
    checkMessage(e.what(), name);
    return e.what();
  }
  return "";
}

std::string readMeshInput(std::span<const uint8_t> bytes, const std::string& name) {
  io::ReadOptions options;
  options.threads = 1;  // the fuzzer runs one input at a time; threads only add noise
  mesh::UnstructuredMesh m;
  try {
    m = io::readMeshFromMemory(bytes, name, options);
  } catch (const FileError& e) {
    checkMessage(e.what(), name);
    return e.what();
  } catch (const std::exception& e) {
    bug(std::string("not a FileError: ") + e.what());
  }
  checkMesh(m);
  return prepare(std::move(m), name);
}

// A format read through a library that opens files (CGNS, Exodus II): the bytes become a file of
// this process's own, read by the ordinary entry point and removed.
std::string libraryFileInput(std::span<const uint8_t> bytes, const std::string& extension) {
  const std::string path =
      (std::filesystem::temp_directory_path() / concat("shellmarch-fuzz-", ::getpid(), extension))
          .string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }
  struct Remove {
    std::string path;
    ~Remove() { std::filesystem::remove(path); }
  } remove{path};
  io::ReadOptions options;
  options.threads = 1;
  mesh::UnstructuredMesh m;
  try {
    m = io::readMesh(path, options);
  } catch (const FileError& e) {
    checkMessage(e.what(), path);
    return e.what();
  } catch (const std::exception& e) {
    bug(std::string("not a FileError: ") + e.what());
  }
  checkMesh(m);
  return prepare(std::move(m), path);
}

std::string pvtuInput(std::span<const uint8_t> bytes) {
  mesh::UnstructuredMesh m;
  std::vector<std::string> opened;
  try {
    m = readPvtuBundle(bytes, &opened);
  } catch (const FileError& e) {
    // The file at fault is the index or a piece; a piece's Source may be absolute, so the message
    // need not start with the index's folder, only with a path the reader asked for.
    const std::string msg = e.what();
    std::string prefix = "fuzz/";
    for (const std::string& path : opened)
      if (msg.rfind(printableLine(path + ":"), 0) == 0) prefix = printableLine(path);
    checkMessage(msg, prefix);
    return msg;
  } catch (const std::exception& e) {
    bug(std::string("not a FileError: ") + e.what());
  }
  checkMesh(m);
  return prepare(std::move(m), "fuzz/index.pvtu");
}

std::string ugridInput(std::span<const uint8_t> bytes) {
  if (bytes.empty()) return "empty input";
  const auto& variants = ugridVariants();
  const std::string& v = variants[bytes[0] % variants.size()];
  return readMeshInput(bytes.subspan(1), v.empty() ? "fuzz.ugrid" : "fuzz." + v + ".ugrid");
}

// Field offsets in the cache header (prep/cache.cpp: magic, version, flags, key, payload size,
// payload checksum).
constexpr size_t kHeaderBytes = 64, kKeyAt = 16, kPayloadBytesAt = 24, kPayloadHashAt = 32;

std::string parseCacheImage(const uint8_t* data, size_t size) {
  uint64_t key = 0;
  if (size >= kHeaderBytes) std::memcpy(&key, data + kKeyAt, 8);  // never stale by key
  prep::CacheRead r;
  try {
    r = prep::parseCache(data, size, key);
  } catch (const std::exception& e) {
    bug(std::string("parseCache threw: ") + e.what());
  }
  if (r.status == prep::CacheStatus::Hit) {
    if (!r.rank) bug("a cache hit without a rank");
    const prep::PreparedRank& rank = *r.rank;
    if (rank.positions.size() != 3 * rank.numVertices()) bug("cached positions mismatch");
    prep::memoryReport(rank);
    return "";
  }
  if (r.rank) bug("a rejected cache with a rank");
  if (r.reason.empty()) bug("rejected without reason");
  return r.reason;
}

// The outcome reported is that of the repaired image, the one that reaches the sections.
std::string cacheInput(std::span<const uint8_t> bytes) {
  std::string outcome = parseCacheImage(bytes.data(), bytes.size());
  // A mutation almost never keeps the checksum right, so the sections behind it would be out of
  // the fuzzer's reach: repair size and checksum and parse again.
  if (bytes.size() < kHeaderBytes) return outcome;
  std::vector<uint8_t> fixed(bytes.begin(), bytes.end());
  const uint64_t payload = fixed.size() - kHeaderBytes;
  const uint64_t hash = hashBytes(fixed.data() + kHeaderBytes, payload);
  std::memcpy(fixed.data() + kPayloadBytesAt, &payload, 8);
  std::memcpy(fixed.data() + kPayloadHashAt, &hash, 8);
  return parseCacheImage(fixed.data(), fixed.size());
}

std::string colormapInput(std::span<const uint8_t> bytes) {
  const std::string name = "fuzz.json";
  scene::TransferFunction tf;
  try {
    tf = scene::parseParaViewColormap(std::string(bytes.begin(), bytes.end()), name);
  } catch (const FileError& e) {
    checkMessage(e.what(), name);
    return e.what();
  } catch (const std::exception& e) {
    bug(std::string("not a FileError: ") + e.what());
  }
  if (tf.table.size() != 256) bug("the table does not have the entries asked for");
  for (const glm::vec4& c : tf.table)
    for (int k = 0; k < 4; ++k)
      if (!(c[k] >= 0.0f && c[k] <= 1.0f)) bug("a table entry outside [0, 1]");
  return "";
}

}  // namespace

const std::vector<std::string>& targetNames() {
  static const std::vector<std::string> names = {
      "vtu", "pvtu", "legacy_vtk", "ugrid", "cache", "colormap", "su2", "gmsh", "cgns", "exodus"};
  return names;
}

Target targetByName(const std::string& name) {
  const auto& names = targetNames();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return Target(i);
  throw std::invalid_argument("unknown fuzz target '" + name + "'");
}

const std::vector<std::string>& ugridVariants() {
  static const std::vector<std::string> v = {"",    "b8", "lb8", "b8l", "lb8l", "b4",
                                             "lb4", "r8", "lr8", "r4",  "lr4"};
  return v;
}

mesh::UnstructuredMesh readPvtuBundle(std::span<const uint8_t> bytes,
                                      std::vector<std::string>* opened) {
  const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::vector<std::string_view> parts;
  for (size_t at = 0;;) {
    const size_t sep = all.find(kPieceSeparator, at);
    parts.push_back(all.substr(at, sep == std::string_view::npos ? sep : sep - at));
    if (sep == std::string_view::npos) break;
    at = sep + kPieceSeparator.size();
  }
  const std::string index = "fuzz/index.pvtu";
  std::map<std::string, size_t> assigned;  // piece path -> bundle part
  io::OpenFile open = [&](const std::string& path) {
    if (opened) opened->push_back(path);
    size_t part = 0;
    if (path != index) part = assigned.try_emplace(path, assigned.size() + 1).first->second;
    if (part >= parts.size()) throw FileError(path, "cannot open: No such file or directory");
    const auto* p = reinterpret_cast<const uint8_t*>(parts[part].data());
    return io::FileBytes::copyOf({p, parts[part].size()});
  };
  io::ReadOptions options;
  options.threads = 1;
  return io::readPvtu(index, options, open);
}

std::string runInput(Target target, std::span<const uint8_t> bytes) {
  switch (target) {
    case Target::Vtu:
      return readMeshInput(bytes, "fuzz.vtu");
    case Target::Pvtu:
      return pvtuInput(bytes);
    case Target::LegacyVtk:
      return readMeshInput(bytes, "fuzz.vtk");
    case Target::Ugrid:
      return ugridInput(bytes);
    case Target::Cache:
      return cacheInput(bytes);
    case Target::Colormap:
      return colormapInput(bytes);
    case Target::Su2:
      return readMeshInput(bytes, "fuzz.su2");
    case Target::Gmsh:
      return readMeshInput(bytes, "fuzz.msh");
    case Target::Cgns:
      return libraryFileInput(bytes, ".cgns");
    case Target::Exodus:
      return libraryFileInput(bytes, ".exo");
  }
  return "";
}

}  // namespace sm::fuzz
