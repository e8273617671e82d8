#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan/) of the unit and MPI tests, run
# with ctest. Any sanitizer report fails the test that made it (-fno-sanitize-recover=all; ASan
# aborts). Leaks are checked in every test but the MPI ones (see below); ci/lsan.supp suppresses
# third-party libraries' own lifetime allocations, by library name only. Sanitizer builds unload no
# library (src/common/keep_modules_loaded.cpp), so the Vulkan layer's allocations keep its name.
#
#   ci/sanitize.sh              the CI set: the libraries' `unit` tests and the MPI tests (see below)
#   ci/sanitize.sh --all        the same with the command-line tool, the viewer and their tests
#   ci/sanitize.sh [--all] -L gpu   any ctest arguments instead (leak checking on)
#
# Writes build-asan/sanitize-{unit,mpi}.xml (JUnit) and build-asan/sanitize-times.txt (wall, user
# and system seconds of the build and each test run) for ci/reliability-report.sh.
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
# Only what the chosen tests run; the GPU image tests run in the normal build only. The CI set is
# the libraries, where untrusted bytes are parsed and fragments exchanged; the command-line tool and
# the viewer (--all) double the build's time and their error tests' (CI's 90-minute limit), so CI
# leaves them to the normal build and the fuzzers, and `--all` runs them under the sanitizers.
all=0
if [ "${1:-}" = --all ]; then all=1; shift; fi
targets=(test_mesh test_io test_partition test_prep test_gen test_ref test_compositor_unit
  test_reliability test_compositor_mpi test_shader_cache test_formats test_common)
skip=()  # tests of targets this set does not build
if [ $all = 1 ]; then
  targets+=(test_viewer test_viewer_unit test_app shellmarch)
else
  skip=(-E '^(app|ViewerHeadless|ViewerTests)[.]')
fi
timed build cmake --build "$build" -j "$jobs" --target "${targets[@]}"

# intercept_tls_get_addr=0: GCC 12's sanitizer runtime (fixed from GCC 14 and LLVM 17) takes a
# dynamic TLS block that happens to start 16 bytes into a page for a pre-2.25 glibc block with a
# header, and records the two words before it, heap garbage here, as the block's address and
# size; LeakSanitizer's tracer then crashes scanning that range at exit ("Tracer caught signal
# 11" in ScanRangeForPointers; google/sanitizers#1322). Lavapipe's LLVM and the validation layer
# have dynamic TLS, so any Vulkan command could meet it, by where malloc put the block: in CI it
# hit app.cli-errors's --k command in 4 full runs of 7. Off, dynamic TLS is not scanned for roots;
# no test reports a leak for it.
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:intercept_tls_get_addr=0}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/ci/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
junit=$(cd "$build" && pwd)
ctest=(ctest --test-dir "$build" --output-on-failure -j "${SHELLMARCH_TEST_JOBS:-2}")
if [ $# -gt 0 ]; then
  timed tests env ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=1" "${ctest[@]}" "$@"
  exit
fi
# The CI set. Every unit test built, with leak checking. Then these MPI tests (the others, GPU
# renders under mpiexec, run in the normal build only): with --all the fault tests through the
# command-line tool (a rank killed or failing mid-frame, a corrupt piece on one rank), and the
# compositor under mpiexec on 2 ranks, which takes every MPI path (exchange, gather, abort) at a
# quarter of the cost of all four rank counts (1, 3 and 4 ranks run in the normal build). Open MPI
# keeps allocations for the process's life, some made through libc calls that the fast unwinder
# cannot walk out of (no Open MPI frame then names them for a suppression), and the slow unwinder
# makes these tests time out: they run with detect_leaks=0 and every other check on.
set +e
timed unit env ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=1" "${ctest[@]}" -L unit "${skip[@]}" \
  --output-junit "$junit/sanitize-unit.xml"
unit=$?
timed mpi env ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" "${ctest[@]}" -L mpi \
  -R "^($([ $all = 1 ] && echo 'Reliability|')CompositorMpi)[.]" -E 'CompositorMpi\.(1|3|4)ranks' \
  --output-junit "$junit/sanitize-mpi.xml"
mpi=$?
set -e
cat "$times"
[ $unit -eq 0 ] && [ $mpi -eq 0 ]
