#!/usr/bin/env bash
# Fault tests through the command-line tool (tests/reliability/CMakeLists.txt registers each case;
# docs/RELIABILITY.md describes them). Usage:
#   faults.sh CASE SHELLMARCH MPIEXEC WORK_DIR
# CASE is one of: data, kill_rank, throw_rank, corrupt_piece, same_error, png_kill, cache_write, cache_corrupt,
# oom_scene, oom_lists_fixed, oom_lists_two_pass, overflow. `data` generates the mesh the others
# use (a ctest fixture). Each case prints what it checked and the time the failing run took; a
# hang is caught by `timeout` (exit status 124), never waited out.
set -u
case=$1 shellmarch=$2 mpiexec=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
data=$work/data/cap.pvtu
dir=$work/$case
limit=${SHELLMARCH_FAULT_TIMEOUT:-240}

# The verdict also goes to $dir/result.txt, for ci/reliability_report.py (ctest keeps only the
# start of a passing test's output).
fail() {
  echo "faults.sh $case: FAILED: $*" | tee "$dir/result.txt"
  exit 1
}
pass() {
  echo "faults.sh $case: passed${1:+ ($1)}" | tee "$dir/result.txt"
  exit 0
}

# after_fault NAME: seconds from the injected fault (the time it logged) to the end of run NAME;
# nothing when no fault was logged.
after_fault() {
  local at
  at=$(sed -n 's/^shellmarch: fault injection: .* at \([0-9.]*\) s (epoch)$/\1/p' "$dir/$1.log" | head -1)
  [ -z "$at" ] || python3 -c "print(f'{$ended - $at:.2f}')"
}

# run NAME CMD...: runs with a timeout, stdout+stderr to $dir/NAME.log; sets status and seconds.
run() {
  local name=$1
  shift
  local t0
  t0=$(date +%s%N)
  timeout -k 10 "$limit" "$@" >"$dir/$name.log" 2>&1
  status=$?
  ended=$(date +%s.%N)
  local ms=$((($(date +%s%N) - t0) / 1000000))
  seconds=$((ms / 1000)).$(printf %03d $((ms % 1000)))
  echo "--- $name: exit status $status after ${seconds}s: $*"
  cat "$dir/$name.log"
  # timeout's status is 124, or 137 where it had to kill: tell a hang by the time it took.
  [ $status -ne 124 ] && [ $((ms / 1000)) -lt "$limit" ] || fail "$name did not end within ${limit}s (a hang)"
}

# ended_after_fault NAME: passes when every rank of run NAME ended within a minute of the logged
# fault (ending is mpiexec's reaction to a dead process; a minute allows for a loaded machine).
ended_after_fault() {
  local late
  late=$(after_fault "$1")
  [ -n "$late" ] || fail "no line says the fault was injected"
  python3 -c "import sys; sys.exit(0 if $late < 60 else 1)" || fail "ranks ended ${late}s after the fault"
  pass "all ranks ended ${late}s after the fault"
}

# frames_after_fault_absent: frames 1 and 2 (rendered after a fault in frame 1) must not exist,
# and every PNG under its final name must be whole.
frames_after_fault_absent() {
  python3 "$here/check_png.py" "$dir"/f_*.png || fail "a PNG under its final name is incomplete"
  [ ! -e "$dir/f_0001.png" ] && [ ! -e "$dir/f_0002.png" ] || fail "a frame after the fault exists"
}

expect_in() {  # expect_in NAME TEXT: the run's output holds TEXT
  grep -qF -- "$2" "$dir/$1.log" || fail "'$2' is not in the output of $1"
}

mpi3=("$mpiexec" -n 3 --oversubscribe "$shellmarch")  # shellmarch on 3 ranks
render_args=(render "$data" --field vortex --size 48x48)
big_args=(render "$data" --field vortex)  # --size follows

if [ "$case" = data ]; then
  rm -rf "$work" && mkdir -p "$work/data"
  dir=$work/data
  run generate "$shellmarch" generate --body capsule --elements 5000 --clusters 3 --steps 3 \
    --out "$data"
  [ $status -eq 0 ] || fail "generate failed"
  pass
fi

[ -f "$data" ] || fail "no $data (the Reliability.data fixture must run first)"
rm -rf "$dir" && mkdir -p "$dir"

