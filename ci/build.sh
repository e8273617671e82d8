#!/usr/bin/env bash
# Configures and builds shellmarch (Release) in build/. Idempotent; reuses an existing build.
#   ci/build.sh [TARGET...]   builds the TARGETs only (ci/demo.sh: shellmarch), else everything
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${SHELLMARCH_JOBS:-$(nproc)}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHELLMARCH_BUILD_TESTS=ON >/dev/null
cmake --build build -j "$jobs" ${1:+--target "$@"}
