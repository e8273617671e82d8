// One `shellmarch render` run on one rank: load this rank's share, prepare (through the cache),
// upload, render the requested time steps, composite, write PNGs on rank 0.
#pragma once

#include "comm/communicator.h"
#include "pipeline/render_options.h"

namespace sm::app {

void runRender(const RenderJob& job, comm::Communicator& comm);

}  // namespace sm::app