case $case in
kill_rank)
  # Rank 1 is killed (SIGKILL: nothing of it runs any more) at the start of frame 1 of 3, while
  # ranks 0 and 2 wait for it in that frame's compositing. mpiexec must end them and say why.
  SHELLMARCH_FAULT=at=frame,frame=1,rank=1,action=kill run render \
    "${mpi3[@]}" "${render_args[@]}" --time all --out "$dir/f.png"
  [ $status -ne 0 ] || fail "mpiexec succeeded although rank 1 was killed"
  grep -qiE "signal 9|killed" "$dir/render.log" || fail "the output does not say that a rank was killed"
  [ -f "$dir/f_0000.png" ] || fail "frame 0, complete before the fault, was not written"
  frames_after_fault_absent
  ended_after_fault render
  ;;
throw_rank)
  # An ordinary error on rank 2 in frame 1: every rank ends, with rank 2's message.
  SHELLMARCH_FAULT=at=frame,frame=1,rank=2,action=throw run render \
    "${mpi3[@]}" "${render_args[@]}" --time all --out "$dir/f.png"
  [ $status -ne 0 ] || fail "mpiexec succeeded although rank 2 failed"
  expect_in render "rank 2 of 3 failed: injected fault on rank 2 in frame 1"
  frames_after_fault_absent
  ended_after_fault render
  ;;
corrupt_piece)
  # Piece 2's data is cut short (its header, which every rank reads to share pieces out, stays
  # whole): only the rank that reads it fails, and that must end every rank with the file's name.
  cp -r "$work/data/cap" "$work/data/cap.pvtu" "$dir/"
  piece=$dir/cap/cap_2.vtu
  truncate -s $(($(stat -c %s "$piece") * 3 / 4)) "$piece"
  run render "${mpi3[@]}" render "$dir/cap.pvtu" --field vortex --size 48x48 --out "$dir/a.png"
  [ $status -ne 0 ] || fail "mpiexec succeeded with a corrupt piece"
  grep -qE "rank [0-9] of 3 failed: .*cap_2\.vtu: " "$dir/render.log" ||
    fail "no rank's message names the corrupt piece"
  [ ! -e "$dir/a.png" ] || fail "an image was written"
  pass "all ranks ended ${seconds}s after start"
  ;;
same_error)
  # Every rank fails the same way (a field no piece has; an impossible option, found before MPI
  # starts): one line says so, not one per rank.
  run render "${mpi3[@]}" render "$data" --field nosuch --size 48x48 --out "$dir/a.png"
  [ $status -ne 0 ] || fail "mpiexec succeeded with a missing field"
  n=$(grep -c "failed: .*has no point or cell array 'nosuch'" "$dir/render.log")
  grep -q "rank 0 of 3 failed: .*'nosuch'" "$dir/render.log" || fail "rank 0 did not report"
  # One line, rank 0's; fewer than one per rank allows for a loaded machine slow to end the others.
  [ "$n" -lt 3 ] || fail "$n lines report the missing field (one per rank)"
  run option "${mpi3[@]}" render "$data" --fovy 0 --out "$dir/a.png"
  [ $status -ne 0 ] || fail "mpiexec succeeded with --fovy 0"
  n=$(grep -c "shellmarch: error: --fovy" "$dir/option.log")
  [ "$n" -ge 1 ] && [ "$n" -lt 3 ] || fail "$n lines report --fovy (one should)"
  [ ! -e "$dir/a.png" ] || fail "an image was written"
  pass "$n line(s) for the option, fewer than the ranks for the field"
  ;;
png_kill)
  # The process dies halfway through writing the PNG: the file under its name keeps its old
  # content; only a temporary name holds the partial bytes.
  echo "previous image" >"$dir/a.png"
  SHELLMARCH_FAULT=at=write,match=.png,action=kill run killed \
    "$shellmarch" "${render_args[@]}" --out "$dir/a.png"
  [ $status -eq 137 ] || fail "expected death by SIGKILL (137), got $status"
  [ "$(cat "$dir/a.png")" = "previous image" ] || fail "a.png was changed by the killed write"
  ls "$dir"/a.png.tmp.* >/dev/null 2>&1 || fail "no partial temporary: the fault did not hit the write"
  run again "$shellmarch" "${render_args[@]}" --out "$dir/a.png"
  [ $status -eq 0 ] || fail "rendering again failed"
  python3 "$here/check_png.py" "$dir/a.png" || fail "the new a.png is incomplete"
  pass
  ;;
