#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan/) of the unit and MPI tests, run
# with ctest. Any sanitizer report fails the test that made it (-fno-sanitize-recover=all; ASan
# aborts). Leaks are checked, except inside the Vulkan driver, the Vulkan loader and validation
# layer, and MPI's own libraries (ci/lsan.supp): those allocate for the process's lifetime and
# never free, and are not ours to fix.
#
#   ci/sanitize.sh              the CI set: every `unit` test and the MPI tests (see below)
#   ci/sanitize.sh -L gpu       any ctest arguments instead
#
# Writes build-asan/sanitize.xml (JUnit) and build-asan/sanitize-times.txt (wall, user and system
# seconds of the build and the tests) for ci/reliability-report.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${SHELLMARCH_JOBS:-$(nproc)}
build=${SHELLMARCH_ASAN_BUILD:-build-asan}
mkdir -p "$build"
times=$build/sanitize-times.txt
: >"$times"
# timed NAME CMD...: runs CMD and appends "NAME wall user system" (seconds) to $times.
timed() {
  local TIMEFORMAT="$1 %R %U %S"
  shift
  { time "$@" 2>&3; } 3>&2 2>>"$times"
}

# -O1: the sanitizers' own guidance; Debug keeps assertions (SM_DCHECK) on as well.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="-O1" \
  -DCMAKE_C_FLAGS="-O1" -DSHELLMARCH_SANITIZE=address,undefined -DSHELLMARCH_BUILD_TESTS=ON >/dev/null
# Only what the chosen tests run; the GPU image tests run in the normal build only.
timed build cmake --build "$build" -j "$jobs" --target test_mesh test_io test_partition \
  test_prep test_gen test_ref test_compositor_unit test_reliability test_compositor_mpi shellmarch

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/ci/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# The CI set: every unit test; the MPI tests through the command-line tool (a rank killed or
# failing mid-frame, a corrupt piece on one rank) and the compositor under mpiexec on 2 ranks, which
# exercises every MPI path (exchange, gather, abort) at a quarter of the cost of all four rank
# counts; 1, 3 and 4 ranks run in the normal build.
args=("$@")
[ ${#args[@]} -gt 0 ] ||
  args=(-L 'unit|mpi' -E 'CompositorMpi\.(1|3|4)ranks')
set +e
timed tests ctest --test-dir "$build" --output-on-failure -j "${SHELLMARCH_TEST_JOBS:-2}" \
  --output-junit "$(cd "$build" && pwd)/sanitize.xml" "${args[@]}"
status=$?
set -e
cat "$times"
exit $status
