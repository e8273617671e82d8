#!/usr/bin/env bash
# Configures and builds shellmarch (Release) in build/. Idempotent; reuses an existing build.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${SHELLMARCH_JOBS:-$(nproc)}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHELLMARCH_BUILD_TESTS=ON >/dev/null
cmake --build build -j "$jobs"
