// In-situ example: a heat solver on a tetrahedra + wedges box, one slab of cells per MPI rank,
// rendered by shellmarch every few steps from its own arrays; rank 0 writes the images.
//
//   mpirun -np 4 shellmarch_heat_insitu --cells 16 --steps 200 --every 50 --out frames
//
// Options: --cells N (grid of 2N x N x N cells), --steps S, --every K (render every K steps and
// after the last), --size WxH, --out DIR, --early-termination E (>= 1: off), --raw (also write
// each frame's float RGBA as DIR/heat_NNNN.rgba: int32 width, int32 height, then 4 floats per
// pixel; exact comparisons).
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "heat_slab.h"
#include "shellmarch/insitu.h"

namespace {

struct Args {
  int cells = 12, steps = 60, every = 30, width = 160, height = 120;
  double earlyTermination = 0.99;
  std::string out = "heat_frames";
  bool raw = false;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    std::string k = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument(k + " needs a value");
      return argv[++i];
    };
    if (k == "--cells")
      a.cells = std::atoi(value());
    else if (k == "--steps")
      a.steps = std::atoi(value());
    else if (k == "--every")
      a.every = std::atoi(value());
    else if (k == "--out")
      a.out = value();
    else if (k == "--early-termination")
      a.earlyTermination = std::atof(value());
    else if (k == "--raw")
      a.raw = true;
    else if (k == "--size") {
      if (std::sscanf(value(), "%dx%d", &a.width, &a.height) != 2)
        throw std::invalid_argument("--size wants WxH");
    } else {
      throw std::invalid_argument("unknown option " + k);
    }
  }
  if (a.cells < 2 || a.steps < 0 || a.every < 1)
    throw std::invalid_argument("bad --cells/--steps/--every");
  return a;
}

void writeRaw(const std::string& path, const shellmarch::insitu::Image& img) {
  std::ofstream f(path, std::ios::binary);
  const int32_t size[2] = {img.width, img.height};
  f.write(reinterpret_cast<const char*>(size), sizeof size);
  f.write(reinterpret_cast<const char*>(img.rgba.data()), std::streamsize(img.rgba.size() * 4));
  if (!f) throw std::runtime_error(path + ": write failed");
}

void writeFrame(const Args& a, int step, const shellmarch::insitu::Image& img) {
  char name[32];
  std::snprintf(name, sizeof name, "heat_%04d", step);
  const std::string stem = a.out + "/" + name;
  img.writePng(stem + ".png", {0.08f, 0.08f, 0.1f});
  if (a.raw) writeRaw(stem + ".rgba", img);
  std::printf("step %4d: wrote %s.png\n", step, stem.c_str());
}

int run(const Args& a) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  heat::HeatSlab sim(heat::Grid{2 * a.cells, a.cells, a.cells}, MPI_COMM_WORLD);
  shellmarch::insitu::Renderer vis(MPI_COMM_WORLD);
  // The topology once: the solver's own arrays, viewed in place.
  vis.setMesh({sim.points(), sim.tetrahedra(), {}, sim.wedges(), {}});

  shellmarch::insitu::RenderSettings s;
  s.width = a.width;
  s.height = a.height;
  // Cold blue and hot red, room temperature (0) transparent; a fixed range keeps frames
  // comparable over time.
  s.table = {{0.23f, 0.30f, 0.75f, 1.0f},
             {0.55f, 0.65f, 0.95f, 0.08f},
             {0.87f, 0.87f, 0.87f, 0.0f},
             {0.95f, 0.60f, 0.45f, 0.08f},
             {0.71f, 0.02f, 0.15f, 1.0f}};
  s.range = {-1.0, 1.0};
  s.opacityScale = 4.0;
  s.earlyTermination = a.earlyTermination;
  if (rank == 0) std::filesystem::create_directories(a.out);
  for (;;) {
    if (sim.steps() % a.every == 0 || sim.steps() == a.steps) {
      vis.setField("temperature", sim.temperature());  // scalars only: no geometry rebuild
      shellmarch::insitu::Image img = vis.render(s);
      if (rank == 0) writeFrame(a, sim.steps(), img);
    }
    if (sim.steps() == a.steps) break;
    sim.step();
  }
  const shellmarch::insitu::Stats st = vis.stats();
  std::printf(
      "rank %d: %llu elements, %llu geometry builds, %llu scalar uploads, last frame %.1f ms "
      "(%s)\n",
      rank, (unsigned long long)st.elements, (unsigned long long)st.geometryBuilds,
      (unsigned long long)st.scalarUploads, st.frameMs, st.deviceName.c_str());
  if (st.validationErrors) {
    std::fprintf(stderr, "rank %d: %llu Vulkan validation errors\n", rank,
                 (unsigned long long)st.validationErrors);
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 0;
  try {
    status = run(parse(argc, argv));
  } catch (const std::exception& e) {
    // Renderer errors are thrown on every rank alike, so every rank gets here and finalises.
    std::fprintf(stderr, "shellmarch_heat_insitu: error: %s\n", e.what());
    status = 1;
  }
  MPI_Finalize();
  return status;
}
