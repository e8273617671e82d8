#include "pipeline/frame_writer.h"

#include <utility>

namespace sm::app {

FrameWriter::FrameWriter(size_t capacity)
    : capacity_(capacity < 1 ? 1 : capacity), thread_([this] { run(); }) {}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameWriter::throwError(std::unique_lock<std::mutex>& lock) {
  std::exception_ptr e = std::exchange(error_, nullptr);
  lock.unlock();
  std::rethrow_exception(e);
}

void FrameWriter::write(std::string path, scene::Image img, scene::Background background) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return held_ < capacity_ || error_; });
  if (error_) throwError(lock);
  queue_.push_back({std::move(path), std::move(img), background});
  ++held_;
  lock.unlock();
  changed_.notify_all();
}

void FrameWriter::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return held_ == 0; });
  if (error_) throwError(lock);
}

void FrameWriter::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
    if (queue_.empty()) return;  // stopping, and every frame written
    Frame f = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    std::exception_ptr failed;
    try {
      scene::writeImage(f.path, f.img, f.background);
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    --held_;
    if (failed && !error_) {
      error_ = failed;
      held_ -= queue_.size();  // the frames after a failure are not written
      queue_.clear();
    }
    changed_.notify_all();
  }
}

}  // namespace sm::app
