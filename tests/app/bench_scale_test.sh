#!/usr/bin/env bash
# `shellmarch bench scale` on two tiny grid meshes and 1 and 2 ranks, run by ctest with
#   bench_scale_test.sh SHELLMARCH WORKDIR
# The table is printed, the JSON has the keys docs/BENCHMARKS.md promises (no timings are
# asserted), 20K and 40K on 1 and 2 ranks give a weak-scaling pair, the meshes are deleted after
# their rows, a failed row is recorded rather than ending the run, and a bad option is one line
# naming it with exit status 2.
set -euo pipefail
sm=$1 work=$2
mkdir -p "$work"
cd "$work"
rm -rf ./data ./*.json ./*.md ./*.log ./*.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

"$sm" bench scale --elements 20K,40K --ranks 1,2 --sizes 64 --frames 1 --frames-check 3 \
  --data-dir data --json scale.json --markdown scale.md >scale.log 2>&1 ||
  { cat scale.log; fail "bench scale failed"; }
grep -q '^| elements | ranks | status |' scale.log || { cat scale.log; fail "no table printed"; }
[ "$(grep -c '| ok ' scale.md)" -eq 4 ] || { cat scale.md; fail "not 4 rows ok"; }
grep -q '^Where the time goes at 40.0K on 2 rank(s)' scale.log || fail "no line on where the time goes"

json scale.json "j['benchmark'] == 'scale' and len(j['meshes']) == 2 and len(j['rows']) == 4"
json scale.json "all(r['ok'] and r['elements'] > 0 for r in j['rows'])"
stages="['generate_s', 'load_s', 'prepare_s', 'context_s', 'upload_s', 'first_frame_s', 'other_s', 'first_image_s', 'warm_ms_64x64']"
json scale.json "all(set($stages) <= set(r['stages']) for r in j['rows'])"
setup="['wall_s', 'warm_frame_ms', 'host_peak_after_setup_bytes', 'prepared_bytes_rank0', 'peak_over_prepared', 'mesh_peak_over_prepared', 'process_peak_rss_bytes', 'memory_rank0']"
json scale.json "all(set($setup) <= set(r['setup']) for r in j['rows'])"
json scale.json "all(m['elements'] > 0 and m['elements_per_second'] > 0 and m['peak_rss_bytes'] > 0 for m in j['meshes'])"
a="j['analysis']"
json scale.json "set($a) == {'exponents', 'strong', 'weak', 'memory', 'time_shares'}"
json scale.json "len([e for e in $a['exponents'] if e['stage'] == 'load_s']) == 2"
json scale.json "$a['weak']['available'] and $a['weak']['rows'][0]['ranks'] == 2"
json scale.json "len($a['strong']) > 0 and len($a['memory']) == 4 and len($a['time_shares']) == 2"
json scale.json "$a['memory'][0]['paper_shares']['connectivity'] == 0.6272"
json scale.json "j['frames_check']['frames'] == 3 and 'grows' in j['frames_check']"
json scale.json "len(j['not_reported']) > 0"
# Each rank's own ratio of what reading and preparing held to its prepared bytes.
json scale.json "all(0 < r['setup']['mesh_peak_over_prepared'] < 100 for r in j['rows'])"

# --report: the same tables again from the JSON, without running anything.
"$sm" bench scale --report scale.json --markdown again.md >again.log 2>&1 ||
  { cat again.log; fail "bench scale --report failed"; }
cmp -s scale.md again.md || { diff scale.md again.md; fail "--report gave other tables"; }
[ -z "$(find data -name '*.pvtu' -o -name '*.vtu')" ] || fail "meshes left in data/ without --keep"

# A launcher that fails: the row is recorded with its error line, and with no row measured the
# run ends with status 1 after writing its JSON.
printf '#!/bin/sh\nexec mpiexec "$@" --field nosuchfield\n' >badmpi.sh
chmod +x badmpi.sh
rc=0
"$sm" bench scale --elements 20K --ranks 1 --sizes 32 --frames 1 --data-dir data \
  --mpirun ./badmpi.sh --json failed.json >failed.log 2>&1 || rc=$?
[ $rc -eq 1 ] || { cat failed.log; fail "a run of failed rows exit $rc, wanted 1"; }
json failed.json "not j['rows'][0]['ok'] and 'nosuchfield' in j['rows'][0]['error']"

rc=0
"$sm" bench scale --elements 3Q >bad.log 2>&1 || rc=$?
[ $rc -eq 2 ] && grep -q -- '--elements' bad.log && [ "$(wc -l <bad.log)" -eq 1 ] ||
  { cat bad.log; fail "--elements 3Q: exit $rc, wanted 2 and one line"; }
echo "bench scale: ok"
