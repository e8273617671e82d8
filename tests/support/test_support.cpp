#include "support/test_support.h"

#include <cstdlib>
#include <filesystem>

namespace sm::test {

std::string sharedDataPath(const std::string& file) {
  const char* env = std::getenv("SHELLMARCH_SHARED_DIR");
  std::string dir = env && *env ? env : SHELLMARCH_DEFAULT_SHARED_DIR;
  return (std::filesystem::path(dir) / "data" / file).string();
}

std::string outputDir(const std::string& testName) {
  const char* env = std::getenv("SHELLMARCH_TEST_OUT");
  std::filesystem::path dir = env && *env ? env : "/tmp/shellmarch-test-out";
  dir /= testName;
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace sm::test
