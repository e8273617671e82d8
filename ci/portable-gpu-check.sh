#!/usr/bin/env bash
# On a machine with a GPU and no Debian packages: the bundle of ci/portable-bundle.sh runs the GPU
# test cases (validation layer on) and `bench render` without the VTK peer, logs under OUT.
#
#   ci/portable-gpu-check.sh BUNDLE_DIR OUT [MESH] [SIZES]
#
# Run from a source tree; the test meshes of ../shared are read from $SHELLMARCH_SHARED_DIR
# (default: ../shared).
set -uo pipefail
b=$1 out=$2 mesh=${3:-demo/capsule.pvtu} sizes=${4:-512,1024}
run=$b/run
mkdir -p "$out"
nvidia-smi > "$out/nvidia-smi.txt" 2>&1
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$icd" ]; then export VK_DRIVER_FILES=$icd; fi
"$run" vulkaninfo --summary > "$out/vulkaninfo.txt" 2>&1
"$run" vulkaninfo 2>/dev/null | grep -E "VK_KHR_(ray_query|acceleration_structure|ray_tracing)" \
  >> "$out/vulkaninfo.txt"

echo "== bench render (no VTK) on $sizes"
timeout 300 "$run" shellmarch bench render --mesh "$mesh" --sizes "$sizes" --runs 5 --no-vtk \
  --pair-rounds 0 --coarser 2,4,5 --work-dir /tmp/bench --json "$out/gpu-render.json" \
  > "$out/bench.log" 2>&1
echo "bench rc=$?"
grep -E "^\| (512|1024|2048)" "$out/bench.log" | head -40

echo "== render --stats"
"$run" shellmarch render "$mesh" --field density --size 768x576 --eye -6,-9,4.5 --at 2.5,0,0 \
  --fovy 32 --colormap inferno --range 1.5,6 --opacity-scale 2 --out "$out/demo.png" --stats \
  > "$out/render.log" 2>&1
echo "render rc=$?"; tail -12 "$out/render.log"

echo "== GPU test cases, validation layer on"
export SHELLMARCH_VALIDATION=1 SHELLMARCH_SHARED_DIR=${SHELLMARCH_SHARED_DIR:-$(realpath ../shared)}
export SHELLMARCH_TEST_OUT=/tmp/shellmarch-test-out
while read -r bin filter; do
  timeout 240 "$run" "$bin" --gtest_filter="$filter" > "$out/$bin.log" 2>&1
  echo "$bin rc=$? $(grep -E '^\[  (PASSED|FAILED)  \]' "$out/$bin.log" | tr '\n' ' ')"
  grep -E '^\[  FAILED  \]' "$out/$bin.log" | head -20
done < "$b/gpu-tests.txt"

if command -v mpiexec > /dev/null; then
  echo "== compositor under mpiexec (the machine's Open MPI), validation layer on"
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  for n in 1 2 3 4; do
    timeout 240 mpiexec -n "$n" --oversubscribe "$run" test_compositor_mpi --gtest_color=no \
      --gtest_filter='CompositorMpi.*' > "$out/test_compositor_mpi_$n.log" 2>&1
    echo "test_compositor_mpi $n ranks rc=$? $(grep -E '^\[  (PASSED|FAILED)  \]' \
      "$out/test_compositor_mpi_$n.log" | tr '\n' ' ')"
  done
fi
