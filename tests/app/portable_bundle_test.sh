#!/usr/bin/env bash
# ci/portable-bundle.sh packs a build that runs from the bundle: with the machine's glibc and with
# the packed one (forced), the packed binary renders the same image as the build tree's, and the
# packed validation layer loads; ci/gpu-check.sh runs from it end to end (--small).
set -uo pipefail
src=$1 build=$2 sm=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fails=0
check() {  # check "what" command...
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fails=$((fails + 1)); fi
}
bash "$src/ci/portable-bundle.sh" "$build" "$work/b.tar" > pack.log 2>&1 || { cat pack.log; exit 1; }
mkdir x && tar -C x -xf b.tar || exit 1
run=$work/x/shellmarch/run
"$sm" generate --analytic cube-tets6 --cube-n 3 --out cube.pvtu > /dev/null || exit 1
opts=(--field linear --size 48x40 --view iso)
"$sm" render cube.pvtu "${opts[@]}" --out tree.png > /dev/null || exit 1
check "packed binary with the machine's glibc renders" "$run" shellmarch render cube.pvtu "${opts[@]}" --out system.png
check "packed binary with the packed glibc renders" env SHELLMARCH_PORTABLE_PACKED=1 "$run" shellmarch render \
  cube.pvtu "${opts[@]}" --out packed.png
check "same image (machine's glibc)" cmp -s tree.png system.png
check "same image (packed glibc)" cmp -s tree.png packed.png
SHELLMARCH_PORTABLE_PACKED=1 LD_DEBUG=libs "$run" shellmarch --help > /dev/null 2> ld.log
check "the packed glibc is the one loaded" grep -q "init: $work/x/shellmarch/glibc/libc.so.6" ld.log
SHELLMARCH_PORTABLE_PACKED=1 LD_DEBUG=libs "$run" shellmarch --help > /dev/null 2> ld-cxx.log
check "the packed C++ runtime is the one loaded" grep -q "init: $work/x/shellmarch/cxx/libstdc++.so.6" ld-cxx.log
check "the validation layer is packed" test -f x/shellmarch/lib/libVkLayer_khronos_validation.so
check "the packed validation layer loads" env SHELLMARCH_VALIDATION=1 SHELLMARCH_PORTABLE_PACKED=1 "$run" test_vk \
  --gtest_filter=Vk.ValidationIsOnInTests
# Open MPI: the machine's when its loader finds libmpi.so.40 (here in ldconfig's cache), also
# from LD_LIBRARY_PATH as `module load` sets it; the packed one when forced.
sysmpi=$( (ldconfig -p || /sbin/ldconfig -p) 2>/dev/null | awk '$1 == "libmpi.so.40" { print $NF; exit }')
LD_DEBUG=libs "$run" shellmarch --help > /dev/null 2> ld-mpi.log
check "the machine's Open MPI is used" grep -q "init: $sysmpi" ld-mpi.log
SHELLMARCH_PORTABLE_PACKED=1 LD_DEBUG=libs "$run" shellmarch --help > /dev/null 2> ld-mpi-packed.log
check "the packed Open MPI is used when forced" grep -q "init: $work/x/shellmarch/mpi/libmpi.so.40" \
  ld-mpi-packed.log
mkdir -p module/lib && cp -L "$sysmpi" "$(dirname "$sysmpi")"/libopen-{pal,rte}.so.40 module/lib/
LD_LIBRARY_PATH=$work/module/lib LD_DEBUG=libs "$run" shellmarch --help > /dev/null 2> ld-mpi-module.log
check "an Open MPI in LD_LIBRARY_PATH (module load) is used" \
  grep -q "init: $work/module/lib/libmpi.so.40" ld-mpi-module.log
check "no C++ MPI bindings are needed" bash -c "! grep -q libmpi_cxx ld-mpi.log"
check "the GPU cases are listed for gpu-check.sh" grep -q "^test_render .*Slab.TetGrid" x/shellmarch/gpu-tests.txt
# The one prepared GPU check, end to end on lavapipe with the bundle just made.
bash "$src/ci/gpu-check.sh" x/shellmarch gpu-check --small > gpu-check.log 2>&1
check "ci/gpu-check.sh --small runs to its end" grep -q "gpu-check: done" gpu-check.log
for step in "bench tracers (demo)" "bench tracers (big)" "test_render" "test_vk" "compositor sweep"; do
  check "gpu-check: $step exits 0" grep -qF "$step rc=0" gpu-check.log
done
check "gpu-check: both tracers' frames, the same image" grep -q "| pipeline | .*same image" gpu-check/summary.md
[ "$fails" -eq 0 ] || { cat gpu-check.log; echo "$fails check(s) failed"; exit 1; }
rm -rf b.tar x module  # 300 MB; kept when a check failed
