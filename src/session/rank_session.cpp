#include "session/rank_session.h"

#include <algorithm>

#include "common/check.h"

namespace sm::session {

RankSession::RankSession(const vk::ContextOptions& context, comm::Communicator* comm,
                         SessionOptions options)
    : ownedContext_(std::make_unique<vk::Context>(context)),
      ctx_(ownedContext_.get()),
      comm_(comm),
      options_(options) {}

RankSession::RankSession(const vk::Context& context, comm::Communicator* comm,
                         SessionOptions options)
    : ctx_(&context), comm_(comm), options_(options) {}

RankSession::~RankSession() {
  releaseScene();
}

render::GpuScene& RankSession::setScene(const prep::PreparedRank& rank,
                                        std::vector<float> positions, render::ShellGeometry shell) {
  releaseScene();
  scene_ = std::make_unique<render::GpuScene>(*ctx_, rank, std::move(positions), shell);
  return *scene_;
}

void RankSession::releaseRenderers() {
  targets_.clear();
  if (passes_) retiredPipelines_ += passes_->pipelinesBuilt();
  passes_.reset();
}

void RankSession::releaseScene() {
  releaseRenderers();
  if (scene_) {
    retiredBuilds_ += scene_->geometryBuilds();
    retiredUploads_ += scene_->scalarUploads();
  }
  scene_.reset();
}

render::GpuScene& RankSession::scene() const {
  SM_CHECK(scene_ != nullptr);
  return *scene_;
}

RankSession::Target& RankSession::target(int width, int height,
                                         const comp::CompositorOptions& lists, vk::Tracer tracer) {
  SM_CHECK(scene_ != nullptr);
  for (size_t i = 0; i < targets_.size(); ++i)
    if (targets_[i].width == width && targets_[i].height == height && targets_[i].lists == lists &&
        targets_[i].tracer == tracer) {
      std::rotate(targets_.begin() + long(i), targets_.begin() + long(i) + 1, targets_.end());
      return targets_.back();
    }
  if (int(targets_.size()) >= std::max(options_.keptSizes, 1)) targets_.erase(targets_.begin());
  Target t;
  t.width = width;
  t.height = height;
  t.lists = lists;
  t.tracer = tracer;
  t.compositor = std::make_unique<comp::DeepCompositor>(*ctx_, comm_, width, height, lists);
  // Pipelines are shared where they serve (the same list mode, encoding and tracer: PassCache).
  t.renderer = std::make_unique<render::Renderer>(*ctx_, *scene_, *t.compositor, passes_, tracer);
  if (passes_ && t.renderer->passes() != passes_) retiredPipelines_ += passes_->pipelinesBuilt();
  passes_ = t.renderer->passes();
  targets_.push_back(std::move(t));
  return targets_.back();
}

render::Renderer& RankSession::renderer(int width, int height) {
  return renderer(width, height, options_.lists, options_.tracer);
}

comp::DeepCompositor& RankSession::compositor(int width, int height) {
  return compositor(width, height, options_.lists, options_.tracer);
}

render::Renderer& RankSession::renderer(int width, int height, const comp::CompositorOptions& lists,
                                        vk::Tracer tracer) {
  return *target(width, height, lists, tracer).renderer;
}

comp::DeepCompositor& RankSession::compositor(int width, int height,
                                              const comp::CompositorOptions& lists,
                                              vk::Tracer tracer) {
  return *target(width, height, lists, tracer).compositor;
}

render::FrameResult RankSession::render(const render::RenderSettings& s,
                                        std::vector<glm::vec4> reuse) {
  return renderer(s.width, s.height).render(s, std::move(reuse));
}

uint64_t RankSession::pipelinesBuilt() const {
  return retiredPipelines_ + (passes_ ? passes_->pipelinesBuilt() : 0);
}

uint64_t RankSession::geometryBuilds() const {
  return retiredBuilds_ + (scene_ ? scene_->geometryBuilds() : 0);
}

uint64_t RankSession::scalarUploads() const {
  return retiredUploads_ + (scene_ ? scene_->scalarUploads() : 0);
}

}  // namespace sm::session
