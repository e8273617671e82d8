#include "file_render.h"
#include "comm/single_rank.h"

#include "comm/reductions.h"
#include "pipeline/render_job.h"
#include "scene/image.h"
#include "scene_args.h"

namespace sm::python {

Frames renderFile(const std::string& path, const std::vector<std::string>& args) {
  app::RenderJob job = parseSceneArgs(path, args);
  job.out.clear();  // nothing is written: the frames come back
  Frames frames;
  frames.width = job.width;
  frames.height = job.height;
  const scene::Background background = job.imageBackground();
  job.frameSink = [&](const scene::Image& img, uint64_t) {
    frames.rgba.push_back(scene::toRgba8(img, background));
  };
  // One process, whatever launched Python: a script under mpirun renders files on each rank
  // alone (data-parallel files are the command's; in situ is Renderer's).
  comm::SingleRank single;
  runRender(job, single);
  return frames;
}

}  // namespace sm::python
