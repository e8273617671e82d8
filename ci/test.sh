#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, and runs every test with the Khronos
# validation layer on (GPU tests fail on any validation message).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
bash ci/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Tests set SHELLMARCH_VALIDATION and their own Mesa shader cache through ctest properties.
ctest --test-dir build --output-on-failure -j "${SHELLMARCH_TEST_JOBS:-2}" "$@"
