// The frame loop's image files, written on a thread of their own: encoding a 1024x1024 PNG takes
// tens of milliseconds that the next frame's rendering would otherwise wait for. The queue is
// bounded (frames held, queued or being written, at most `capacity`), so memory stays at a couple
// of frames however slowly the disk goes; each file is written atomically as scene::writeImage
// writes it, with the same bytes as a write on the caller's thread.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "scene/image.h"

namespace sm::app {

class FrameWriter {
 public:
  explicit FrameWriter(size_t capacity = 2);
  // Waits for the frames queued (an error then goes unreported: finish() is where it is said).
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queues `img` for `path` (scene::writeImage) and returns; waits first while `capacity` frames
  // are held. Throws the error of an earlier frame's write, if one failed (frames queued after
  // it are dropped: the run stops as it would have at that frame).
  void write(std::string path, scene::Image img, scene::Background background);
  // Waits until every frame queued is written; throws the first error.
  void finish();

 private:
  struct Frame {
    std::string path;
    scene::Image img;
    scene::Background background;
  };
  void run();
  void throwError(std::unique_lock<std::mutex>& lock);

  const size_t capacity_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;
  size_t held_ = 0;  // queued plus the one being written
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace sm::app
