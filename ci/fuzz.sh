#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer, coverage
# instrumentation in every library) in build-fuzz/ and runs each for a bounded time, seeded from the
# test fixtures, a cache written by the real writer, and every committed regression input. Fails on
# any crash, sanitizer report, leak, timeout or oversized allocation, and names the input to commit.
#
#   ci/fuzz.sh                 every target, SHELLMARCH_FUZZ_SECONDS (default 30) each
#   ci/fuzz.sh vtu cache       only these targets
#
# Writes build-fuzz/fuzz-summary.tsv (target, seconds, executions, exec/s, corpus, coverage, result)
# and build-fuzz/fuzz-times.txt (wall, user and system seconds of each step) for
# ci/reliability-report.sh. The corpus in build-fuzz/corpus/ grows across local runs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${SHELLMARCH_FUZZ_SECONDS:-30}
jobs=${SHELLMARCH_JOBS:-$(nproc)}
build=${SHELLMARCH_FUZZ_BUILD:-build-fuzz}
shared=${SHELLMARCH_SHARED_DIR:-$root/../shared}
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(vtu pvtu legacy_vtk ugrid cache colormap su2 gmsh cgns exodus)

mkdir -p "$build"
times=$build/fuzz-times.txt
: >"$times"
# timed NAME CMD...: runs CMD and appends "NAME wall user system" (seconds) to $times.
timed() {
  local TIMEFORMAT="$1 %R %U %S"
  shift
  { time "$@" 2>&3; } 3>&2 2>>"$times"
}

start=$(date +%s)
# -O1 keeps the fuzzer fast while the sanitizers see through inlining; _GLIBCXX_ASSERTIONS turns
# out-of-range operator[] on std::vector and std::array into a finding even inside capacity.
flags="-O1 -fsanitize=fuzzer-no-link -D_GLIBCXX_ASSERTIONS"
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" -DSHELLMARCH_SANITIZE=address,undefined \
  -DSHELLMARCH_FUZZ=ON -DSHELLMARCH_BUILD_TESTS=OFF >/dev/null
timed build cmake --build "$build" -j "$jobs" --target fuzzers
built=$(date +%s)

seeds=$build/seeds
rm -rf "$seeds"
python3 tests/fuzz/make_seeds.py "$seeds" "$root" "$shared/data"
for mesh in tests/io/data/mesh_ascii.vtu tests/io/data/weld.pvtu; do
  out=$seeds/cache/$(basename "$mesh" | tr . _)
  mkdir -p "$out"
  "$build/tests/fuzz/fuzz_make_cache_seed" "$mesh" "$out"
done

# The solvers' formats, written by their own libraries (tests/formats writers).
formats=$build/format-files
rm -rf "$formats"
# (libgmsh keeps allocations for the process's life: the seed writer is no fuzz target.)
for f in cgns exodus gmsh; do
  ASAN_OPTIONS=detect_leaks=0 "$build/tests/fuzz/fuzz_make_format_seeds" $f "$formats/$f" >/dev/null
done
for t in cgns exodus su2 gmsh; do mkdir -p "$seeds/$t"; done
find "$formats" -name '*.cgns' -exec cp {} "$seeds/cgns/" \;
find "$formats/exodus" -type f -exec cp {} "$seeds/exodus/" \;
find "$formats" -name '*.su2' -exec cp {} "$seeds/su2/" \;
find "$formats" -name '*.msh' -exec cp {} "$seeds/gmsh/" \;

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:allocator_may_return_null=0}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/ci/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
summary=$build/fuzz-summary.tsv
printf 'target\tseconds\texecutions\texec_per_s\tcorpus\tcoverage\tresult\n' >"$summary"
# fuzz_one TARGET: fuzzes one target, then writes its summary line to $build/fuzz-TARGET.tsv and,
# when it failed, the log's tail and what to do to $build/fuzz-TARGET.failed.
fuzz_one() {
  local t=$1
  local corpus=$build/corpus/$t artifacts=$build/artifacts/$t
  rm -f "$build/fuzz-$t.failed"
  mkdir -p "$corpus" "$artifacts"
  local regressions=tests/fuzz/regressions/$t
  local dirs=("$corpus" "$seeds/$t")
  [ -d "$regressions" ] && dirs+=("$regressions")
  # Keywords of the format, where there is a grammar to speak of (tests/fuzz/dict/).
  local options=()
  [ -f "tests/fuzz/dict/$t.dict" ] && options+=(-dict="tests/fuzz/dict/$t.dict")
  local log=$build/fuzz-$t.log
  echo "fuzz: $t for ${seconds}s"
  # -max_len 64 KiB: every format's structure fits, and larger seeds (can.vtu, post.vtk) are read
  # truncated. -malloc_limit_mb: no input of that size may make a reader allocate 256 MiB at once
  # (the most a 64 KiB zlib stream inflates to is 64 MiB); larger means it believed a size.
  # -timeout: one input taking 30 s is a hang (the limit leaves room for a loaded machine).
  local status=0
  timed "fuzz_$t" "$build/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -max_len=65536 -malloc_limit_mb=256 \
    -rss_limit_mb=2048 -timeout=30 -print_final_stats=1 -artifact_prefix="$artifacts/" \
    "${options[@]}" "${dirs[@]}" >"$log" 2>&1 || status=$?
  local runs rate cov size result=ok
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  size=$(find "$corpus" -type f | wc -l)
  if [ $status -ne 0 ]; then
    result=FAILED
    {
      tail -n 60 "$log"
      echo "fuzz: $t FAILED (status $status); input(s) in $artifacts/:"
      ls -1 "$artifacts"
      echo "fuzz: fix it, then commit the input as tests/fuzz/regressions/$t/<name> (the"
      echo "      regression test replays it through the normal entry point)"
    } >"$build/fuzz-$t.failed"
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$seconds" "${runs:-0}" "${rate:-0}" "$size" \
    "${cov:-0}" "$result" >"$build/fuzz-$t.tsv"
}

# One fuzzer per core at a time: each is single-threaded, so the same fuzzing time per target takes
# a fraction of the wall time.
running=0
for t in "${targets[@]}"; do
  if [ $running -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
wait
failed=()
for t in "${targets[@]}"; do
  cat "$build/fuzz-$t.tsv" >>"$summary"
  if [ -f "$build/fuzz-$t.failed" ]; then
    cat "$build/fuzz-$t.failed"
    failed+=("$t")
  fi
done
end=$(date +%s)
column -t -s $'\t' "$summary"
echo "fuzz: build $((built - start)) s, fuzzing $((end - built)) s, total $((end - start)) s"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: FAILED: ${failed[*]}"
  exit 1
fi
