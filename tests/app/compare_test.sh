#!/usr/bin/env bash
# `shellmarch compare` and `render --compare`, run by ctest with
#   compare_test.sh cli|render SHELLMARCH WORKDIR
# cli: tiny PNGs and PFMs made here with known differences: the table and JSON numbers, exit status
# 0 within the tolerance, 1 beyond it, 2 for images it cannot compare and bad options (one line of
# error, nothing written), the difference image's size. render: a render checked against its own
# image passes, against another view fails, on 1 and 2 ranks (rank 0 alone compares).
set -uo pipefail
case=$1 sm=$(realpath "$2") work=$3/$1
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh" || exit 1
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fails=0
# expect_status STATUS "what the message must contain" command...: exactly STATUS, one error line
# naming what is wrong.
expect_status() {
  local status=$1 want=$2; shift 2
  local out rc
  out=$("$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -ne "$status" ] || ! grep -qF -- "$want" <<<"$out" || [ "$(grep -c . <<<"$out")" -ne 1 ] ||
     ! grep -q '^shellmarch: error: ' <<<"$out"; then
    echo "FAIL: '$*' exit $rc (wanted $status), wanted one error line with '$want', got:"
    printf '%s\n' "$out"; fails=$((fails + 1))
  else
    echo "ok ($rc): $out"
  fi
}
check() { "$@" || { echo "FAIL: $*"; fails=$((fails + 1)); }; }
# png_size FILE W H: the PNG's header says W x H.
png_size() {
  python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); \
sys.exit(0 if d[:8]==b'\x89PNG\r\n\x1a\n' and struct.unpack('>II',d[16:24])==(int(sys.argv[2]),int(sys.argv[3])) else 1)" "$@"
}
no_temporaries() { ! ls -A | grep -q -i 'tmp'; }

if [ "$case" = cli ]; then
  python3 - <<'PY'
