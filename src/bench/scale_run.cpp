#include "bench/scale_run.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>

#include "bench/bench_common.h"
#include "bench/scale_fit.h"
#include "cli/program.h"
#include "common/error.h"
#include "common/file_util.h"
#include "io/mesh_io.h"

extern char** environ;

namespace sm::app::bench {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::vector<std::string> logLines(const std::string& logPath) {
  std::vector<std::string> lines;
  std::string text;
  try {
    text = readTextFile(logPath);
  } catch (const Error&) {
    return lines;
  }
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  return lines;
}

// Why a child failed, in one line: shellmarch's own error (the cause; mpirun's banners only
// repeat that a rank exited or aborted), else a rank killed by a signal, else the log's last
// line that is not a banner's rule.
std::string failureLine(const std::string& logPath, int status) {
  const std::vector<std::string> lines = logLines(logPath);
  for (const char* mark : {"shellmarch: error:", "shellmarch: rank ", "error:", "exited on signal",
                           "Killed", "out of memory"})
    for (const std::string& line : lines)
      if (line.find(mark) != std::string::npos) return printableLine(line);
  if (status > 128)
    return concat("killed by signal ", status - 128, status - 128 == 9 ? " (out of memory?)" : "");
  for (auto it = lines.rbegin(); it != lines.rend(); ++it)
    if (it->find("-----") == std::string::npos) return printableLine(*it);
  return concat("exit status ", status);
}

std::string sizeArg(int w, int h) {
  return concat(w, "x", h);
}

// The stages of a render, in seconds. The wall time to the first image and "other" are
// estimates: render does not time its process from start to first image.
nlohmann::json timeRecord(const nlohmann::json& stats, double wallSeconds, int repeat) {
  nlohmann::json r;
  r["load_s"] = jsonNumber(stats, "load_seconds_max");
  r["prepare_s"] = jsonNumber(stats, "prepare_seconds_max");
  r["context_s"] = jsonNumber(stats, "startup.context_ms") / 1e3;
  r["pipelines_s"] = jsonNumber(stats, "startup.pipelines_ms") / 1e3;  // within the first frame
  r["first_frame_s"] = jsonNumber(stats, "startup.first_frame_ms") / 1e3;
  r["upload_s"] = jsonNumber(stats, "scene_upload_seconds_max");  // acceleration structures too
  // render times frames only when it renders more than one; a single frame is the cold one.
  double warm = jsonNumber(stats, "sequence.frame_ms_mean");
  if (!std::isfinite(warm) && stats.contains("frames") && !stats["frames"].empty())
    warm = jsonNumber(stats["frames"][0], "total_ms");
  r["warm_frame_ms"] = warm;
  r["frames_timed"] = repeat;
  r["wall_s"] = wallSeconds;
  // A plain render (one frame, cold) would have ended about the timed frames sooner.
  const double firstImage = wallSeconds - repeat * warm / 1e3;
  r["first_image_s"] = firstImage;
  // The rest: MPI start and exit.
  double known = 0;
  for (const char* k : {"load_s", "prepare_s", "context_s", "upload_s", "first_frame_s"})
    known += r[k].get<double>();
  r["other_s"] = firstImage - known;
  return r;
}

// Memory: the largest rank's host peaks, rank 0's prepared structures and their ratio.
void addMemory(nlohmann::json& r, const nlohmann::json& stats) {
  r["elements"] = stats.value("elements", nlohmann::json());
  r["elements_per_rank"] = stats.value("elements_per_rank", nlohmann::json());
  r["elements_rank0"] = stats.value("elements_rank0", nlohmann::json());
  r["host_peak_after_load_bytes"] = jsonNumber(stats, "host_peak_bytes_after_load_per_rank.max");
  r["host_peak_after_setup_bytes"] = jsonNumber(stats, "host_peak_bytes_after_setup_per_rank.max");
  r["host_after_first_frame_bytes"] =
      jsonNumber(stats, "host_bytes_after_first_frame_per_rank.max");
  r["host_after_last_frame_bytes"] = jsonNumber(stats, "host_bytes_after_last_frame_per_rank.max");
  r["device_bytes_max_rank"] = jsonNumber(stats, "device_bytes_max_rank");
  r["memory_rank0"] = stats.value("memory_rank0", nlohmann::json());
  const double prepared = jsonNumber(stats, "memory_rank0.prepared_bytes");
  r["prepared_bytes_rank0"] = prepared;
  r["peak_over_prepared"] = r["host_peak_after_setup_bytes"].get<double>() / prepared;
  // What reading and preparing the mesh hold at their peak, less what the process held before
  // any mesh (code, libraries, MPI), before the device has a copy (lavapipe's is host memory):
  // the memory that grows with the mesh, against the prepared size.
  r["host_at_start_bytes"] = jsonNumber(stats, "host_bytes_at_start_per_rank.max");
  r["host_peak_after_prepare_bytes"] =
      jsonNumber(stats, "host_peak_bytes_after_prepare_per_rank.max");
  // Each rank's own ratio: ranks hold unequal shares, so a ratio of maxima would mix ranks.
  r["mesh_peak_over_prepared"] = jsonNumber(stats, "host_mesh_peak_over_prepared_per_rank.max");
}

}  // namespace