cache_write)
  # An error while the preparation cache is written: the run fails with the message and the cache
  # folder holds neither a cache nor a temporary.
  SHELLMARCH_FAULT=at=write,match=.smprep,action=throw run render \
    "$shellmarch" "${render_args[@]}" --cache-dir "$dir/cache" --out "$dir/a.png"
  [ $status -eq 1 ] || fail "expected exit status 1, got $status"
  expect_in render "injected fault on rank 0 while writing $dir/cache/"
  [ -z "$(ls -A "$dir/cache")" ] || fail "the cache folder is not empty: $(ls -A "$dir/cache")"
  [ ! -e "$dir/a.png" ] || fail "an image was written"
  pass
  ;;
cache_corrupt)
  # A damaged cache is detected, reported and replaced; the replacement is then used.
  run first "$shellmarch" "${render_args[@]}" --cache-dir "$dir/cache" --out "$dir/a.png"
  [ $status -eq 0 ] || fail "the first render failed"
  cache=$(ls "$dir"/cache/*.smprep)
  [ -f "$cache" ] || fail "no cache written"
  size=$(stat -c %s "$cache")
  printf '\xff\xff\xff\xff' | dd of="$cache" bs=1 seek=$((size / 2)) conv=notrunc status=none
  run damaged "$shellmarch" "${render_args[@]}" --cache-dir "$dir/cache" --out "$dir/b.png" --stats
  [ $status -eq 0 ] || fail "a damaged cache made the render fail"
  expect_in damaged "checksum mismatch; preparing again"
  truncate -s $((size - 100)) "$cache"
  run truncated "$shellmarch" "${render_args[@]}" --cache-dir "$dir/cache" --out "$dir/c.png"
  [ $status -eq 0 ] || fail "a truncated cache made the render fail"
  expect_in truncated "payload size does not match the file size; preparing again"
  run reused "$shellmarch" "${render_args[@]}" --cache-dir "$dir/cache" --out "$dir/d.png" --stats
  [ $status -eq 0 ] || fail "rendering from the rewritten cache failed"
  expect_in reused "(from cache)"
  cmp -s "$dir/a.png" "$dir/d.png" || fail "the image from the cache differs"
  pass
  ;;
oom_scene)
  # Too little device memory for the scene: the message says what it needs and how many ranks
  # would fit; the budget it names is then enough.
  SHELLMARCH_DEVICE_MEMORY_LIMIT=64K run small "$shellmarch" "${render_args[@]}" --out "$dir/a.png"
  [ $status -eq 1 ] || fail "expected exit status 1, got $status"
  expect_in small "out of device memory for the scene"
  grep -qE "what would fit: about [0-9]+ ranks \(mpiexec -n [0-9]+\)" "$dir/small.log" || fail "no rank count suggested"
  [ ! -e "$dir/a.png" ] || fail "an image was written"
  need=$(sed -n 's/.*need about \([0-9.]*\) \([KMG]\)iB.*/\1\2/p' "$dir/small.log" | head -1)
  [ -n "$need" ] || fail "the message gives no size"
  # What it says the scene needs, plus 2 MiB for the compositor's buffers of a small image and
  # 4 MiB for the pre-integrated transfer function of element-exact frames (the default).
  budget=$(python3 -c "import sys; v='$need'; u={'K':1<<10,'M':1<<20,'G':1<<30}[v[-1]]; print(int(float(v[:-1])*u) + (6<<20))")
  SHELLMARCH_DEVICE_MEMORY_LIMIT=$budget run enough "$shellmarch" "${render_args[@]}" --out "$dir/a.png"
  [ $status -eq 0 ] || fail "the scene's stated need ($need + 6 MiB) was not enough"
  pass "needs about $need"
  ;;
oom_lists_fixed)
  # Fixed lists of K = 16 slots on 512x512 pixels (100 MiB) beside a scene of 0.2 MiB and the
  # 4 MiB pre-integrated transfer function (element-exact frames, the default) in a 28 MiB budget:
  # the message suggests a K and a size that fit, and both do.
  args=("${big_args[@]}" --lists drop)
  SHELLMARCH_DEVICE_MEMORY_LIMIT=28M run small "$shellmarch" "${args[@]}" --size 512x512 --k 16 \
    --out "$dir/a.png"
  [ $status -eq 1 ] || fail "expected exit status 1, got $status"
  expect_in small "out of device memory for fragment lists"
  k=$(sed -n 's/.*what would fit: --k \([0-9]*\).*/\1/p' "$dir/small.log")
  size=$(sed -n 's/.*--size \([0-9]*x[0-9]*\).*/\1/p' "$dir/small.log" | tail -1)
  [ -n "$k" ] && [ -n "$size" ] || fail "no --k and --size suggested"
  SHELLMARCH_DEVICE_MEMORY_LIMIT=28M run fit_k "$shellmarch" "${args[@]}" --size 512x512 --k "$k" \
    --out "$dir/k.png"
  [ $status -eq 0 ] || fail "the suggested --k $k does not fit"
  SHELLMARCH_DEVICE_MEMORY_LIMIT=28M run fit_size "$shellmarch" "${args[@]}" --k 16 --size "$size" \
    --out "$dir/s.png"
  [ $status -eq 0 ] || fail "the suggested --size $size does not fit"
  pass "suggested --k $k, --size $size"
  ;;
