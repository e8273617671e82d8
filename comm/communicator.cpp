#include "comm/communicator.h"

namespace sm::comm {

void runOrAbort(Communicator& comm, const std::function<void()>& fn) {
  try {
    fn();
  } catch (const CommAborted&) {
    throw;  // another rank failed first and has already ended the group
  } catch (const std::exception& e) {
    comm.abort(e.what());
  }
}

}  // namespace sm::comm