ChildRun runChild(const std::vector<std::string>& argv, const std::string& logPath) {
  ChildRun r;
  const auto start = std::chrono::steady_clock::now();
  const SpawnResult run = spawnLogged(argv, logPath);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.status = run.status;
  r.peakRssBytes = run.peakRssBytes;
  if (r.status < 0)
    r.error = concat("could not start ", argv[0]);
  else if (r.status != 0)
    r.error = failureLine(logPath, r.status);
  return r;
}

std::string scaleMeshPath(const ScaleArgs& a, uint64_t target) {
  return joinPath(a.dataDir, concat("scale-", a.method, "-", target, ".pvtu"));
}

nlohmann::json generateMesh(const ScaleArgs& a, uint64_t target) {
  const std::string path = scaleMeshPath(a, target), record = path + ".generate.json";
  // A mesh kept by an earlier --keep run is reused with the record of its generation: at 128 M
  // elements, generating again would cost more than the rest of its row.
  if (a.keep && fileExists(path) && fileExists(record)) {
    nlohmann::json j = nlohmann::json::parse(readTextFile(record), nullptr, false);
    if (!j.is_discarded() && !j.contains("error")) {
      j["reused"] = true;
      return j;
    }
  }
  std::filesystem::create_directories(a.dataDir);
  std::vector<std::string> argv = {siblingExecutable("shellmarch"), "generate"};
  if (a.method != "gmsh") argv.insert(argv.end(), {"--method", a.method});
  argv.insert(argv.end(), {"--elements", std::to_string(target), "--out", path});
  if (a.clusters > 0) argv.insert(argv.end(), {"--clusters", std::to_string(a.clusters)});
  std::fprintf(stderr, "bench scale: generating %llu elements (%s)\n", (unsigned long long)target,
               a.method.c_str());
  const ChildRun r = runChild(argv, path + ".generate.log");
  nlohmann::json j = {{"elements_target", target},
                      {"mesh", path},
                      {"method", a.method},
                      {"seconds", r.seconds},
                      {"peak_rss_bytes", r.peakRssBytes},
                      {"reused", false}};
  if (r.status != 0) {
    j["error"] = r.error;
    return j;
  }
  // The count written, from generate's "wrote PATH: N elements (...)" line: the methods hit
  // their target only approximately.
  static const std::regex wrote(R"(^wrote .*: ([0-9]+) elements)");
  std::smatch m;
  for (const std::string& line : logLines(path + ".generate.log"))
    if (std::regex_search(line, m, wrote)) j["elements"] = std::stoull(m[1].str());
  if (!j.contains("elements")) {
    j["error"] = "generate printed no 'wrote ...: N elements' line";
    return j;
  }
  j["elements_per_second"] = j["elements"].get<double>() / std::max(r.seconds, 1e-9);
  if (a.keep) writeJsonFile(record, j);
  return j;
}

