#!/usr/bin/env bash
# The README's first command: installs what the build needs, builds the shellmarch program only
# (ci/test.sh installs and builds the rest: tests, fuzzers, benchmarks), generates the built-in demo
# data set (a CFD-like capsule mesh with all four element types, split into non-convex clusters) and
# renders it to demo/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh --build-only
bash ci/build.sh shellmarch shellmarch_python  # the program, and `import shellmarch` (build/python)
export MESA_SHADER_CACHE_DIR=${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}
mkdir -p demo
if [ ! -f demo/capsule.pvtu ]; then
  ./build/bin/shellmarch generate --body capsule --elements 300000 --clusters 8 --steps 4 --hex-block \
    --out demo/capsule.pvtu
fi
# The bow shock, shock layer and wake of the capsule (the "density" field), looking from upstream.
./build/bin/shellmarch render demo/capsule.pvtu --field density --size 768x576 --eye -6,-9,4.5 --at 2.5,0,0 \
  --fovy 32 --colormap inferno --range 1.5,6 --opacity-scale 2 --legend --out demo/demo.png --stats
echo "demo: wrote $PWD/demo/demo.png"
