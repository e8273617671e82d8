// Which time steps `render --time` renders: one step, every step, a range of them, or the step
// at a time value (as ParaView's animation snaps to a data set's time steps).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "comm/reductions.h"

namespace sm::app {

// `text` is one of
//   K          step K
//   all        every step
//   A:B[:S]    steps A, A + S, ... up to B included (S >= 1, default 1)
//   t=VALUE    the step whose time value is nearest VALUE (the first of two as near), VALUE
//              within the first and last step's times
// `available` steps exist (agreed by every rank); `times` are the data's time values, one per
// step, on the ranks that read them (empty on a rank without pieces). Collective: every rank
// gets the same steps or throws sm::Error naming --time.
std::vector<uint64_t> selectSteps(const std::string& text, uint64_t available,
                                  const std::vector<double>& times, comm::Communicator& comm);

// Whether `text` asks for a sequence (all, or a range), however many steps it turns out to hold.
bool selectsSequence(const std::string& text);

}  // namespace sm::app