void removeMesh(const std::string& path) {
  std::vector<std::string> files;
  try {
    files = io::meshFiles(path);
  } catch (const std::exception&) {
    files = {path};  // unreadable index: at least the index goes
  }
  std::error_code ec;
  for (const std::string& f : files) std::filesystem::remove(f, ec);
  std::filesystem::remove(path, ec);
  // The pieces' folders, which remove() leaves where something else is in them.
  for (const std::string& f : files)
    if (directoryOf(f) != directoryOf(path)) std::filesystem::remove(directoryOf(f), ec);
}

nlohmann::json renderOnce(const ScaleArgs& a, const std::string& mesh, const std::string& tag,
                          int ranks, int w, int h, int repeat) {
  const std::string base = joinPath(a.dataDir, tag);
  const std::string stats = base + ".stats.json", image = base + ".png";
  std::filesystem::remove(stats);
  const std::vector<std::string> argv = {a.mpirun, "-n", std::to_string(ranks), "--oversubscribe",
                                         siblingExecutable("shellmarch"), "render", mesh,
                                         // The grid mesh is a flat annulus: along its axis
                                         // the disc fills the image, where the default
                                         // view leaves four pixels in five empty.
                                         "--view", "+z", "--size", sizeArg(w, h), "--repeat",
                                         std::to_string(repeat), "--stats-json", stats, "--out",
                                         image};
  std::fprintf(stderr, "bench scale: %s (%d rank(s), %dx%d, %d frames)\n", tag.c_str(), ranks, w, h,
               repeat);
  const ChildRun r = runChild(argv, base + ".log");
  std::error_code ec;
  std::filesystem::remove(image, ec);  // only the numbers are wanted
  nlohmann::json j;
  if (r.status == 0) {
    const nlohmann::json s = nlohmann::json::parse(readTextFile(stats), nullptr, false);
    if (s.is_discarded()) j["error"] = concat("render wrote no readable ", stats);
    if (!s.is_discarded()) {
      j = timeRecord(s, r.seconds, repeat);
      addMemory(j, s);
    }
  } else {
    j["error"] = r.error;
    j["wall_s"] = r.seconds;
  }
  j["ok"] = !j.contains("error");
  j["width"] = w;
  j["height"] = h;
  j["process_peak_rss_bytes"] = r.peakRssBytes;
  j["stats_json"] = stats;
  return j;
}

nlohmann::json framesCheck(const ScaleArgs& a, const std::string& mesh, int ranks, int w, int h,
                           int frames) {
  const nlohmann::json many =
      renderOnce(a, mesh, concat("frames-check-", frames), ranks, w, h, frames);
  nlohmann::json j = {{"frames", frames}, {"ranks", ranks}, {"width", w}, {"height", h}};
  if (!many["ok"].get<bool>()) {
    j["error"] = many["error"];
    return j;
  }
  // After the first and after the last frame: not the whole process's peak, under which the load
  // and preparation would hide a slow growth.
  const double before = jsonNumber(many, "host_after_first_frame_bytes");
  const double after = jsonNumber(many, "host_after_last_frame_bytes");
  j["measure"] = "host bytes after the first and the last frame (render --stats-json)";
  j["before_bytes"] = before;
  j["after_bytes"] = after;
  j["growth_bytes"] = after - before;
  j["growth_bytes_per_frame"] = (after - before) / double(frames - 1);
  // Allocator noise is a few MiB; a leak of a frame's buffers would be that many times frames.
  j["grows"] = after - before > std::max(8 * kMiB, 0.02 * before);
  return j;
}

}  // namespace sm::app::bench
