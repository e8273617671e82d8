// `render --time`: step indices, ranges, 'all' and time values, and every malformed or impossible
// request named by the option (app::selectSteps on one process; the collective agreement of ranks
// with and without the times is exercised by app.time-steps under mpiexec).
#include <gtest/gtest.h>

#include "comm/reductions.h"
#include "comm/single_rank.h"
#include "common/error.h"
#include "pipeline/time_selection.h"

namespace sm::app {
namespace {

using Steps = std::vector<uint64_t>;

Steps select(const std::string& text, uint64_t available, std::vector<double> times = {}) {
  comm::SingleRank one;
  return selectSteps(text, available, times, one);
}

std::string errorOf(const std::string& text, uint64_t available, std::vector<double> times = {}) {
  try {
    select(text, available, times);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "'" << text << "' was accepted";
  return {};
}

TEST(TimeSelection, IndicesRangesAndAll) {
  EXPECT_EQ(select("0", 1), Steps{0});
  EXPECT_EQ(select("4", 5), Steps{4});
  EXPECT_EQ(select("all", 3), (Steps{0, 1, 2}));
  EXPECT_EQ(select("all", 0), Steps{0});  // a mesh without fields still renders once
  EXPECT_EQ(select("1:3", 5), (Steps{1, 2, 3}));
  EXPECT_EQ(select("2:2", 5), Steps{2});
  EXPECT_EQ(select("0:9:4", 10), (Steps{0, 4, 8}));
  EXPECT_EQ(select("1:7:3", 8), (Steps{1, 4, 7}));  // the last included when the stride meets it
}

// `all` and ranges are sequences however many steps they hold (their files are numbered).
TEST(TimeSelection, AllAndRangesAreSequences) {
  for (const char* s : {"all", "0:0", "1:3:2"}) EXPECT_TRUE(selectsSequence(s)) << s;
  for (const char* s : {"0", "3", "t=0.5"}) EXPECT_FALSE(selectsSequence(s)) << s;
}

TEST(TimeSelection, NearestTimeValue) {
  const std::vector<double> times{0.0, 0.25, 1.5, 2.0};
  EXPECT_EQ(select("t=0", 4, times), Steps{0});
  EXPECT_EQ(select("t=0.2", 4, times), Steps{1});
  EXPECT_EQ(select("t=0.875", 4, times), Steps{1});  // halfway: the first of two as near
  EXPECT_EQ(select("t=1.4", 4, times), Steps{2});
  EXPECT_EQ(select("t=2", 4, times), Steps{3});
  EXPECT_EQ(select("t=2e0", 4, times), Steps{3});
  EXPECT_EQ(select("t=-1", 2, {-3.0, 5.0}), Steps{0});
}

TEST(TimeSelection, BadRequestsNameTheOption) {
  EXPECT_EQ(errorOf("5", 5), "--time: step 5 does not exist (the data has 5 time steps: 0 .. 4)");
  EXPECT_EQ(errorOf("1", 1), "--time: step 1 does not exist (the data has 1 time step: 0 .. 0)");
  for (const char* bad : {"", "-1", "+1", "1.5", "x", "18446744073709551616", " 1"})
    EXPECT_EQ(errorOf(bad, 3), std::string("--time: '") + bad +
                                   "' is not a step index, FIRST:LAST[:STRIDE], t=TIME or 'all'");
  for (const char* bad : {"1:", ":2", "1:2:0", "1:2:3:4", "a:b", "1:-2"})
    EXPECT_EQ(errorOf(bad, 3), std::string("--time: '") + bad +
                                   "' is not a range FIRST:LAST or FIRST:LAST:STRIDE of steps");
  EXPECT_EQ(errorOf("2:1", 3), "--time: '2:1' starts after it ends");
  EXPECT_EQ(errorOf("0:3", 3), "--time: step 3 does not exist (the data has 3 time steps: 0 .. 2)");
  const std::vector<double> times{0.0, 0.5, 1.0};
  EXPECT_EQ(errorOf("t=1.5", 3, times), "--time: 1.5 is outside the data's times (0 .. 1)");
  EXPECT_EQ(errorOf("t=-0.1", 3, times), "--time: -0.1 is outside the data's times (0 .. 1)");
  for (const char* bad : {"t=", "t=x", "t=1x", "t=nan", "t=inf", "t= 1"})
    EXPECT_EQ(errorOf(bad, 3, times),
              std::string("--time: '") + bad + "' is not t= followed by a time value");
  EXPECT_EQ(errorOf("t=0.5", 3),
            "--time: 't=0.5': the data has no time values; give a step index (0 .. 2)");
  EXPECT_EQ(errorOf("t=0.5", 3, {0.0, 1.0}),
            "--time: 't=0.5': the data has no time values for each of its steps; give a step "
            "index (0 .. 2)");
}

}  // namespace
}  // namespace sm::app
