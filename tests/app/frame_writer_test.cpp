// The frame loop's writer thread: the files it writes hold the bytes a write on the caller's
// thread gives, in any number of frames through its bounded queue, and a failed write is thrown
// at the next write or at finish(), not lost.
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "common/file_util.h"
#include "pipeline/frame_writer.h"
#include "support/test_support.h"

namespace sm::app {
namespace {

scene::Image frame(int w, int h, int seed) {
  scene::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float a = float((x * 7 + y * 3 + seed) % 11) / 10.0f;
      img.at(x, y) = glm::vec4(a * float(x) / w, a * float(y) / h, a * 0.5f, a);
    }
  return img;
}

TEST(FrameWriter, WritesTheBytesAWriteOnTheCallersThreadGives) {
  const std::string dir = test::outputDir("FrameWriter.Bytes");
  const scene::Background backgrounds[] = {glm::vec3(0.1f, 0.2f, 0.3f), std::nullopt};
  {
    FrameWriter writer(2);
    for (int i = 0; i < 6; ++i)
      writer.write(dir + "/thread_" + std::to_string(i) + ".png", frame(40 + i, 30, i),
                   backgrounds[i % 2]);
    writer.write(dir + "/thread.pfm", frame(20, 10, 9), glm::vec3(0.5f));
    writer.finish();
  }
  for (int i = 0; i < 6; ++i) {
    const std::string direct = dir + "/direct_" + std::to_string(i) + ".png";
    scene::writeImage(direct, frame(40 + i, 30, i), backgrounds[i % 2]);
    EXPECT_EQ(readFile(dir + "/thread_" + std::to_string(i) + ".png"), readFile(direct)) << i;
  }
  scene::writeImage(dir + "/direct.pfm", frame(20, 10, 9), glm::vec3(0.5f));
  EXPECT_EQ(readFile(dir + "/thread.pfm"), readFile(dir + "/direct.pfm"));
}

TEST(FrameWriter, AFailedWriteIsThrownAtTheNextWriteOrAtFinish) {
  const std::string dir = test::outputDir("FrameWriter.Errors");
  const std::string missing = dir + "/no-such-folder/a.png";
  {
    FrameWriter writer(1);
    writer.write(missing, frame(8, 8, 0), glm::vec3(0.0f));
    EXPECT_THROW(writer.finish(), Error);
    writer.finish();                                                    // said once
    writer.write(dir + "/after.png", frame(8, 8, 0), glm::vec3(0.0f));  // it goes on
    writer.finish();
  }
  {
    FrameWriter writer(1);
    writer.write(missing, frame(8, 8, 0), glm::vec3(0.0f));
    // Capacity one: the next write waits for the failed one, and throws its error.
    EXPECT_THROW(writer.write(dir + "/b.png", frame(8, 8, 0), glm::vec3(0.0f)), Error);
  }
  {
    FrameWriter writer;  // left with an error never asked for: the destructor neither throws
    writer.write(missing, frame(8, 8, 0), glm::vec3(0.0f));  // nor hangs
  }
  EXPECT_THROW(scene::writeImage(dir + "/t.pfm", frame(4, 4, 0), std::nullopt), Error);
}

}  // namespace
}  // namespace sm::app
