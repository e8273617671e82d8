// FrameRequest to RenderSettings (session::makeRenderSettings): the defaults that depend on the
// whole data set, known answers, and each refusal keyed by the setting at fault.
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "common/setting_error.h"
#include "scene/camera.h"
#include "scene/view_defaults.h"
#include "session/frame_request.h"

namespace sm::session {
namespace {

DataExtent unitCube(double meanElementSize = 0.25) {
  DataExtent d;
  d.whole.extend(glm::dvec3(0.0));
  d.whole.extend(glm::dvec3(1.0));
  d.meanElementSize = meanElementSize;
  d.name = "cube.vtu";
  return d;
}

// The key of the SettingError `f` throws, "" when it throws none.
std::string keyOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const SettingError& e) {
    return e.key();
  }
  return "";
}

std::string keyFor(const FrameRequest& r, std::pair<double, double> range = {0.0, 1.0}) {
  return keyOf([&] { makeRenderSettings(r, unitCube(), "f", range); });
}

TEST(FrameRequest, DefaultsComeFromTheWholeDataSet) {
  FrameRequest r;
  r.width = 64;
  r.height = 32;
  const render::RenderSettings s = makeRenderSettings(r, unitCube(), "f", {2.0, 5.0});
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.height, 32);
  // A coarse mesh (4 elements a side): 256 samples across the diagonal, not half an element.
  EXPECT_DOUBLE_EQ(s.dt, std::sqrt(3.0) / 256);
  EXPECT_DOUBLE_EQ(s.transferFunction.unitDistance, std::sqrt(3.0) / 8);
  EXPECT_EQ(s.transferFunction.lo, 2.0);
  EXPECT_EQ(s.transferFunction.hi, 5.0);
  const scene::Camera iso = scene::frameBounds(unitCube().whole, scene::ViewPreset::Iso, 2.0);
  EXPECT_EQ(s.camera.eye, iso.eye);
  EXPECT_EQ(s.camera.at, iso.at);
  EXPECT_EQ(s.integration, render::Integration::ElementExact);
  // A fine mesh keeps half an element.
  EXPECT_DOUBLE_EQ(makeRenderSettings(r, unitCube(0.001), "f", {0, 1}).dt, 0.0005);
}

TEST(FrameRequest, GivenValuesAreKept) {
  FrameRequest r;
  r.step = 0.05;
  r.unitDistance = 2.0;
  r.eye = glm::dvec3(3, 0, 0);
  r.table = {glm::vec4(0, 0, 0, 0), glm::vec4(1, 0.5f, 0, 1)};
  r.opacityScale = 0.5;
  r.earlyTermination = 0.9;
  r.integration = render::Integration::Sampled;
  const render::RenderSettings s = makeRenderSettings(r, unitCube(), "f", {0, 1});
  EXPECT_EQ(s.dt, 0.05);
  EXPECT_EQ(s.transferFunction.unitDistance, 2.0);
  EXPECT_EQ(s.camera.eye, glm::dvec3(3, 0, 0));
  EXPECT_EQ(s.camera.at, glm::dvec3(0.5));  // the data's centre without `at`
  EXPECT_EQ(s.transferFunction.table, r.table);
  EXPECT_EQ(s.transferFunction.opacityScale, 0.5);
  EXPECT_EQ(s.earlyTermination, 0.9);
  EXPECT_EQ(s.integration, render::Integration::Sampled);
}

TEST(FrameRequest, EachRefusalIsKeyedByItsSetting) {
  auto with = [](const std::function<void(FrameRequest&)>& change) {
    FrameRequest r;
    change(r);
    return r;
  };
  EXPECT_EQ(keyFor(FrameRequest{}), "");
  EXPECT_EQ(keyFor(with([](auto& r) { r.width = 0; })), "size");
  EXPECT_EQ(keyFor(with([](auto& r) { r.height = 20000; })), "size");
  EXPECT_EQ(keyFor(with([](auto& r) { r.view = "diagonal"; })), "view");
  EXPECT_EQ(keyFor(with([](auto& r) { r.eye = glm::dvec3(NAN, 0, 0); })), "eye");
  EXPECT_EQ(keyFor(with([](auto& r) { r.eye = glm::dvec3(0.5); })), "eye");  // the centre
  EXPECT_EQ(keyFor(with([](auto& r) {
              r.eye = glm::dvec3(2, 0, 0);
              r.at = r.eye;
            })),
            "at");
  EXPECT_EQ(keyFor(with([](auto& r) {
              r.eye = glm::dvec3(0.5, 0.5, 5);
              r.up = glm::dvec3(0, 0, 1);
            })),
            "up");
  EXPECT_EQ(keyFor(with([](auto& r) { r.fovyDeg = 180; })), "fovy");
  EXPECT_EQ(keyFor(with([](auto& r) { r.colormap = "no-such-map"; })), "colormap");
  EXPECT_EQ(keyFor(with([](auto& r) { r.table = {glm::vec4(0)}; })), "table");
  EXPECT_EQ(keyFor(with([](auto& r) { r.table = {glm::vec4(0), glm::vec4(2)}; })), "table");
  EXPECT_EQ(keyFor(with([](auto& r) { r.opacityPoints = {{1, 0.5}, {0, 0.5}}; })), "opacity");
  EXPECT_EQ(keyFor(with([](auto& r) { r.opacityScale = -1; })), "opacity-scale");
  EXPECT_EQ(keyFor(with([](auto& r) { r.unitDistance = 0.0; })), "unit-distance");
  EXPECT_EQ(keyFor(with([](auto& r) { r.step = -1.0; })), "step");
  EXPECT_EQ(keyFor(with([](auto& r) { r.step = 1e-12; })), "step");  // finer than floats resolve
  EXPECT_EQ(keyFor(with([](auto& r) {
              r.step = 10.0;
              r.integration = render::Integration::Sampled;
            })),
            "step");  // beyond the data: few rays would take a sample
  EXPECT_EQ(keyFor(with([](auto& r) { r.step = 10.0; })), "");  // element-exact takes none
  EXPECT_EQ(keyFor(with([](auto& r) { r.earlyTermination = 0; })), "early-termination");
  EXPECT_EQ(keyFor(with([](auto& r) {
              r.shading.enabled = true;
              r.shading.shininess = 0.5;
            })),
            "shading");
  EXPECT_EQ(keyFor(with([](auto& r) { r.clipPlanes.resize(7); })), "clip");
  EXPECT_EQ(keyFor(with([](auto& r) { r.logScale = true; }), {0.0, 1.0}), "log-scale");
  EXPECT_EQ(keyFor(with([](auto& r) { r.logScale = true; }), {0.5, 1.0}), "");
}

TEST(FrameRequest, MessagesNameTheFieldAndTheDataSet) {
  FrameRequest r;
  r.logScale = true;
  try {
    makeRenderSettings(r, unitCube(), "pressure", {-1.0, 4.0});
    ADD_FAILURE() << "a log scale over -1 .. 4 was accepted";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.key(), "log-scale");
    EXPECT_NE(e.detail().find("field 'pressure' has the range -1 .. 4"), std::string::npos)
        << e.detail();
  }
  // A mesh of flat elements: the fault lies with the data set, not with a setting not given.
  try {
    makeRenderSettings(FrameRequest{}, unitCube(0.0), "f", {0, 1});
    ADD_FAILURE() << "a flat mesh was accepted";
  } catch (const SettingError& e) {
    ADD_FAILURE() << "keyed " << e.key() << ": " << e.what();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cube.vtu: every element has zero volume"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sm::session
