#!/usr/bin/env bash
# The habits of a well-behaved tool: --version, grouped help with examples, the bash completion
# script from the program's options, the man pages the build wrote, the progress line, and the
# thread budget recorded in --stats-json.
# Usage: etiquette_test.sh SHELLMARCH DOC_DIR WORK
set -uo pipefail
sm=$1 doc=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok: $*"; }

# --version: one line, the project's version, before or after the command.
v=$("$sm" --version) || fail "--version exit status $?"
[[ $v =~ ^shellmarch\ [0-9]+\.[0-9]+\.[0-9]+\ \( ]] && ok "$v" || fail "--version printed '$v'"
[ "$("$sm" render --version)" = "$v" ] || fail "render --version differs from --version"

# render --help: every option in a named group (no CLI11 catch-all "OPTIONS:"), with examples.
help=$("$sm" render --help) || fail "render --help exit status $?"
for group in "Data:" "Camera:" "Transfer function:" "Time:" "Output:" \
  "Parallel and fragment lists:" "Device and caches:" "Examples:"; do
  grep -q "^$group" <<<"$help" || fail "render --help lacks the group '$group'"
done
grep -q "^OPTIONS:" <<<"$help" && fail "render --help has ungrouped options"
view_help=$("$sm" view --help)
grep -q "^Camera:" <<<"$view_help" || fail "view --help is not grouped"

# Completion: written from the options, so every option of render --help completes.
"$sm" completion bash >shellmarch.bash || fail "completion bash exit status $?"
bash -n shellmarch.bash || fail "the completion script is not valid bash"
complete_words() {  # the candidates bash offers for the words given (the last one being typed)
  bash -c 'source shellmarch.bash; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _shellmarch
           printf "%s\n" "${COMPREPLY[@]}"' _ "$@"
}
options=$(grep -oE '^ +--[a-z0-9-]+' <<<"$help" | tr -d ' ' | sort -u)
offered=$(complete_words shellmarch render mesh.vtu -- | sort -u)
missing=$(comm -23 <(echo "$options") <(echo "$offered"))
[ -z "$missing" ] && ok "render completes its $(wc -l <<<"$options") options" ||
  fail "render's options missing from completion: $missing"
[ "$(complete_words shellmarch ren)" = render ] || fail "'ren' does not complete to render"
[ "$(complete_words shellmarch render m.vtu --tracer pi)" = pipeline ] ||
  fail "--tracer values do not complete"
grep -qx -- '+x' <<<"$(complete_words shellmarch render m.vtu --view '')" || fail "--view values"
grep -qx -- viridis <<<"$(complete_words shellmarch render m.vtu --colormap vi)" ||
  fail "--colormap values"
grep -qx -- render <<<"$(complete_words shellmarch bench '')" ||
  fail "bench's subcommands do not complete"
# A flag before the command takes no value: the next word is still the command.
grep -qx -- render <<<"$(complete_words shellmarch --verbose ren)" || fail "global flags before the command"
cmp -s shellmarch.bash "$doc/shellmarch.bash" || fail "the build's completion script is stale"

# Man pages: one per command, from its --help.
for c in "" -info -generate -render -view -bench -devices -compare -completion; do
  [ -s "$doc/shellmarch$c.1" ] || fail "no man page shellmarch$c.1"
done
grep -q -- 'colormap' "$doc/shellmarch-render.1" || fail "shellmarch-render.1 lacks --colormap"
grep -q "$("$sm" --version | cut -d' ' -f2)" "$doc/shellmarch.1" || fail "shellmarch.1 lacks the version"
if command -v man >/dev/null; then
  man -l "$doc/shellmarch-render.1" 2>/dev/null | grep -q "render" || fail "man cannot read it"
fi

# Progress: forced on, a render sequence reports its frames on stderr; --quiet wins over nothing
# else but the variable; without it (stderr not a terminal) nothing.
"$sm" generate --analytic cube-tets6 --cube-n 3 --out cube.pvtu >/dev/null 2>&1 || fail "generate"
SHELLMARCH_PROGRESS=1 "$sm" render cube.pvtu --orbit 3 --size 16x16 --out o.png 2>progress.txt ||
  fail "render --orbit 3 exit status $?"
grep -q "^shellmarch: frame 3/3 (100%)" progress.txt && ok "$(tail -n 1 progress.txt)" ||
  fail "no progress line: $(cat progress.txt)"
"$sm" render cube.pvtu --orbit 3 --size 16x16 --out o.png 2>quiet.txt || fail "render"
[ ! -s quiet.txt ] || fail "progress on a stderr that is not a terminal: $(cat quiet.txt)"
if command -v script >/dev/null; then  # a terminal: the line appears; -q silences it
  # Long enough (over a second of frames) for the line to show.
  script -qec "$sm render cube.pvtu --orbit 30 --size 128x128 --out t.png" /dev/null >tty.txt 2>&1
  grep -q "frame 30/30" tty.txt || fail "no progress line on a terminal: $(cat -v tty.txt)"
  script -qec "$sm render cube.pvtu --orbit 30 --size 128x128 --out t.png -q" /dev/null >tty-q.txt 2>&1
  grep -q "frame" tty-q.txt && fail "-q after the command did not silence the progress line"
fi

# Threads: OMP_NUM_THREADS is what the stats report, and what it came from.
OMP_NUM_THREADS=1 "$sm" render cube.pvtu --size 16x16 --out s.png --stats-json s.json || fail "render"
python3 - s.json <<'PY' || fail "--stats-json threads/version"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["threads"] == {"per_rank": 1, "from": "OMP_NUM_THREADS"}, j["threads"]
assert j["version"].count(".") == 2, j["version"]
PY

echo "$fails failure(s)"
[ "$fails" -eq 0 ]
