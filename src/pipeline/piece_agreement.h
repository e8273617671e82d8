// Ranks that each read some pieces of one file must find in them what one rank reading every
// piece would (which refuses pieces that disagree): otherwise whether a file renders would depend
// on how many ranks share its pieces.
#pragma once

#include <string>

#include "comm/reductions.h"

namespace sm::app {

// Collective. `holds` false for a rank that read no pieces (it takes part, compares nothing).
// When the holders' `description`s (what their pieces hold, in words) differ, every rank throws
// sm::Error: "SOURCE: the pieces do not hold the same WHAT: rank A (its pieces) has ...; rank B
// (...) has ...", naming the first holder and the first that differs from it.
void checkPiecesAgree(const std::string& source, const std::string& what,
                      const std::string& description, bool holds, const std::string& pieces,
                      comm::Communicator& comm);

}  // namespace sm::app
