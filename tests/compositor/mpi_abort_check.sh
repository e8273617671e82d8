#!/usr/bin/env bash
# Runs the test binary under mpiexec with a test that throws on the last rank, and checks that every
# process ended promptly (no rank left waiting in a collective), with a failing status and the
# error message. Usage: mpi_abort_check.sh MPIEXEC RANKS TEST_BINARY MAX_SECONDS
set -u
mpiexec=$1 ranks=$2 binary=$3 limit=$4
last=$((ranks - 1))
start=$(date +%s)
output=$(timeout $((limit * 4)) "$mpiexec" -n "$ranks" --oversubscribe "$binary" \
  --gtest_also_run_disabled_tests --gtest_filter='CompositorMpi.DISABLED_FailureOnOneRankEndsAllRanks' 2>&1)
status=$?
elapsed=$(($(date +%s) - start))
echo "$output"
echo "mpi_abort_check: exit status $status after ${elapsed}s"
fail() { echo "mpi_abort_check: FAILED: $*"; exit 1; }
[ "$status" -eq 0 ] && fail "mpiexec succeeded although rank $last threw"
[ "$status" -eq 124 ] && fail "ranks hung (killed by timeout after $((limit * 4))s)"
grep -q "injected failure on rank $last" <<<"$output" || fail "the error message was not printed"
[ "$elapsed" -le "$limit" ] || fail "took ${elapsed}s, more than ${limit}s"
echo "mpi_abort_check: passed"
