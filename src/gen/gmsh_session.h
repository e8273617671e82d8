// gmsh is one global instance per process, with global options and a current model. A session
// owns it for the length of one generation: serialised by a lock (two generators in one process
// take turns), initialised without the user's gmsh configuration files (results must not depend on
// ~/.gmshrc), silent unless the log level is Debug, and cleared of its models on every exit path.
#pragma once

#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include "common/error.h"

namespace sm::gen {

class GmshSession {
 public:
  explicit GmshSession(int threads);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;
};

// A failure inside gmsh: the stage that failed and gmsh's own message.
class GmshError : public Error {
 public:
  GmshError(const std::string& stage, const std::string& gmshMessage)
      : Error("gmsh failed while ", stage, ": ", gmshMessage) {}
};

// Throws GmshError for the first error gmsh logged since the last call, and forgets the log. The
// session keeps gmsh from throwing (an exception thrown from inside gmsh's mesher leaves it
// refusing all later work: "I'm busy! Ask me that later"), so errors are read from its log.
void throwGmshErrors(const char* stage);

// Runs f() as one stage: gmsh's logged errors (and anything it still throws) become GmshError.
template <typename F>
auto gmshStage(const char* stage, F&& f) {
  throwGmshErrors("an earlier stage");
  try {
    if constexpr (std::is_void_v<decltype(f())>) {
      f();
      throwGmshErrors(stage);
    } else {
      auto result = f();
      throwGmshErrors(stage);
      return result;
    }
  } catch (const std::string& message) {
    throw GmshError(stage, message);
  }
}

// Node tags of every element of a gmsh element type in the current model, in fresh vectors (gmsh
// 4.8 leaves the output untouched when there are none).
std::vector<std::size_t> elementNodes(int gmshType);

}  // namespace sm::gen
