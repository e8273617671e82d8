#!/usr/bin/env bash
# Runs every benchmark behind docs/BENCHMARKS.md and docs/ACCURACY.md, one after another (they
# must not share the cores with each other: each prints the load average it saw), and leaves the
# printed tables (*.md) and JSON in OUT (default out/bench-results). Meshes, CPU references and
# VTK's outputs are generated once under SHELLMARCH_BENCH_WORK (default out/bench) and reused.
#
#   ci/benchmarks.sh [OUT] [NAME ...]    NAME: prep render first-image accuracy features time compositor
#
# About an hour on 2 cores the first time (the 5-million-element mesh and the converged CPU
# references dominate), 20 minutes after. Needs a build (ci/build.sh) and python3-vtk9 for the peers.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/bench-results}
shift || true
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(prep render first-image accuracy features time compositor)
work=${SHELLMARCH_BENCH_WORK:-out/bench}
sm=build/bin/shellmarch
comp=build/compositor/shellmarch_bench_compositor
mkdir -p "$out" "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export MESA_SHADER_CACHE_DIR=${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}

for name in "${names[@]}"; do
  echo "== $name ($(uptime | sed 's/.*load/load/'))" >&2
  case $name in
  prep)
    # --formats: the same meshes read from CGNS and Exodus II copies, against the .pvtu.
    "$sm" bench prep --elements 1000000,5000000 --runs 3 --formats cgns,exodus --work-dir "$work" \
      --json "$out/prep.json" | tee "$out/prep.md" ;;
  render)
    "$sm" bench render --sizes 512,1024 --runs 3 --vtk-runs 3 --coarser 2,4,5 --work-dir "$work" \
      --json "$out/render.json" | tee "$out/render.md" ;;
  first-image)
    # Start to PNG in fresh processes, cold and warm shader caches, beside VTK's whole process:
    # a 72 k-element capsule at 256x256 and the demo at 768x576.
    mesh=$work/capsule-72000-c4.pvtu
    [ -f "$mesh" ] || "$sm" generate --body capsule --elements 72000 --clusters 4 --out "$mesh"
    "$sm" bench render --mesh "$mesh" --field density --only-first-image --first-image 256x256 \
      --first-image-runs 3 --work-dir "$work/first-image-72k" --json "$out/first-image-72k.json" \
      | tee "$out/first-image-72k.md"
    "$sm" bench render --field density --only-first-image --first-image 768x576 \
      --first-image-runs 3 --work-dir "$work" --json "$out/first-image-demo.json" \
      | tee "$out/first-image-demo.md" ;;
  accuracy)
    "$sm" bench accuracy --size 320x240 --runs 3 --ranks 4 --clusters 32 --work-dir "$work" \
      --json "$out/accuracy.json" --markdown "$out/accuracy.md" --plot "$out/accuracy.png" ;;
  features)
    "$sm" bench features --size 384 --runs 3 --rounds 5 --work-dir "$work" \
      --json "$out/features.json" --markdown "$out/features.md" ;;
  time)
    # The paper's measure: frames per second averaged over 20 time steps, several runs; scalars
    # of the next step are read and uploaded while a frame renders (--no-prefetch: without).
    mesh=$work/capsule-300000-c8-s20-hex.pvtu
    [ -f "$mesh" ] || "$sm" generate --body capsule --elements 300000 --clusters 8 --steps 20 \
      --hex-block --out "$mesh"
    mkdir -p "$work/time"
    : >"$out/time.md"
    for ranks in 1 2; do
      for prefetch in on off; do
        flag=()
        [ $prefetch = on ] || flag=(--no-prefetch)
        mpiexec -n $ranks "$sm" render "$mesh" --field vortex --time all --repeat 3 --size 512x512 \
          --view iso --integration sampled --out "$work/time/frame.png" --stats \
          --stats-json "$out/time-$ranks-$prefetch.json" "${flag[@]}" 2>&1 | grep -E "sequence|scalars:" | sed "s/^/ranks $ranks, prefetch $prefetch: /" \
          | tee -a "$out/time.md"
      done
    done ;;
  compositor)
    "$comp" sweep --max-ranks 8 --sizes 512,1024 --json "$out/compositor.json" | tee "$out/compositor.md"
    "$comp" replay --ranks 72,552 --width 1024 --height 1024 | tee "$out/compositor-replay.md"
    # The same rank counts from real frames: each virtual rank's share of the demo rendered in
    # turn, its fragment counts dumped and replayed through the exchange.
    "$sm" bench counts --ranks 72,552 --sizes 512,1024 --work-dir "$work" \
      --json "$out/compositor-counts.json" --markdown "$out/compositor-counts.md" ;;
  *)
    echo "benchmarks.sh: unknown benchmark '$name'" >&2
    exit 2 ;;
  esac
done
echo "benchmarks: results in $out" >&2
