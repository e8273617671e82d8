#!/usr/bin/env bash
# The one prepared GPU check. On a machine that has the portable bundle (ci/portable-bundle.sh) and
# a GPU driver but no Debian packages, in under 8 minutes on a data-centre GPU:
#   1. the device: nvidia-smi, vulkaninfo, `shellmarch devices` (the tracers it offers);
#   2. the GPU test cases (validation layer on), each tracer the device offers (the harness renders
#      every image with both where both are offered and compares them bit for bit);
#   3. `bench tracers` on the demo capsule at 512², 1024² and 2048²;
#   4. `bench tracers` on a mesh of at least 10 M elements made there (a cube of 6 tetrahedra a
#      cell, 120 a side: 10.4 M) at 1024²;
#   5. the compositor sweep at 1 to 8 ranks (processes on the one GPU, the machine's mpiexec);
# and writes each step's JSON and log, plus summary.md (one Markdown table of the frames and the
# device), into OUT. Every step has its own time limit, so one that hangs costs only its share.
#
#   ci/gpu-check.sh BUNDLE_DIR OUT [--small]
#
# --small proves the script end to end on lavapipe (tests/app/portable_bundle_test.sh runs it): sizes
# 64 and 128, a 30 k-element capsule, a 25 k-element cube, two test cases, ranks 1 to 2. Run from a source tree (the test meshes of ../shared: $SHELLMARCH_SHARED_DIR); the demo is
# demo/capsule.pvtu when there (ci/demo.sh), else generated (gmsh is in the bundle).
set -uo pipefail
b=$(cd "$1" && pwd) out=$2 small=${3:-}
run=$b/run
mkdir -p "$out"
out=$(cd "$out" && pwd)
start=$SECONDS
step() { echo "== [$((SECONDS - start)) s] $*"; }
# budget N: a step's time limit, N seconds or what is left of the whole check's 470 s if less (at
# least 1), so that the check ends inside its 8 minutes with its summary written.
budget() {
  local left=$((470 - (SECONDS - start)))
  if [ "$left" -lt "$1" ]; then echo $((left > 1 ? left : 1)); else echo "$1"; fi
}
if [ "$small" = --small ]; then
  sizes=64,128 cube=16 rounds=2 runs=2 ranks=2 comp_sizes=64 test_limit=900 demo_elements=30000
else
  sizes=512,1024,2048 cube=120 rounds=3 runs=5 ranks=8 comp_sizes=512,1024,2048 test_limit=120
  demo_elements=300000
fi

