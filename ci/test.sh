#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, and runs every test with the Khronos
# validation layer on (GPU tests fail on any validation message).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
# Each step's wall, user and system seconds go to build/ci-times.txt (docs/RELIABILITY.md reports
# the CI's time from it).
mkdir -p build
: >build/ci-times.txt
timed() {
  local TIMEFORMAT="$1 %R %U %S"
  shift
  { time "$@" 2>&3; } 3>&2 2>>build/ci-times.txt
}
timed build bash ci/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Tests set SHELLMARCH_VALIDATION and their own Mesa shader cache through ctest properties.
timed tests ctest --test-dir build --output-on-failure -j "${SHELLMARCH_TEST_JOBS:-2}" \
  --output-junit "$PWD/build/ctest.xml" "$@"
# Bad input and faults (docs/RELIABILITY.md): every loader fuzzed for a bounded time, then the unit
# and MPI tests under AddressSanitizer and UndefinedBehaviorSanitizer. On full runs only (no ctest
# arguments); SHELLMARCH_SKIP_RELIABILITY=1 leaves them out.
if [ $# -eq 0 ] && [ "${SHELLMARCH_SKIP_RELIABILITY:-0}" != 1 ]; then
  timed fuzz bash ci/fuzz.sh
  timed sanitize bash ci/sanitize.sh
fi
