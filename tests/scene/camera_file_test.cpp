// ParaView camera files (scene/camera_file.h): a file as ParaView writes it, the round trip, and
// malformed files refused with one line naming the file and the property.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/error.h"
#include "common/file_util.h"
#include "scene/camera_file.h"

namespace sm::scene {
namespace {

const std::string kData = SHELLMARCH_SCENE_TEST_DATA;

// ParaView's File > Save Camera of a parallel view (tests/scene/data/paraview_parallel.pvcc).
TEST(CameraFile, ReadsWhatParaViewWrites) {
  const Camera c = readCameraFile(kData + "/paraview_parallel.pvcc");
  const double s = 2.7320508075688772;  // 1 + sqrt(3)
  EXPECT_DOUBLE_EQ(c.eye.x, 0.5 + s);
  EXPECT_DOUBLE_EQ(c.eye.y, 0.5 - s);
  EXPECT_DOUBLE_EQ(c.eye.z, s);
  EXPECT_EQ(c.at, glm::dvec3(0.5, 0.5, 0));
  EXPECT_DOUBLE_EQ(c.up.z, 0.81649658092772603);
  EXPECT_EQ(c.fovyDeg, 30);
  EXPECT_TRUE(c.parallel);
  EXPECT_DOUBLE_EQ(c.parallelScale, 0.866025403784439);
  EXPECT_NO_THROW(cameraFrame(c, 16, 16));
}

TEST(CameraFile, WritesWhatItReadsBackExactly) {
  Camera c;
  c.eye = {0.1, -1.0 / 3.0, 7e-5};
  c.at = {2.5, 1e-17, -4};
  c.up = {0, 0.2, 1};
  c.fovyDeg = 33.3;
  for (bool parallel : {false, true}) {
    c.parallel = parallel;
    c.parallelScale = 0.123456789012345678;
    const Camera r = parseCameraFile(cameraFileText(c), "round.pvcc");
    EXPECT_EQ(r.eye, c.eye);
    EXPECT_EQ(r.at, c.at);
    EXPECT_EQ(r.up, c.up);
    EXPECT_EQ(r.fovyDeg, c.fovyDeg);
    EXPECT_EQ(r.parallel, c.parallel);
    EXPECT_EQ(r.parallelScale, c.parallelScale);
  }
  // Written as ParaView writes it: the root, the view proxy and the properties it reads.
  const std::string text = cameraFileText(c);
  for (const char* part :
       {"<PVCameraConfiguration description=\"ParaView camera configuration\" version=\"1.0\">",
        "<Proxy group=\"views\" type=\"RenderView\"", "name=\"CameraFocalPoint\"",
        "name=\"CenterOfRotation\"", "name=\"CameraParallelProjection\"", "<Domain name=\"bool\""})
    EXPECT_NE(text.find(part), std::string::npos) << part;
}

TEST(CameraFile, WritesAFileThatReadsBack) {
  const std::string dir = std::filesystem::temp_directory_path() / "shellmarch_camera_file_test";
  std::filesystem::create_directories(dir);
  const Camera c = readCameraFile(kData + "/paraview_parallel.pvcc");
  writeCameraFile(dir + "/saved.pvcc", c);
  const Camera r = readCameraFile(dir + "/saved.pvcc");
  EXPECT_EQ(r.eye, c.eye);
  EXPECT_EQ(r.parallelScale, c.parallelScale);
  std::filesystem::remove_all(dir);
}

// ParaView's file with one property's text replaced.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = readTextFile(kData + "/paraview_parallel.pvcc");
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The message: one line, starting with the file's name, holding `want`.
void expectRefused(const std::string& text, const std::string& want) {
  try {
    parseCameraFile(text, "bad.pvcc");
    ADD_FAILURE() << "accepted; wanted an error with '" << want << "'";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("bad.pvcc: ", 0), 0u) << m;
    EXPECT_NE(m.find(want), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(CameraFile, RefusesMissingProperties) {
  expectRefused(edited("name=\"CameraFocalPoint\"", "name=\"SomethingElse\""),
                "property CameraFocalPoint is missing");
  expectRefused(edited("name=\"CameraViewAngle\"", "name=\"X\""),
                "property CameraViewAngle is missing");
  // Parallel needs its scale.
  expectRefused(edited("name=\"CameraParallelScale\"", "name=\"X\""),
                "property CameraParallelScale is missing");
  expectRefused(edited("<Element index=\"2\" value=\"2.7320508075688772\"/>", ""),
                "property CameraPosition: element 2 is missing");
}

TEST(CameraFile, RefusesValuesThatAreNotNumbers) {
  expectRefused(edited("value=\"-2.2320508075688772\"", "value=\"abc\""),
                "property CameraPosition: element 1 value 'abc' is not a finite number");
  expectRefused(edited("value=\"30\"", "value=\"30deg\""), "property CameraViewAngle: element 0");
  expectRefused(edited("value=\"30\"", "value=\"nan\""), "property CameraViewAngle: element 0");
  expectRefused(edited("value=\"0.866025403784439\"", "value=\"1e999\""),
                "property CameraParallelScale: element 0");
  expectRefused(edited("<Element index=\"0\" value=\"30\"/>", "<Element index=\"0\"/>"),
                "property CameraViewAngle: element 0 has no value");
  expectRefused(
      edited("<Element index=\"0\" value=\"30\"/>", "<Element index=\"one\" value=\"30\"/>"),
      "property CameraViewAngle: element index 'one'");
}

TEST(CameraFile, RefusesImpossibleCameras) {
  expectRefused(edited("value=\"30\"", "value=\"180\""), "property CameraViewAngle is 180");
  expectRefused(edited("value=\"0.866025403784439\"", "value=\"-2\""),
                "property CameraParallelScale is -2");
  expectRefused(edited("      <Element index=\"0\" value=\"1\"/>\n      <Domain",
                       "      <Element index=\"0\" value=\"2\"/>\n      <Domain"),
                "property CameraParallelProjection is 2");
  // Up along the line of sight: (1, -1, 1).
  std::string up = edited(
      "value=\"-0.40824829046386296\"/>\n      <Element index=\"1\" "
      "value=\"0.40824829046386296\"/>\n      <Element index=\"2\" "
      "value=\"0.81649658092772603\"",
      "value=\"1\"/>\n      <Element index=\"1\" value=\"-1\"/>\n      "
      "<Element index=\"2\" value=\"1\"");
  expectRefused(up, "property CameraViewUp");
  expectRefused(edited("<Element index=\"0\" value=\"0.5\"/>\n      <Element index=\"1\" "
                       "value=\"0.5\"/>\n      <Element index=\"2\" value=\"0\"/>",
                       "<Element index=\"0\" value=\"3.2320508075688772\"/>\n      <Element "
                       "index=\"1\" value=\"-2.2320508075688772\"/>\n      <Element index=\"2\" "
                       "value=\"2.7320508075688772\"/>"),
                "CameraPosition and CameraFocalPoint are the same point");
  expectRefused(edited("number_of_elements=\"3\"", "number_of_elements=\"2\""),
                "property CameraPosition has number_of_elements=\"2\", not 3");
}

TEST(CameraFile, RefusesDocumentsThatAreNotCameraFiles) {
  expectRefused(edited("PVCameraConfiguration description", "VTKFile description"),
                "is not well-formed XML");  // the end tag no longer matches
  std::string root = edited("<PVCameraConfiguration description", "<CustomViewpoints description");
  root.replace(root.rfind("</PVCameraConfiguration>"), 24, "</CustomViewpoints>");
  expectRefused(root, "the root element is <CustomViewpoints>, not <PVCameraConfiguration>");
  expectRefused(edited("group=\"views\"", "group=\"sources\""), "has no view <Proxy");
  const std::string whole = readTextFile(kData + "/paraview_parallel.pvcc");
  expectRefused(whole.substr(0, whole.size() / 2), "is not well-formed XML");  // truncated
  expectRefused("", "is not well-formed XML");
  expectRefused("{\"camera\": 1}", "is not well-formed XML");
  expectRefused(edited("    <Property name=\"CenterOfRotation\"",
                       "    <Property name=\"CameraViewAngle\" number_of_elements=\"1\">\n"
                       "      <Element index=\"0\" value=\"30\"/>\n    </Property>\n"
                       "    <Property name=\"CenterOfRotation\""),
                "property CameraViewAngle is given twice");
}

TEST(CameraFile, AMissingFileIsAnErrorNamingIt) {
  try {
    readCameraFile(kData + "/no_such_camera.pvcc");
    ADD_FAILURE() << "read a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_camera.pvcc"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sm::scene
