// shellmarch compare RESULT BASELINE [--tolerance LEVELS] [--max-share FRACTION] [--diff FILE.png]
//                                    [--json FILE]
// An image regression check for CI (app/image_check.h): a table of the differences per channel,
// a difference image, exit status 0 within the tolerance, 1 beyond it, 2 for a command line or
// images it cannot compare (unreadable, of different sizes), as cmp and diff do.
#include <iostream>
#include <memory>

#include "cli/cli_checks.h"
#include "cli/commands.h"
#include "cli/image_check.h"
#include "common/error.h"

namespace sm::app {

void registerCompare(CLI::App& app) {
  auto files = std::make_shared<CheckFiles>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare an image with a baseline (PNG or PFM) for tests in CI: exit status 0 within the "
      "tolerance, 1 beyond it, 2 for images it cannot compare");
  cmd->add_option("result", files->result, "The image to check (.png or .pfm)")->required();
  cmd->add_option("baseline", files->baseline, "The image it must match (.png or .pfm)")
      ->required();
  addToleranceOptions(cmd, files->tolerance);
  cmd->add_option("--diff", files->diff,
                  "Difference image to write (.png; default RESULT.diff.png beside RESULT): "
                  "pixels beyond the tolerance red, within it but different yellow")
      ->check(writableFile());
  cmd->add_option("--json", files->json, "Also write the numbers as JSON to this file")
      ->check(writableFile());
  cmd->callback([files] {
    const ImageCheck check = runImageCheck(*files, std::cout);
    if (!check.passed) throw Error(checkFailure(check, *files));  // exit status 1
  });
}

}  // namespace sm::app
