#!/usr/bin/env bash
# Every C++ file git tracks is as .clang-format lays it out (ctest ci.format). Files whose layout is
# data (colour-map tables) or shared with GLSL (shaders/shared, where clang-format would reflow
# macros GLSL must read as written) hold `// clang-format off` themselves, not an exclusion here.
# Usage: ci/check_format.sh [SOURCE_ROOT]   (fix with: git clang-format, or clang-format -i FILE)
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"
format=${CLANG_FORMAT:-clang-format}
command -v "$format" >/dev/null || { echo "check_format: $format is not installed"; exit 1; }
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.hpp')
[ ${#files[@]} -gt 0 ] || { echo "check_format: no C++ files found (not a git checkout?)"; exit 1; }
if ! out=$("$format" --dry-run --Werror "${files[@]}" 2>&1); then
  grep -E '^[^ ].*: (error|warning):' <<<"$out" | cut -d: -f1 | sort | uniq -c |
    awk '{print "check_format: " $2 ": " $1 " place(s) not formatted"}'
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
