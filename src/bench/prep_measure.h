// One preparation measurement of `shellmarch bench prep`: read a mesh and prepare it as one rank,
// per stage, with the peak resident memory, in a fresh child process.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm::app::bench {

struct PrepMeasureOptions {
  std::string path;
  std::vector<std::string> fields;  // empty: every point array (as `render` reads)
  unsigned threads = 1;             // reader threads; preparation itself runs on one core
};

// The stages' seconds, the counts and the memory of one run (a child process per call).
nlohmann::json measurePrepOnce(const PrepMeasureOptions& options);

// Medians over runs of measurePrepOnce results, with elements/s per stage and for connectivity +
// shell + compaction, the largest peak, and the memory ratio against the prepared size.
nlohmann::json summarisePrepRuns(const std::vector<nlohmann::json>& runs);

// The stages in table order: JSON key and column title.
struct PrepStage {
  const char* key;
  const char* title;
};
const std::vector<PrepStage>& prepStages();

}  // namespace sm::app::bench
