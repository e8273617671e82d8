#include "prep/memory_report.h"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "prep/compaction.h"

namespace sm::prep {

uint64_t MemoryReport::preparedBytes() const {
  return vertices + connectivity + shell + elementBytes() + scalarsPerStep * scalarSteps +
         accelerationStructures;
}

double MemoryReport::compactionSavings() const {
  return plainElements ? 1.0 - double(compactedElements) / double(plainElements) : 0.0;
}

MemoryReport memoryReport(const PreparedRank& r, uint64_t scalarSteps) {
  MemoryReport m;
  m.compact = r.compact;
  m.vertices = 3 * r.numVertices() * sizeof(float);  // the positions, which a GpuScene may hold
  m.vertexMap = r.vertexSource.size() * sizeof(uint32_t);
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    m.connectivity += r.neighbors[t].size() * sizeof(uint32_t);
    m.compactedElements += r.elementCount[t] * compactBytes(t);
    m.plainElements += r.elementCount[t] * plainBytes(t);
  }
  m.shell =
      (r.shellIndices.size() + r.shellRefs.size() + r.shellOther.size() + r.shellAdjacency.size()) *
      sizeof(uint32_t);
  m.scalarsPerStep = r.numVertices() * sizeof(float);
  m.scalarSteps = scalarSteps;
  return m;
}

std::string formatBytes(uint64_t b) {
  char buf[64];
  if (b >= (1ull << 30))
    std::snprintf(buf, sizeof buf, "%.2f GiB", b / double(1ull << 30));
  else if (b >= (1ull << 20))
    std::snprintf(buf, sizeof buf, "%.2f MiB", b / double(1ull << 20));
  else if (b >= 1024)
    std::snprintf(buf, sizeof buf, "%.1f KiB", b / 1024.0);
  else
    std::snprintf(buf, sizeof buf, "%llu B", (unsigned long long)b);
  return buf;
}

std::string MemoryReport::table() const {
  const uint64_t total = preparedBytes();
  auto row = [&](const char* name, uint64_t bytes) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "| %-28s | %12s | %6.2f%% |\n", name, formatBytes(bytes).c_str(),
                  total ? 100.0 * bytes / total : 0.0);
    return std::string(buf);
  };
  std::string s =
      "| structure                    |        bytes |  share |\n"
      "|------------------------------|-------------:|-------:|\n";
  s += row("connectivity", connectivity);
  s += row(compact ? "elements (XOR-compacted)" : "elements (plain)", elementBytes());
  s += row("shell triangles", shell);
  s += row("shell BLAS + TLAS", accelerationStructures);
  s += row("vertices", vertices);
  s += row("scalars (resident steps)", scalarsPerStep * scalarSteps);
  s += row("total", total);
  char buf[200];
  std::snprintf(
      buf, sizeof buf,
      "element indices: plain %s, compacted %s: compaction saves %.2f%% (paper: 72.49%%)\n",
      formatBytes(plainElements).c_str(), formatBytes(compactedElements).c_str(),
      100.0 * compactionSavings());
  return s + buf;
}

void to_json(nlohmann::json& j, const MemoryReport& m) {
  j = nlohmann::json{{"vertices", m.vertices},
                     {"vertex_map_host", m.vertexMap},
                     {"connectivity", m.connectivity},
                     {"shell", m.shell},
                     {"compacted_elements", m.compactedElements},
                     {"plain_elements", m.plainElements},
                     {"scalars_per_step", m.scalarsPerStep},
                     {"scalar_steps", m.scalarSteps},
                     {"acceleration_structures", m.accelerationStructures},
                     {"compact", m.compact},
                     {"prepared_bytes", m.preparedBytes()},
                     {"compaction_savings", m.compactionSavings()}};
}

}  // namespace sm::prep
