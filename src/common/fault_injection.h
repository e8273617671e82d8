// Fault injection for the reliability tests (tests/reliability, docs/RELIABILITY.md): makes one
// rank die or fail at a chosen point, so that tests can check that every other rank ends with the
// message and that no half-written output remains. Off unless SHELLMARCH_FAULT is set:
//
//   SHELLMARCH_FAULT=at=frame,frame=N[,rank=R],action=kill|throw
//       at the start of the N-th frame a render draws (0 = the first), after the scene is built
//   SHELLMARCH_FAULT=at=write[,match=SUBSTRING][,rank=R],action=kill|throw
//       halfway through writing an output file (PNG, cache, mesh, JSON) under its temporary name
//   SHELLMARCH_FAULT=at=read-ahead[,rank=R],action=stall
//       a time step read ahead while a frame renders (the viewer's play, render --time all) does
//       not start until the reader stops it or a minute passes: a read that is still running
//       when the viewer closes or jumps to another step, however fast the disk
//   SHELLMARCH_FAULT=at=range-pass[,rank=R],action=close|next-field
//       the viewer's window asks to close while a new field's range pass reads its steps (as
//       if its close button were pressed then), before the pass's first step; or, next-field,
//       the next-field key is pressed then (once, at the first pass)
//
// stall applies to at=read-ahead only, close and next-field to at=range-pass only. kill raises
// SIGKILL (a crash or the kernel's OOM killer: nothing runs after it); throw raises
// sm::Error("injected fault ..."), the path of any ordinary error. The rank is the process's MPI
// rank as the launcher sets it (0 without one); no rank= means every rank.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace sm::fault {

void atFrame(uint64_t frame);
void atWrite(const std::string& path);
// On the read-ahead thread, before the read; `stopped` is the read's stop request.
void atReadAhead(const std::function<bool()>& stopped);
// Asked by the viewer during a range pass: what the fault says the user does now (action=close:
// closes the window, at every pass; action=next-field: presses the next-field key, once).
enum class RangePassInput { None, Close, NextField };
RangePassInput atRangePass();

}  // namespace sm::fault
