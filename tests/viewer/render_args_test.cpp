// The viewer's report of how to render what it shows (render_args) and the names of the s key's
// screenshots, without a window: exact numbers, the flags that apply and only those.
#include <gtest/gtest.h>

#include <algorithm>

#include "viewer/render_args.h"
#include "viewer/screen_image.h"

namespace sm::view {
namespace {

bool has(const std::vector<std::string>& args, const std::string& arg) {
  return std::find(args.begin(), args.end(), arg) != args.end();
}

TEST(RenderArgs, CarryTheStateExactlyAndOnlyTheFlagsThatApply) {
  ViewState s;
  s.eye = {0.1, 2.0 / 3.0, -5.0};
  s.at = {0, 0, 0};
  s.up = {0, 0, 1};
  s.fovyDeg = 30;
  s.step = 2;
  s.opacityScale = 1.5;
  s.dt = 0.1;
  FieldInfo f{"pressure", 3, {-1.0, 1e-3}};
  scene::TransferFunction tf = scene::makeTransferFunction("viridis");
  tf.unitDistance = 0.25;
  const std::string map = "viridis";
  const std::vector<scene::OpacityPoint> none;
  const std::vector<scene::ClipPlane> noPlanes;
  std::vector<std::string> args = renderArgs(s, 64, 48, {f, map, tf, none, noPlanes, false});
  EXPECT_EQ(args, (std::vector<std::string>{
                      "--size=64x48", "--eye=0.10000000000000001,0.66666666666666663,-5",
                      "--at=0,0,0", "--up=0,0,1", "--fovy=30", "--field=pressure", "--time=2",
                      "--colormap=viridis", "--range=-1,0.001", "--opacity-scale=1.5",
                      "--step=0.10000000000000001", "--unit-distance=0.25"}));
  // Parsed back, %.17g gives the same doubles.
  EXPECT_EQ(std::stod("0.66666666666666663"), 2.0 / 3.0);

  tf.scale = scene::ScalarScale::Log;
  const std::vector<scene::OpacityPoint> points = {{0.3, 0.0}, {0.5, 1.0}};
  scene::ClipPlane p;
  p.point = {0, 0, 0};
  p.normal = {1, 0, 0};
  args = renderArgs(s, 64, 48, {f, map, tf, points, {p}, true});
  EXPECT_TRUE(has(args, "--legend"));
  EXPECT_TRUE(has(args, "--log-scale"));
  EXPECT_FALSE(has(args, "--integration=sampled"));  // element-exact, the default, says nothing
  EXPECT_EQ(std::count_if(args.begin(), args.end(),
                          [](const std::string& a) { return a.rfind("--opacity=", 0) == 0; }),
            1);
  EXPECT_EQ(std::count_if(args.begin(), args.end(),
                          [](const std::string& a) { return a.rfind("--clip=", 0) == 0; }),
            1);
  args = renderArgs(s, 64, 48, {f, map, tf, none, noPlanes, false, true});
  EXPECT_TRUE(has(args, "--integration=sampled"));
  EXPECT_EQ(std::count_if(args.begin(), args.end(),
                          [](const std::string& a) { return a.rfind("--parallel", 0) == 0; }),
            0);
  s.parallel = 1;
  s.parallelScale = 0.1;
  args = renderArgs(s, 64, 48, {f, map, tf, none, noPlanes, false});
  EXPECT_TRUE(has(args, "--parallel-scale=0.10000000000000001"));  // implies --parallel
}

TEST(ScreenImage, ScreenshotsAreNumberedBeforeTheExtension) {
  EXPECT_EQ(numberedPath("out/shot.png", 12), "out/shot_0012.png");
  EXPECT_EQ(numberedPath("", 3), "shellmarch-view_0003.png");
  EXPECT_EQ(numberedPath("dir.v2/shot", 1), "dir.v2/shot_0001.png");  // the dot is the folder's
}

TEST(ScreenImage, EnlargingRepeatsEachPixel) {
  const std::vector<glm::vec4> small = {glm::vec4(1), glm::vec4(2), glm::vec4(3), glm::vec4(4)};
  std::vector<glm::vec4> out;
  enlarge(small, 2, 2, 4, 2, out);
  ASSERT_EQ(out.size(), 8u);
  const float want[8] = {1, 1, 2, 2, 3, 3, 4, 4};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(out[size_t(i)].x, want[i]) << i;
}

}  // namespace
}  // namespace sm::view
