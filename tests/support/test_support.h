// Helpers shared by the test programs: where the shared data and test outputs live, and small
// meshes built inline.
#pragma once

#include <string>

#include "mesh/unstructured_mesh.h"

namespace sm::test {

// ../shared/data (or $SHELLMARCH_SHARED_DIR/data).
std::string sharedDataPath(const std::string& file);
// A fresh folder for this test's outputs under $SHELLMARCH_TEST_OUT (or /tmp); created on demand.
std::string outputDir(const std::string& testName);

}  // namespace sm::test
