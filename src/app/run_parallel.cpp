#include "app/run_parallel.h"

namespace sm::app {

void runParallel(const std::function<void(Collectives&)>& body) {
  SingleProcess single;
  body(single);
}

}  // namespace sm::app
