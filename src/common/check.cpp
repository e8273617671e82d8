#include "common/check.h"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace sm::detail {

void checkFailed(const char* file, int line, const char* expr, const std::string& msg) {
  std::fprintf(stderr, "shellmarch: internal error: CHECK(%s) failed at %s:%d%s%s\n", expr, file,
               line, msg.empty() ? "" : ": ", msg.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace sm::detail