step "device"
nvidia-smi > "$out/nvidia-smi.txt" 2>&1
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$icd" ]; then export VK_DRIVER_FILES=$icd; fi
# NVIDIA's driver loads glvnd's libraries through the machine's own loader paths: where the machine
# has none, the packed copies are installed system-wide (docs/BENCHMARKS.md, "On a GPU").
if [ -d "$b/glvnd" ] && ! (ldconfig -p 2>/dev/null | grep -q 'libGLX.so.0 '); then
  cp -n "$b"/glvnd/* /usr/lib/x86_64-linux-gnu/ 2>/dev/null && ldconfig 2>/dev/null
  echo "installed glvnd's libraries from the bundle"
fi
"$run" vulkaninfo --summary > "$out/vulkaninfo.txt" 2>&1
"$run" vulkaninfo 2>/dev/null | grep -E "VK_KHR_(ray_query|acceleration_structure|ray_tracing)|subgroupSupportedStages" -A0 \
  >> "$out/vulkaninfo.txt"
timeout 60 "$run" shellmarch devices > "$out/devices.txt" 2>&1
timeout 60 "$run" shellmarch devices --json > "$out/devices.json" 2>> "$out/devices.txt"
cat "$out/devices.txt"

step "demo mesh"
demo=demo/capsule.pvtu
if [ ! -f "$demo" ] || [ "$small" = --small ]; then
  demo=$out/demo/capsule.pvtu
  timeout "$(budget 240)" "$run" shellmarch generate --body capsule --elements "$demo_elements" --clusters 8 --steps 4 \
    --hex-block --out "$demo" > "$out/generate.log" 2>&1
  echo "generate rc=$? $(tail -1 "$out/generate.log")"
fi

step "bench tracers: demo at $sizes"
timeout "$(budget 200)" "$run" shellmarch bench tracers --mesh "$demo" --field vortex --sizes "$sizes" \
  --rounds "$rounds" --runs "$runs" --json "$out/tracers-demo.json" --markdown "$out/tracers-demo.md" \
  > "$out/tracers-demo.log" 2>&1
echo "bench tracers (demo) rc=$?"; cat "$out/tracers-demo.md" 2>/dev/null || tail -5 "$out/tracers-demo.log"

big_size=1024
[ "$small" = --small ] && big_size=128
step "bench tracers: cube-tets6 $cube^3 at $big_size²"
timeout "$(budget 150)" "$run" shellmarch bench tracers --analytic cube-tets6 --cube-n "$cube" --field vortex \
  --sizes "$big_size" --rounds "$rounds" --runs "$runs" --json "$out/tracers-big.json" \
  --markdown "$out/tracers-big.md" > "$out/tracers-big.log" 2>&1
echo "bench tracers (big) rc=$?"; cat "$out/tracers-big.md" 2>/dev/null || tail -5 "$out/tracers-big.log"

step "GPU test cases, validation layer on"
export SHELLMARCH_VALIDATION=1 SHELLMARCH_SHARED_DIR=${SHELLMARCH_SHARED_DIR:-$(realpath ../shared)}
export SHELLMARCH_TEST_OUT=/tmp/shellmarch-test-out
while read -r bin filter; do
  if [ "$small" = --small ]; then  # lavapipe runs them all in ctest: a sample proves the path
    case $bin in
      test_render) filter='TracerChoice.AutoTakes*' ;;
      test_vk) ;;
      *) continue ;;
    esac
  fi
  timeout "$(budget "$test_limit")" "$run" "$bin" --gtest_filter="$filter" --gtest_color=no > "$out/$bin.log" 2>&1
  echo "$bin rc=$? $(grep -E '^\[  (PASSED|FAILED)  \]' "$out/$bin.log" | tr '\n' ' ')"
  grep -E '^\[  FAILED  \]' "$out/$bin.log" | head -20
done < "$b/gpu-tests.txt"
unset SHELLMARCH_VALIDATION

if command -v mpiexec > /dev/null; then
  step "compositor sweep, 1 to $ranks ranks"
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  timeout "$(budget 120)" "$run" shellmarch_bench_compositor sweep --max-ranks "$ranks" --sizes "$comp_sizes" \
    --frames 5 --ownerships interleaved --mpiexec "mpiexec --oversubscribe" \
    --json "$out/compositor.json" > "$out/compositor.log" 2>&1
  echo "compositor sweep rc=$?"; grep -E "^ *[0-9]+ +[0-9]+ " "$out/compositor.log" | head -30
fi

step "summary"
{
  echo "# shellmarch on $(head -1 "$out/devices.txt" 2>/dev/null)"
  echo
  grep -m1 "Driver Version" "$out/nvidia-smi.txt" 2>/dev/null
  echo
  echo "## Demo capsule"
  cat "$out/tracers-demo.md" 2>/dev/null
  echo
  echo "## cube-tets6 $cube^3"
  cat "$out/tracers-big.md" 2>/dev/null
  echo
  echo "## GPU test cases"
  for f in "$out"/test_*.log; do
    [ -f "$f" ] && echo "- $(basename "$f" .log): $(grep -E '^\[  (PASSED|FAILED)  \]' "$f" | tr '\n' ' ')"
  done
} > "$out/summary.md"
cat "$out/summary.md"
echo "gpu-check: done in $((SECONDS - start)) s"
