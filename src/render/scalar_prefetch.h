// Changing the time step or field without a stall: while frame k renders, a background thread
// loads the scalars of frame k + 1 (from disk, gathered into the scene's vertex order) and stages
// them in the scene's second scalar buffer; between the frames the buffers swap. Nothing but
// scalars moves: no connectivity, shell or acceleration structure is rebuilt.
#pragma once

#include <functional>
#include <future>
#include <vector>

#include "render/gpu_scene.h"

namespace sm::render {

// What one switch of scalars cost.
struct ScalarSwitch {
  double waitMs = 0;    // the rendering thread waited this long (load + upload when not prefetched)
  double loadMs = 0;    // producing the values (reading, gathering), on whichever thread did it
  double uploadMs = 0;  // copying them to the device
  bool prefetched = false;
};

class ScalarPrefetcher {
 public:
  // Values in the scene's vertex order (prep::gatherScalars).
  using Load = std::function<std::vector<float>()>;

  explicit ScalarPrefetcher(GpuScene& scene) : scene_(scene) {}
  // Waits for a prefetch still running (its result and errors are dropped).
  ~ScalarPrefetcher();
  ScalarPrefetcher(const ScalarPrefetcher&) = delete;
  ScalarPrefetcher& operator=(const ScalarPrefetcher&) = delete;

  // Starts loading and staging the next scalars on a background thread; one at a time. `load`
  // runs on that thread: it must not touch MPI or the scene.
  void prefetch(Load load);
  bool pending() const { return pending_.valid(); }
  // Between frames: waits for the prefetch, rethrows its error, makes its scalars the ones frames
  // read.
  ScalarSwitch swap();
  // Waits for a prefetch under way and drops its scalars and its error (the step it loaded is
  // not going to be shown); the buffer frames read is untouched.
  void discard();
  // Without a prefetch (the first frame, or prefetching off): loads and uploads now, on this
  // thread, into the buffer frames read.
  ScalarSwitch loadNow(const Load& load);

 private:
  GpuScene& scene_;
  std::future<ScalarSwitch> pending_;
};

}  // namespace sm::render
