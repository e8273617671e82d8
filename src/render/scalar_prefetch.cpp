#include "render/scalar_prefetch.h"

#include "common/check.h"
#include "common/timer.h"

namespace sm::render {

ScalarPrefetcher::~ScalarPrefetcher() {
  if (pending_.valid()) pending_.wait();
}

void ScalarPrefetcher::prefetch(Load load) {
  SM_CHECK(!pending_.valid());
  pending_ = std::async(std::launch::async, [this, load = std::move(load)] {
    ScalarSwitch s;
    Timer t;
    std::vector<float> values = load();
    s.loadMs = t.ms();
    t.reset();
    scene_.stageScalars(values);
    s.uploadMs = t.ms();
    s.prefetched = true;
    return s;
  });
}

ScalarSwitch ScalarPrefetcher::swap() {
  SM_CHECK(pending_.valid());
  Timer t;
  ScalarSwitch s = pending_.get();
  s.waitMs = t.ms();
  scene_.swapScalars();
  return s;
}

void ScalarPrefetcher::discard() {
  if (!pending_.valid()) return;
  pending_.wait();
  pending_ = {};
}

ScalarSwitch ScalarPrefetcher::loadNow(const Load& load) {
  SM_CHECK(!pending_.valid());  // setScalars may not run beside stageScalars
  ScalarSwitch s;
  Timer t;
  std::vector<float> values = load();
  s.loadMs = t.ms();
  t.reset();
  scene_.setScalars(values);
  s.uploadMs = t.ms();
  s.waitMs = s.loadMs + s.uploadMs;
  return s;
}

}  // namespace sm::render
