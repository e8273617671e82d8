// gtest main for tests run under mpiexec: initialises and finalises MPI, gives the tests the world
// communicator and one Vulkan context per process, prints only rank 0's progress (failures of
// every rank are printed with their rank), and fails every rank when one failed. An exception that
// escapes a test ends all ranks through MPI_Abort with its message: gtest must not swallow it, or
// the other ranks would wait in a collective the failed rank never joins.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "mpi_world.h"

namespace sm::comp::test {
namespace {

comm::MpiCommunicator* gWorld = nullptr;
vk::Context* gContext = nullptr;

class RankFailurePrinter : public ::testing::EmptyTestEventListener {
 public:
  explicit RankFailurePrinter(int rank) : rank_(rank) {}
  void OnTestPartResult(const ::testing::TestPartResult& r) override {
    if (!r.failed()) return;
    std::fprintf(stderr, "[rank %d] %s:%d: failure\n%s\n", rank_,
                 r.file_name() ? r.file_name() : "?", r.line_number(), r.summary());
  }

 private:
  int rank_;
};

}  // namespace

comm::MpiCommunicator& mpiWorld() {
  return *gWorld;
}
const vk::Context& mpiContext() {
  return *gContext;
}

}  // namespace sm::comp::test

int main(int argc, char** argv) {
  using namespace sm::comp;
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  GTEST_FLAG_SET(catch_exceptions, false);
  int failed = 0;
  {
    sm::comm::MpiCommunicator world;
    test::gWorld = &world;
    sm::comm::runOrAbort(world, [&] {
      sm::vk::ContextOptions o;
      o.rayTracing = false;
      sm::vk::Context ctx(o);
      test::gContext = &ctx;
      if (world.rank() != 0) {
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
        listeners.Append(new test::RankFailurePrinter(world.rank()));
      }
      failed = RUN_ALL_TESTS() != 0 ? 1 : 0;
      failed = int(world.allreduceMax(uint64_t(failed)));
      test::gContext = nullptr;
    });
  }
  MPI_Finalize();
  return failed;
}
