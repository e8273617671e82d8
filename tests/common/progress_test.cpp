// The progress line (common/progress.h): when it shows, what it says, and that nested work shows
// one line.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "common/progress.h"

namespace sm {
namespace {

// What Progress writes to standard error while `work` runs, with SHELLMARCH_PROGRESS = `forced`
// ("" unset).
template <typename Work>
std::string stderrOf(const char* forced, Work work) {
  if (*forced)
    setenv("SHELLMARCH_PROGRESS", forced, 1);
  else
    unsetenv("SHELLMARCH_PROGRESS");
  testing::internal::CaptureStderr();
  work();
  std::string text = testing::internal::GetCapturedStderr();
  unsetenv("SHELLMARCH_PROGRESS");
  return text;
}

TEST(Progress, SilentWhereNobodyWatches) {
  // Not forced, and standard error captured (not a terminal): nothing, even when allowed.
  allowProgress(true);
  const std::string out = stderrOf("", [] {
    Progress p("frame", 3);
    for (int i = 0; i < 3; ++i) p.advance();
    EXPECT_FALSE(p.shown());
  });
  allowProgress(false);
  EXPECT_EQ(out, "");
  EXPECT_EQ(stderrOf("0",
                     [] {
                       Progress p("frame", 2);
                       p.advance(2);
                     }),
            "");
}

TEST(Progress, ForcedLinesEndWithTheTotal) {
  const std::string out = stderrOf("1", [] {
    Progress p("piece written", 4);
    for (int i = 0; i < 4; ++i) p.advance();
  });
  // A short job: only the final line (none before the first second), with the count and 100%.
  EXPECT_EQ(out.rfind("shellmarch: piece written 4/4 (100%), 0 s\n", 0), 0u) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos) << "lines, not a terminal's carriage returns";
}

TEST(Progress, OnlyTheOutermostWorkCounts) {
  const std::string out = stderrOf("1", [] {
    Progress steps("step written", 2);
    for (int s = 0; s < 2; ++s) {
      Progress pieces("piece written", 3);
      EXPECT_FALSE(pieces.shown());
      for (int i = 0; i < 3; ++i) pieces.advance();
      steps.advance();
    }
  });
  EXPECT_EQ(out.find("piece"), std::string::npos) << out;
  EXPECT_NE(out.find("shellmarch: step written 2/2 (100%)"), std::string::npos) << out;
}

TEST(Progress, DurationsReadAsPeopleWriteThem) {
  EXPECT_EQ(shortDuration(0.4), "0 s");
  EXPECT_EQ(shortDuration(59.4), "59 s");
  EXPECT_EQ(shortDuration(65), "1 min 05 s");
  EXPECT_EQ(shortDuration(3725), "1 h 02 min");
  EXPECT_EQ(shortDuration(-3), "0 s");
}

}  // namespace
}  // namespace sm
