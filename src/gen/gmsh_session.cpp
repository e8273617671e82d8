#include "gen/gmsh_session.h"

#include <gmsh.h>

#include <cstdlib>

#include "common/log.h"
#include "common/parallel.h"

namespace sm::gen {
namespace {

std::mutex& gmshMutex() {
  static std::mutex m;
  return m;
}

// gmsh 4.8 does not survive finalize() followed by a second initialize() (seen: the second volume
// mesh aborted in its pyramid code), so it is initialised once per process, cleared between
// sessions and finalised at exit.
void initialiseOnce() {
  static bool initialised = false;
  if (initialised) return;
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  initialised = true;
  std::atexit([] {
    try {
      gmsh::finalize();
    } catch (...) {
      // Exiting anyway.
    }
  });
}

// A fresh log (stopping the logger discards what it holds).
void restartLog() {
  static bool started = false;
  if (started) gmsh::logger::stop();
  gmsh::logger::start();
  started = true;
}

}  // namespace

GmshSession::GmshSession(int threads) : lock_(gmshMutex()) {
  try {
    initialiseOnce();
    const bool verbose = log::level() >= log::Level::Debug;
    gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
    // Errors (1) at least: they are read back from gmsh's log.
    gmsh::option::setNumber("General.Verbosity", verbose ? 4 : 1);
    gmsh::option::setNumber("General.NumThreads", threads > 0 ? threads : int(hardwareThreads()));
    gmsh::option::setNumber("General.AbortOnError", 0);
    // Node tags carry identity between the stages' models; gmsh must not renumber them.
    gmsh::option::setNumber("Mesh.Renumber", 0);
    restartLog();
    gmsh::clear();
  } catch (const std::string& message) {
    throw GmshError("initialising", message);
  }
}

GmshSession::~GmshSession() {
  try {
    gmsh::clear();  // the models' memory, not the instance
  } catch (...) {
    // Nothing to report from a destructor; the next session clears again.
  }
}

void throwGmshErrors(const char* stage) {
  std::vector<std::string> lines;
  gmsh::logger::get(lines);
  restartLog();
  for (const auto& line : lines)
    if (line.rfind("Error", 0) == 0) {
      const size_t colon = line.find(':');
      throw GmshError(stage, colon == std::string::npos ? line : line.substr(colon + 2));
    }
}

std::vector<std::size_t> elementNodes(int gmshType) {
  std::vector<std::size_t> elementTags, nodeTags;
  gmsh::model::mesh::getElementsByType(gmshType, elementTags, nodeTags, -1);
  return nodeTags;
}

}  // namespace sm::gen
