// shellmarch view MESH [the data, camera and transfer-function options of render]
//                      [--frames K] [--script FILE] [--screenshot FILE] [--print-camera]
//                      [--save-camera FILE.pvcc]
//                      [--headless] [--play] [--fps F] [--no-overlay]
// An interactive window on rank 0 (GLFW, presented through a Vulkan swapchain); every rank renders
// every frame. Controls: `shellmarch view --help-controls`; script format: `--help-script`.
#include <cstdio>
#include <memory>

#include "cli/cli_checks.h"
#include "cli/commands.h"
#include "cli/run_parallel.h"
#include "cli/scene_options.h"
#include "common/error.h"
#include "common/file_util.h"
#include "viewer/input.h"
#include "viewer/script.h"
#include "viewer/viewer.h"

namespace sm::app {

void registerView(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view", "Interactive viewer (GLFW window on rank 0; data-parallel under mpirun)");
  auto job = std::make_shared<RenderJob>();
  auto raw = std::make_shared<SceneOptionText>();
  auto opts = std::make_shared<view::ViewOptions>();
  addSceneOptions(cmd, *job, *raw, "Time step index to start at (default 0)");
  cmd->add_option("--frames", opts->frames, "Render this many frames, then exit");
  cmd->add_option("--script", opts->script,
                  "Replay input from this file, or '-' for standard input (format: --help-script)");
  cmd->add_option(
         "--screenshot", opts->screenshot,
         "Write the last frame here at exit (PNG, no overlay); the s key writes FILE_NNNN.png")
      ->check(CLI::Validator(
          [](std::string& path) {
            return fileExtension(path) == ".png" ? std::string()
                                                 : "'" + path + "' must end in .png";
          },
          "FILE.png"))
      ->check(writableFile());
  cmd->add_flag(
      "--print-camera", opts->printCamera,
      "At exit, print the final camera and settings as one JSON line, with the render arguments");
  cmd->add_option("--save-camera", opts->saveCamera,
                  "At exit, write the final camera as a ParaView camera file (.pvcc: ParaView "
                  "loads it in Adjust Camera > Configurations; --camera reads it)")
      ->check(CLI::Validator(
          [](std::string& path) {
            return fileExtension(path) == ".pvcc" ? std::string()
                                                  : "'" + path + "' must end in .pvcc";
          },
          "FILE.pvcc"))
      ->check(writableFile());
  cmd->add_flag("--headless", opts->headless,
                "No window: present to a headless surface (needs --frames or --script)");
  auto noOverlay = std::make_shared<bool>(false);
  cmd->add_flag("--no-overlay", *noOverlay, "Start with the overlay hidden (o toggles it)");
  cmd->add_flag("--play", opts->play,
                "Start playing the time steps, one a frame, the next read ahead (space pauses)");
  cmd->add_option("--fps", opts->fps,
                  "While playing, show at most this many time steps a second (default: a step a "
                  "frame, as fast as frames come)");
  cmd->add_option("--interactive-scale", opts->interactiveScale,
                  "While the camera moves, render at 1/N of the window's size, shown enlarged "
                  "(default 2; 1: always full size)");
  cmd->add_flag_callback(
      "--help-controls",
      [] {
        std::fputs(view::controlsHelp().c_str(), stdout);
        throw CLI::Success();
      },
      "Print the mouse and key controls and exit");
  cmd->add_flag_callback(
      "--help-script",
      [] {
        std::fputs(view::scriptHelp().c_str(), stdout);
        throw CLI::Success();
      },
      "Print the --script format and exit");
  groupSceneOptions(cmd);
  cmd->callback([cmd, job, raw, opts, noOverlay] {
    applySceneOptions(*raw, *job);
    if (job->transparent)
      throw Error("--background transparent: for render only (a window shows no transparency)");
    // 0 is "no cap" inside; given on the command line it is a mistake like a negative rate.
    if (cmd->count("--fps") && !(opts->fps > 0))
      throw Error("--fps: ", opts->fps, " is not a positive number of steps a second");
    opts->overlay = !*noOverlay;
    runParallel([&](comm::Communicator& comm) { view::runView(*job, *opts, comm); });
  });
}

}  // namespace sm::app
