#include "bench/prep_measure.h"

#include <algorithm>

#include "bench/bench_common.h"
#include "common/memory.h"
#include "common/timer.h"
#include "io/mesh_io.h"
#include "prep/memory_report.h"
#include "prep/prepare.h"

namespace sm::app::bench {

const std::vector<PrepStage>& prepStages() {
  static const std::vector<PrepStage> stages = {{"load", "load (read + weld)"},
                                                {"vertex_order", "vertex order + rebase"},
                                                {"connectivity", "connectivity"},
                                                {"shell", "shell"},
                                                {"compaction", "compaction"}};
  return stages;
}

nlohmann::json measurePrepOnce(const PrepMeasureOptions& o) {
  return runInChild([&] {
    // The child inherits the parent's (small) resident set; the peak is counted from here on.
    resetPeakResident();
    const uint64_t start = currentResidentBytes();
    Timer timer;
    io::ReadOptions read;
    read.fields = o.fields;
    read.threads = o.threads;
    mesh::UnstructuredMesh mesh = io::readMesh(o.path, read);
    const double load = timer.seconds();
    const uint64_t peakLoad = peakResidentBytes(), rssLoad = currentResidentBytes();
    const uint64_t elements = mesh.numCells(), vertices = mesh.points.size();
    prep::GlobalFrame frame = prep::makeGlobalFrame(mesh.bounds());
    prep::PrepResult r = prep::prepareRank(mesh, frame, prep::PrepOptions{true});
    const uint64_t peak = peakResidentBytes(), rssPrep = currentResidentBytes();
    prep::MemoryReport mem = prep::memoryReport(r.rank);
    nlohmann::json j;
    j["seconds"] = {{"load", load},
                    {"vertex_order", r.timings.vertexOrder},
                    {"connectivity", r.timings.connectivity},
                    {"shell", r.timings.shell},
                    {"compaction", r.timings.compaction}};
    j["elements"] = elements;
    j["vertices"] = vertices;
    j["boundary_faces"] = r.connectivity.boundaryFaces;
    j["interior_faces"] = r.connectivity.interiorFaces;
    j["shell_triangles"] = r.rank.numShellTriangles();
    j["memory"] = mem;
    j["prepared_bytes"] = mem.preparedBytes();
    j["compaction_savings"] = mem.compactionSavings();
    j["start_rss_bytes"] = start;
    j["peak_after_load_bytes"] = peakLoad;
    j["peak_bytes"] = peak;
    // Resident after each phase: what the allocator kept of the phase's peak.
    j["rss_after_load_bytes"] = rssLoad;
    j["rss_after_prepare_bytes"] = rssPrep;
    return j;
  });
}

nlohmann::json summarisePrepRuns(const std::vector<nlohmann::json>& runs) {
  const nlohmann::json& first = runs.front();
  const double elements = first["elements"].get<double>();
  nlohmann::json s;
  for (const char* k :
       {"elements", "vertices", "boundary_faces", "interior_faces", "shell_triangles", "memory",
        "compaction_savings", "rss_after_load_bytes", "rss_after_prepare_bytes"})
    s[k] = first[k];
  s["runs"] = runs.size();
  double combined = 0;
  for (const PrepStage& st : prepStages()) {
    std::vector<double> v;
    for (const auto& r : runs) v.push_back(r["seconds"][st.key].get<double>());
    const double sec = median(v);
    s["stages"][st.key] = {
        {"seconds", sec}, {"seconds_all", v}, {"elements_per_second", elements / sec}};
    if (std::string(st.key) == "connectivity" || std::string(st.key) == "shell" ||
        std::string(st.key) == "compaction")
      combined += sec;
  }
  s["conn_shell_compaction"] = {{"seconds", combined},
                                {"elements_per_second", elements / combined}};
  uint64_t peak = 0, peakLoad = 0, start = ~0ull;
  for (const auto& r : runs) {
    peak = std::max(peak, r["peak_bytes"].get<uint64_t>());
    peakLoad = std::max(peakLoad, r["peak_after_load_bytes"].get<uint64_t>());
    start = std::min(start, r["start_rss_bytes"].get<uint64_t>());
  }
  const double prepared = first["prepared_bytes"].get<double>();
  s["memory_peak"] = {{"prepared_bytes", first["prepared_bytes"]},
                      {"start_rss_bytes", start},
                      {"peak_after_load_bytes", peakLoad},
                      {"peak_bytes", peak},
                      {"peak_above_start_bytes", peak - start},
                      {"ratio_peak_above_start", double(peak - start) / prepared},
                      {"ratio_peak", double(peak) / prepared}};
  return s;
}

}  // namespace sm::app::bench
