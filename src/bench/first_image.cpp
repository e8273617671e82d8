#include "bench/first_image.h"

#include <cstdio>
#include <filesystem>

#include "bench/bench_common.h"
#include "cli/program.h"
#include "common/error.h"
#include "common/file_util.h"

namespace sm::app::bench {
namespace {

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.9g", v);
  return s;
}

// `shellmarch render` of the benchmark's frame at w x h, as a user would type it.
std::vector<std::string> renderCommand(const RenderArgs& a, const Scenes& sc,
                                       const std::string& mesh, int w, int h,
                                       const std::string& out, const std::string& stats) {
  const std::string self = siblingExecutable("shellmarch");
  std::vector<std::string> cmd = {self,
                                  "render",
                                  mesh,
                                  "--field",
                                  a.field,
                                  "--size",
                                  concat(w, "x", h),
                                  "--view",
                                  a.view,
                                  "--fovy",
                                  number(a.fovy),
                                  "--colormap",
                                  a.colormap,
                                  "--opacity-scale",
                                  number(a.opacityScale),
                                  "--early-termination",
                                  number(a.earlyTermination),
                                  "--range",
                                  number(sc.range.first) + "," + number(sc.range.second),
                                  "--out",
                                  out,
                                  "--stats-json",
                                  stats};
  if (!a.stepText.empty()) cmd.insert(cmd.end(), {"--step", a.stepText});
  return cmd;
}

// The startup block of a run's --stats-json, or null.
nlohmann::json startupOf(const std::string& statsPath) {
  try {
    return nlohmann::json::parse(readTextFile(statsPath)).value("startup", nlohmann::json());
  } catch (const std::exception&) {
    return nullptr;
  }
}

}  // namespace

nlohmann::json measureFirstImage(const RenderArgs& a, const Scenes& sc, const std::string& mesh) {
  const auto [w, h] = parseSizes("--first-image", a.firstImage).front();
  const std::string dir = joinPath(a.workDir, "first-image");
  const std::string mesa = joinPath(dir, "mesa-cache"), shaders = joinPath(dir, "shader-cache");
  std::filesystem::create_directories(dir);
  // Private caches, so that "cold" is cold whatever the user's are; no validation layer.
  const std::vector<std::string> env = {"MESA_SHADER_CACHE_DIR=" + mesa,
                                        "SHELLMARCH_CACHE_DIR=" + shaders,
                                        "SHELLMARCH_VALIDATION=0"};
  std::fprintf(stderr, "first image %dx%d: %d cold and warm processes\n", w, h, a.firstImageRuns);
  nlohmann::json j;
  std::vector<double> cold, warm;
  for (int i = 0; i < a.firstImageRuns; ++i) {
    std::filesystem::remove_all(mesa);
    std::filesystem::remove_all(shaders);
    for (bool isCold : {true, false}) {
      const std::string tag = isCold ? "cold" : "warm";
      const std::string stats = joinPath(dir, "stats_" + tag + ".json");
      ProcessResult r =
          runProcess(renderCommand(a, sc, mesh, w, h, joinPath(dir, "shellmarch.png"), stats), env,
                     joinPath(dir, "render_" + tag + ".log"));
      if (r.status != 0) throw Error("first image: shellmarch render failed: ", r.error);
      (isCold ? cold : warm).push_back(r.seconds);
      j["startup_" + tag] = startupOf(stats);
    }
  }
  j["width"] = w;
  j["height"] = h;
  j["runs"] = a.firstImageRuns;
  j["cold_seconds"] = median(cold);
  j["warm_seconds"] = median(warm);
  j["cold_seconds_all"] = cold;
  j["warm_seconds_all"] = warm;
  render::RenderSettings s = settingsFor(a, sc, w, h);
  const nlohmann::json size = {{"width", w}, {"height", h}, {"camera", cameraJson(s.camera)}};
  j["vtk"] = vtkFirstImage(a, sc, mesh, size, a.firstImageRuns);
  if (j["vtk"].value("available", false)) {
    const double vtk = j["vtk"]["seconds"].get<double>();
    j["vtk_over_cold"] = vtk / median(cold);
    j["vtk_over_warm"] = vtk / median(warm);
  }
  return j;
}

void printFirstImage(const nlohmann::json& b) {
  const bool vtk = b["vtk"].value("available", false);
  Table t({concat("first image ", b["width"].get<int>(), "x", b["height"].get<int>(),
                  ", start to PNG (median of ", b["runs"].get<int>(), ")"),
           "seconds", "VTK / this"});
  auto ratio = [&](const char* key) { return b.contains(key) ? fixed(b[key], 2) : "-"; };
  t.add({"shellmarch, cold caches", fixed(b["cold_seconds"], 2), ratio("vtk_over_cold")});
  t.add({"shellmarch, warm caches", fixed(b["warm_seconds"], 2), ratio("vtk_over_warm")});
  t.add({"VTK (whole process)", vtk ? fixed(b["vtk"]["seconds"], 2) : "-", vtk ? "1.00" : "-"});
  std::printf("\n%s", t.str().c_str());
  if (!vtk) std::printf("VTK not measured: %s\n", b["vtk"].value("reason", "").c_str());
  for (const char* tag : {"cold", "warm"}) {
    const nlohmann::json& s = b["startup_" + std::string(tag)];
    if (s.is_null()) continue;
    std::printf(
        "%s: context %.0f ms, pipelines %.0f ms (%llu of %zu from the shader cache), "
        "first frame %.0f ms (tracing on the device %.0f ms)\n",
        tag, s["context_ms"].get<double>(), s["pipelines_ms"].get<double>(),
        (unsigned long long)s["pipelines_from_cache_rank0"].get<uint64_t>(),
        s["pipelines_rank0"].size(), s["first_frame_ms"].get<double>(),
        s["first_frame_device_ms"].get<double>());
  }
}

}  // namespace sm::app::bench
