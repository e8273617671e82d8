#!/usr/bin/env bash
# Regenerates docs/RELIABILITY.md: runs the fuzzers (ci/fuzz.sh), the sanitizer build of the unit
# and MPI tests (ci/sanitize.sh) and the fault tests (ctest -L reliability cases in build/), then
# writes what ran, for how long, and what it found.
#
#   ci/reliability-report.sh              everything (about 20 minutes on 2 cores)
#   ci/reliability-report.sh --no-run     only rewrite the document from the last runs' results
#
# SHELLMARCH_FUZZ_SECONDS sets the time per fuzz target (default 30, as in CI).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" != --no-run ]; then
  bash ci/build.sh
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  bash ci/fuzz.sh || true
  bash ci/sanitize.sh || true
  ctest --test-dir build -R '^Reliability\.' --output-junit "$PWD/build/reliability.xml" -j 2 || true
fi
python3 ci/reliability_report.py docs/RELIABILITY.md
echo "reliability-report: wrote docs/RELIABILITY.md"
