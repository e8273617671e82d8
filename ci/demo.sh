#!/usr/bin/env bash
# The README's first command: installs everything, builds, generates the built-in demo data set (a
# CFD-like capsule mesh with all four element types, split into non-convex clusters) and renders it
# to demo/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
bash ci/build.sh
export MESA_SHADER_CACHE_DIR=${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}
mkdir -p demo
if [ ! -f demo/capsule.pvtu ]; then
  ./build/src/app/shellmarch generate --body capsule --elements 300000 --clusters 8 --steps 4 --hex-block \
    --out demo/capsule.pvtu
fi
./build/src/app/shellmarch render demo/capsule.pvtu --field vortex --size 768x576 --view iso \
  --colormap cool-to-warm --out demo/demo.png --stats
echo "demo: wrote $PWD/demo/demo.png"