import struct, zlib
def png(path, w, h, px, alpha=False):
    comp = 4 if alpha else 3
    raw = b''.join(b'\0' + bytes(v for p in px[y * w:(y + 1) * w] for v in p[:comp]) for y in range(h))
    def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    ihdr = struct.pack('>IIBBBBB', w, h, 8, 6 if alpha else 2, 0, 0, 0)
    open(path, 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
def pfm(path, w, h, px):  # rows top first; PFM stores the bottom row first
    rows = [px[y * w:(y + 1) * w] for y in range(h)][::-1]
    open(path, 'wb').write(b'PF\n%d %d\n-1.0\n' % (w, h) + b''.join(struct.pack('<3f', *p) for r in rows for p in r))
a = [(10, 20, 30)] * 8           # 4x2
b = list(a); b[0] = (13, 20, 30); b[5] = (10, 24, 30)  # R +3 in one pixel, G +4 in another
png('a.png', 4, 2, a); png('b.png', 4, 2, b); png('small.png', 3, 2, a[:6])
png('rgba.png', 4, 2, [p + (255,) for p in a[:7]] + [(10, 20, 30, 0)], alpha=True)
data = open('a.png', 'rb').read(); open('cut.png', 'wb').write(data[:len(data) - 20])
open('junk.png', 'wb').write(b'not a png at all')
pfm('a.pfm', 2, 1, [(0.5, 0.0, 0.0), (0.0, 0.0, 0.0)])
pfm('b.pfm', 2, 1, [(0.25, 0.0, 0.0), (0.0, 0.0, 0.0)])
open('cut.pfm', 'wb').write(b'PF\n2 1\n-1.0\n' + b'\0' * 12)
PY
  # Identical images pass, PSNR infinite; the difference image sits beside the result.
  out=$("$sm" compare a.png a.png); rc=$?
  [ $rc -eq 0 ] || fail "identical images: exit $rc"
  grep -q '^R .* inf$' <<<"$out" || { echo "$out"; fail "identical images: no infinite PSNR"; }
  check png_size a.diff.png 4 2
  # Known differences: max R 3 and G 4, RMSE sqrt(9/8) and sqrt(2), 2 of 8 pixels beyond 0.
  "$sm" compare b.png a.png --json b.json >b.txt 2>b.err; rc=$?
  [ $rc -eq 1 ] || fail "different images: exit $rc, wanted 1"
  [ "$(wc -l <b.err)" -eq 1 ] && grep -qF "'b.png' differs from 'a.png' beyond the tolerance: 2 of 8 pixels (25%)" b.err ||
    { cat b.err; fail "different images: not the one line of error wanted"; }
  grep -q 'FAILED' b.txt || fail "different images: the table does not say FAILED"
  json b.json "j['channels']['R']['max_abs'] == 3 and j['channels']['G']['max_abs'] == 4"
  json b.json "abs(j['channels']['R']['rmse'] - (9 / 8) ** 0.5) < 1e-12 and abs(j['channels']['G']['rmse'] - 2 ** 0.5) < 1e-12"
  json b.json "abs(j['channels']['all']['rmse'] - (25 / 24) ** 0.5) < 1e-12"
  json b.json "abs(j['channels']['G']['psnr_db'] - 20 * __import__('math').log10(255 / 2 ** 0.5)) < 1e-9"
  json b.json "j['channels']['B']['psnr_db'] is None and j['channels']['A']['max_abs'] == 0"
  json b.json "j['beyond'] == 2 and j['beyond_share'] == 0.25 and j['pixels'] == 8 and not j['passed']"
  json b.json "j['diff'] == 'b.diff.png' and j['width'] == 4 and j['height'] == 2"
  check png_size b.diff.png 4 2
  # The tolerance is "more than T levels": G's 4 alone is beyond 3; 1 of 8 is a share of 0.125.
  check "$sm" compare b.png a.png --tolerance 4
  check "$sm" compare b.png a.png --tolerance 3 --max-share 0.125 --diff custom.png --json t.json
  json t.json "j['beyond'] == 1 and j['passed'] and j['diff'] == 'custom.png'"
  check png_size custom.png 4 2
  "$sm" compare b.png a.png --tolerance 3 --max-share 0.124 >/dev/null 2>&1
  [ $? -eq 1 ] || fail "1 of 8 pixels beyond against --max-share 0.124 did not exit 1"
  # PFMs in levels: (0.5 - 0.25) * 255 = 63.75; alpha in the summary only when an image has it.
  "$sm" compare a.pfm b.pfm --tolerance 63.75 --json f.json >/dev/null || fail "PFM within 63.75 levels"
  json f.json "j['channels']['R']['max_abs'] == 63.75 and j['beyond'] == 0 and not j['all_includes_alpha']"
  "$sm" compare rgba.png a.png --json r.json >/dev/null 2>&1
  json r.json "j['channels']['A']['max_abs'] == 255 and j['all_includes_alpha'] and j['beyond'] == 1"
  # Images it cannot compare, and bad options: exit 2, one line naming the file or option, and
  # no difference image or JSON written.
  rm -f ./*.diff.png ./*.json
  expect_status 2 "'small.png' is 3x2 pixels but 'a.png' is 4x2" "$sm" compare small.png a.png --json s.json
  expect_status 2 "missing.png: cannot open" "$sm" compare missing.png a.png
  expect_status 2 "missing.pfm: cannot open" "$sm" compare a.pfm missing.pfm
  expect_status 2 "cut.png: not a readable PNG" "$sm" compare cut.png a.png
  expect_status 2 "junk.png: not a readable PNG" "$sm" compare a.png junk.png
  expect_status 2 "cut.pfm: truncated PFM" "$sm" compare cut.pfm a.pfm
  expect_status 2 "RESULT: 'a.jpg' must end in .png or .pfm" "$sm" compare a.jpg a.png
  expect_status 2 "--tolerance: '-1' is negative" "$sm" compare b.png a.png --tolerance -1
  expect_status 2 "--tolerance: 'nan' is not a finite number" "$sm" compare b.png a.png --tolerance nan
  expect_status 2 "--tolerance: 'inf' is not a finite number" "$sm" compare b.png a.png --tolerance inf
  expect_status 2 "--tolerance: 'two' is not a number" "$sm" compare b.png a.png --tolerance two
  expect_status 2 "--tolerance" "$sm" compare b.png a.png --tolerance=
  expect_status 2 "--max-share: '1.5' is more than 1" "$sm" compare b.png a.png --max-share 1.5
  expect_status 2 "--max-share: '-0.1' is negative" "$sm" compare b.png a.png --max-share -0.1
  expect_status 2 "--diff: 'd.jpg' must end in .png" "$sm" compare b.png a.png --diff d.jpg
  expect_status 2 "--diff: 'a.png' is also the file of BASELINE" "$sm" compare b.png a.png --diff a.png
  expect_status 2 "--json: 'b.png' is also the file of RESULT" "$sm" compare b.png a.png --json b.png
  expect_status 2 "--diff: 'nowhere/d.png' is in a folder that does not exist" "$sm" compare b.png a.png --diff nowhere/d.png
  expect_status 2 "baseline is required" "$sm" compare b.png
  [ -z "$(ls ./*.diff.png ./*.json 2>/dev/null)" ] || { ls; fail "a refused comparison wrote a file"; }
  no_temporaries || { ls -A; fail "temporary files left behind"; }
  # A difference image or JSON that cannot be written is trouble too (2), not a failed check.
  mkdir -p ro && chmod 555 ro
  if [ ! -w ro ]; then
    expect_status 2 "--diff" "$sm" compare b.png a.png --diff ro/d.png
  fi
  chmod 755 ro
else
  "$sm" generate --analytic cube-tets6 --cube-n 3 --out cube.pvtu >/dev/null || fail "generate"
  view=(cube.pvtu --size 48x32 --range 0,1 --background 0,0,0)
  "$sm" render "${view[@]}" --out base.png || fail "render"
  "$sm" render "${view[@]}" --out same.png --compare base.png >same.txt || fail "render --compare against its own image"
  grep -q 'passed' same.txt || { cat same.txt; fail "no table"; }
  check png_size same.diff.png 48 32
  # Unrounded floats against 8-bit levels: within half a level (and float rounding).
  check "$sm" render "${view[@]}" --out float.pfm --compare base.png --tolerance 0.501
  # Another view: beyond the tolerance, exit 1, the image and the difference image written.
  expect_status 1 "'other.png' differs from 'base.png' beyond the tolerance" \
    "$sm" render "${view[@]}" --view +x --out other.png --compare base.png --tolerance 1
  check png_size other.png 48 32
  check png_size other.diff.png 48 32
  check "$sm" render "${view[@]}" --view +x --out other2.png --compare base.png --max-share 1
  # Refused before rendering (exit 2, nothing written).
  expect_status 2 "--compare: 'base.png' is 48x32 pixels, the image rendered 40x32" \
    "$sm" render cube.pvtu --size 40x32 --out small.png --compare base.png
  expect_status 2 "missing.png: cannot open" "$sm" render "${view[@]}" --out m.png --compare missing.png
  expect_status 2 "--compare: 'base.png' is also the file of --out" "$sm" render "${view[@]}" --out base.png --compare base.png
  expect_status 2 "--compare: checks one image, not a sequence" "$sm" render "${view[@]}" --time all --out s.png --compare base.png
  expect_status 2 "--tolerance requires --compare" "$sm" render "${view[@]}" --out t.png --tolerance 1
  expect_status 2 "--tolerance: 'nan' is not a finite number" "$sm" render "${view[@]}" --out t.png --compare base.png --tolerance nan
  for f in small.png m.png s.png s_0000.png t.png; do [ ! -e "$f" ] || fail "a refused render wrote $f"; done
  # Two ranks: rank 0 alone compares (one table), and a failed check ends the run with status 1.
  mpi 2 "$sm" render "${view[@]}" --out two.png --compare base.png >two.txt || fail "2 ranks against 1"
  [ "$(grep -c 'passed' two.txt)" -eq 1 ] || { cat two.txt; fail "2 ranks: not one table"; }
  mpi 2 "$sm" render "${view[@]}" --view +x --out two_other.png --compare base.png >/dev/null 2>&1
  rc=$?; [ $rc -eq 1 ] || fail "2 ranks, another view: exit $rc, wanted 1"
fi
[ $fails -eq 0 ] || fail "$fails check(s) failed"
echo "all passed"
