#include "bench/registry.h"

namespace sm::app::bench {

void configureScaleBench(CLI::App& cmd);  // bench_scale.cpp

const std::vector<BenchCommand>& benchCommands() {
  static const std::vector<BenchCommand> all = {
      {"prep",
       "Load and preparation throughput (elements/s per stage) and peak memory on generated "
       "meshes, next to VTK's surface extraction",
       configurePrepBench},
      {"render",
       "Frames and samples per second per stage, compacted vs plain, next to VTK's unstructured "
       "ray cast mapper, with both images' error against the CPU reference",
       configureRenderBench},
      {"accuracy",
       "Error against the CPU reference and time per frame for every rung of the accuracy ladder "
       "(step sizes, element-exact, fragment encoding, list modes, single-fragment compositing)",
       configureAccuracyBench},
      {"features",
       "Pay for what you use: each optional feature's cost when unused (specialised out, A/A noise "
       "floor), compiled in without effect, and used",
       configureFeatureBench},
      {"counts",
       "The exchange at 72 and 552 ranks from real frames: each virtual rank's share rendered in "
       "turn, its fragment counts dumped and replayed (bytes per rank, load imbalance)",
       configureCountBench},
      {"tracers",
       "The two tracers (ray queries, ray tracing pipeline) taking turns on one view: frames, "
       "stages and throughput of each, their ratio per round, and whether their images agree",
       configureTracerBench},
      {"scale",
       "Cost curve over element counts and ranks: generate, load, prepare, first image and warm "
       "frames per stage, growth exponents, strong and weak scaling, bytes per element",
       configureScaleBench},
      {"png",
       "PNG encoding of a rendered frame: stb_image_write against libpng at several zlib levels, "
       "bytes and time to encode",
       configurePngBench},
  };
  return all;
}

}  // namespace sm::app::bench
