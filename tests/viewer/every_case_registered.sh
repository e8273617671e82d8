#!/usr/bin/env bash
# every_case_registered.sh TEST_EXE CASE...: fails naming each case TEST_EXE holds
# (--gtest_list_tests) that is not among the CASEs ctest runs, and each CASE it does not hold.
set -euo pipefail
exe=$1
shift
listed=$("$exe" --gtest_list_tests | awk '/^[^ ]/ { suite = $1 } /^  / { print suite $1 }' | sort)
registered=$(printf '%s\n' "$@" | sort)
status=0
while read -r case; do
  echo "FAIL: $case is in $(basename "$exe") but ctest does not run it (tests/viewer/CMakeLists.txt)"
  status=1
done < <(comm -23 <(echo "$listed") <(echo "$registered") | grep .)
while read -r case; do
  echo "FAIL: ctest runs $case, which $(basename "$exe") does not hold"
  status=1
done < <(comm -13 <(echo "$listed") <(echo "$registered") | grep .)
[ $status -eq 0 ] && echo "$(echo "$listed" | wc -l) cases, every one registered"
exit $status
