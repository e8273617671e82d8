// `shellmarch view`: the interactive viewer. Every rank renders every frame; rank 0 owns the
// window, reads input (window and --script), and broadcasts the frame's state before rendering.
#pragma once

#include <string>

#include "comm/reductions.h"
#include "pipeline/render_options.h"

namespace sm::view {

struct ViewOptions {
  int frames = 0;            // > 0: render this many frames, then exit
  std::string script;        // input to replay (see script.h)
  std::string screenshot;    // the last frame goes here at exit; also names the s key's PNGs
  bool printCamera = false;  // one JSON line on stdout at exit: camera, settings, render args
  std::string saveCamera;    // at exit, the camera as a ParaView camera file (.pvcc) here
  bool headless = false;     // no window: VK_EXT_headless_surface, input from --script only
  bool overlay = true;
  bool play = false;  // start playing: a step a frame (space pauses)
  double fps = 0;     // > 0: while playing, at most this many steps a second
  // > 1: frames whose input moves the camera render at 1/interactiveScale of the window's size
  // (shown enlarged), so that dragging keeps up; the frames after, and screenshots, at full size.
  int interactiveScale = 2;
};

void runView(const app::RenderJob& job, const ViewOptions& options, comm::Communicator& comm);

}  // namespace sm::view