oom_lists_two_pass)
  # Two-pass lists on 512x512 pixels need about 16 MiB beside the scene; 14 MiB hold the
  # per-pixel buffers but not the segments and fragments behind them. The suggested size fits.
  SHELLMARCH_DEVICE_MEMORY_LIMIT=14M run small "$shellmarch" "${big_args[@]}" --size 512x512 \
    --out "$dir/a.png"
  [ $status -eq 1 ] || fail "expected exit status 1, got $status"
  expect_in small "out of device memory for fragment lists"
  size=$(sed -n 's/.*what would fit: .*--size \([0-9]*x[0-9]*\).*/\1/p' "$dir/small.log")
  [ -n "$size" ] || fail "no --size suggested"
  SHELLMARCH_DEVICE_MEMORY_LIMIT=14M run fit_size "$shellmarch" "${big_args[@]}" --size "$size" \
    --out "$dir/s.png"
  [ $status -eq 0 ] || fail "the suggested --size $size does not fit"
  pass "suggested --size $size"
  ;;
overflow)
  # One slot per pixel where rays cross the capsule's hollow twice: the overflow is counted in
  # --stats and the JSON, and a warning says the image is approximate. Exact lists never warn.
  run fixed "$shellmarch" "${render_args[@]}" --lists drop --k 1 --stats \
    --stats-json "$dir/fixed.json" --out "$dir/a.png"
  [ $status -eq 0 ] || fail "the render failed"
  expect_in fixed "fixed-length fragment lists (--k 1) overflowed"
  n=$(python3 -c "import json; print(json.load(open('$dir/fixed.json'))['fragment_overflow'])")
  [ "$n" -gt 0 ] || fail "fragment_overflow is $n in the JSON"
  grep -qE "overflow [1-9][0-9]*;" "$dir/fixed.log" || fail "--stats does not show the overflow"
  # Without --stats the warning is still given: an approximate image must never be silent.
  run quiet "$shellmarch" "${render_args[@]}" --lists drop --k 1 --out "$dir/q.png"
  [ $status -eq 0 ] || fail "the render without --stats failed"
  expect_in quiet "fixed-length fragment lists (--k 1) overflowed"
  run exact "$shellmarch" "${render_args[@]}" --stats --stats-json "$dir/exact.json" --out "$dir/b.png"
  [ $status -eq 0 ] || fail "the two-pass render failed"
  grep -q "overflowed" "$dir/exact.log" && fail "two-pass lists warned of overflow"
  n=$(python3 -c "import json; print(json.load(open('$dir/exact.json'))['fragment_overflow'])")
  [ "$n" -eq 0 ] || fail "two-pass lists report an overflow of $n"
  pass
  ;;
*)
  fail "unknown case"
  ;;
esac
