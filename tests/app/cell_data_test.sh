#!/usr/bin/env bash
# Cell data rendered through --field: averaged onto the points of the whole mesh, the same on one
# rank and on several (each reading only its pieces), and the same image as the point data that mean gives (VTK's Cell Data to
# Point Data on a mesh of volume cells only), computed here independently, in Python.
#   cell_data_test.sh SHELLMARCH WORK_DIR
set -euo pipefail
sm=$1 work=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$work" && cd "$work"
rm -rf cells cells.pvtu checker.pvtu uneven.pvtu uneven.png whole.vtu series* gen gen.pvd mixed.pvtu mixed.png nan.vtu nan_*.png ./*.pfm ./*.json streamed-*

python3 - <<'PY'
import math, os, struct

n = 6  # hexahedra per side; three pieces of two slabs each along x
f32 = lambda v: struct.unpack('f', struct.pack('f', v))[0]
num = lambda v: '%.9g' % f32(v)
point = lambda i, j, k: (i / n, j / n, k / n)
def cell_value(i, j, k):
    x, y, z = (i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n
    return f32(1.0 + math.sin(3 * x) * y + 0.5 * z * z)
def corners(i, j, k):
    return [(i, j, k), (i + 1, j, k), (i + 1, j + 1, k), (i, j + 1, k),
            (i, j, k + 1), (i + 1, j, k + 1), (i + 1, j + 1, k + 1), (i, j + 1, k + 1)]

def vtu(path, cells, point_values=None, steps=2, scale=1):
    ids, pts = {}, []
    for c in cells:
        for p in corners(*c):
            if p not in ids:
                ids[p] = len(pts)
                pts.append(p)
    conn = ' '.join(str(ids[p]) for c in cells for p in corners(*c))
    offsets = ' '.join(str(8 * (m + 1)) for m in range(len(cells)))
    xyz = ' '.join(num(v) for p in pts for v in point(*p))
    if point_values is None:  # c, a vector v = (c, 2c), and s with steps c, 2c (, 3c)
        c = [scale * cell_value(*q) for q in cells]
        series = ''.join('<DataArray type="Float32" Name="s@t%d" format="ascii">%s</DataArray>'
                         % (k, ' '.join(num((k + 1) * v) for v in c)) for k in range(steps))
        data = ('<CellData><DataArray type="Float32" Name="c" format="ascii">%s</DataArray>'
                '<DataArray type="Float32" Name="v" NumberOfComponents="2" format="ascii">%s'
                '</DataArray>%s</CellData>') % (' '.join(num(v) for v in c),
                                                ' '.join(num(v) + ' ' + num(2 * v) for v in c),
                                                series)
    else:  # c, and a vector w = (c, 2c) whose component w[1] is a field only when named
        data = ('<PointData><DataArray type="Float32" Name="c" format="ascii">%s</DataArray>'
                '<DataArray type="Float32" Name="w" NumberOfComponents="2" format="ascii">%s'
                '</DataArray></PointData>') % (
                    ' '.join(num(point_values[p]) for p in pts),
                    ' '.join(num(point_values[p]) + ' ' + num(2 * f32(point_values[p])) for p in pts))
    with open(path, 'w') as out:
        out.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
                  'byte_order="LittleEndian"><UnstructuredGrid>'
                  '<Piece NumberOfPoints="%d" NumberOfCells="%d">%s'
                  '<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">%s'
                  '</DataArray></Points><Cells>'
                  '<DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>'
                  '<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray>'
                  '<DataArray type="UInt8" Name="types" format="ascii">%s</DataArray>'
                  '</Cells></Piece></UnstructuredGrid></VTKFile>\n'
                  % (len(pts), len(cells), data, xyz, conn, offsets, ' '.join(['12'] * len(cells))))

allcells = [(i, j, k) for i in range(n) for j in range(n) for k in range(n)]
os.makedirs('cells', exist_ok=True)
for piece in range(3):
    vtu('cells/cells_%d.vtu' % piece, [c for c in allcells if c[0] // 2 == piece])
# The same cells in three interlocked pieces (cell (i, j, k) in piece (i + j + k) mod 3): every
# piece meets the others at faces, edges and single points, and no piece is convex.
for piece in range(3):
    vtu('cells/checker_%d.vtu' % piece, [c for c in allcells if sum(c) % 3 == piece])
# The same cells in one file, and a series of the interlocked pieces whose step k holds (k + 1) c
# as c (s's step k).
vtu('whole.vtu', allcells)
for k in range(2):
    for piece in range(3):
        vtu('cells/series_%d_%d.vtu' % (k, piece), [c for c in allcells if sum(c) % 3 == piece],
            steps=1, scale=k + 1)
    with open('series_%d.pvtu' % k, 'w') as out:
        out.write('<?xml version="1.0"?>\n<VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid>'
                  + ''.join('<Piece Source="cells/series_%d_%d.vtu"/>' % (k, p) for p in range(3))
                  + '</PUnstructuredGrid></VTKFile>\n')
with open('series.pvd', 'w') as out:
    out.write('<VTKFile type="Collection"><Collection><DataSet timestep="0" file="series_0.pvtu"/>'
              '<DataSet timestep="1" file="series_1.pvtu"/></Collection></VTKFile>\n')
# Pieces that disagree: the second holds three steps of s.
vtu('cells/uneven_0.vtu', [c for c in allcells if sum(c) % 3 == 0])
vtu('cells/uneven_1.vtu', [c for c in allcells if sum(c) % 3 != 0], steps=3)
for name, stem in (('cells.pvtu', 'cells'), ('checker.pvtu', 'checker')):
    with open(name, 'w') as out:
        out.write('<?xml version="1.0"?>\n<VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid>'
                  + ''.join('<Piece Source="cells/%s_%d.vtu"/>' % (stem, p) for p in range(3))
                  + '</PUnstructuredGrid></VTKFile>\n')
# The oracle: each point the mean of the cells around it, in double, stored as float.
sums = {}
for c in allcells:
    for p in corners(*c):
        s, k = sums.get(p, (0.0, 0))
        sums[p] = (s + cell_value(*c), k + 1)
vtu('points.vtu', allcells, {p: s / k for p, (s, k) in sums.items()})
PY

fails=0
check() {  # check WHAT FILE_A FILE_B: the two images must be identical to the bit
  if cmp -s "$2" "$3"; then echo "ok: $1"; else echo "FAIL: $1 ($2 and $3 differ)"; fails=$((fails + 1)); fi
}
args=(--view iso --size 96x96 --range 0.9,2.5)
"$sm" render cells.pvtu --field c "${args[@]}" --out one.pfm
mpiexec -n 3 --oversubscribe "$sm" render cells.pvtu --field c "${args[@]}" --out three.pfm
# Each rank reads only its pieces and adds the other ranks' sums at the points they share; four
# ranks for three pieces leave one rank with none.
mpiexec -n 4 --oversubscribe "$sm" render checker.pvtu --field c "${args[@]}" --out checker.pfm
"$sm" render points.vtu --field c "${args[@]}" --out oracle.pfm
"$sm" render cells.pvtu --field 'v[1]' --view iso --size 96x96 --range 1.8,5 --out component.pfm
# Several ranks composite in another order than one and sum a shared point's cells in another
# order: float rounding, at most a few 1e-7 (a seam of points averaged over one rank's cells only
# would be off by percent).
close() {  # close WHAT A.pfm B.pfm
python3 - "$2" "$3" <<'PY' && echo "ok: $1" || { echo "FAIL: $1"; fails=$((fails + 1)); }
import struct, sys
def load(path):
    data = open(path, 'rb').read()
    lines = data.split(b'\n', 3)
    w, h = map(int, lines[1].split())
    return struct.unpack('<%df' % (w * h * 3), lines[3][:w * h * 12])
a, b = load(sys.argv[1]), load(sys.argv[2])
worst = max(abs(x - y) for x, y in zip(a, b))
print('largest difference:', worst)
sys.exit(0 if worst <= 1e-6 else 1)
PY
}
close "cell data on 1 and 3 ranks" one.pfm three.pfm
close "cell data in interlocked pieces on 4 ranks, one without pieces" one.pfm checker.pfm
# Time steps of cell data on several ranks: step k is (k + 1) c, so over (k + 1) times the range
# it is the image of c.
mpiexec -n 4 --oversubscribe "$sm" render checker.pvtu --field s --time 1 --view iso --size 96x96 \
  --range 1.8,5 --out steps.pfm
close "step 1 of cell data in interlocked pieces on 4 ranks" one.pfm steps.pfm
# Every step of cell data (--time all) is read and averaged over the ranks when its frame comes,
# one step in memory: one file on one rank, interlocked pieces on 4 ranks (one without pieces) and
# a series of them on 3; the same frames as the whole file on 2 ranks, which holds every step in
# memory (a file that is not split in pieces is split after reading).
streams() {  # streams NAME RANKS FILE FIELD: how many times the log says the cell data is streamed
  mpiexec -n "$2" --oversubscribe "$sm" -v render "$3" --field "$4" --time all --view iso \
    --size 96x96 --range 0.9,5 --out "streamed-$1.pfm" 2>&1 | grep -c "is streamed" || true
}
for case in "one 1 whole.vtu s" "pieces 4 checker.pvtu s" "series 3 series.pvd c" "memory 2 whole.vtu s"; do
  read -r name ranks file field <<<"$case"
  n=$(streams "$name" "$ranks" "$file" "$field")
  want=1; [ "$name" = memory ] && want=0
  if [ "$n" -eq "$want" ]; then echo "ok: $name: cell data streamed: $n"
  else echo "FAIL: $name: 'is streamed' logged $n times, not $want"; fails=$((fails + 1)); fi
done
for k in 0 1; do
  for name in one pieces series; do
    close "step $k of streamed cell data ($name) as in memory" "streamed-memory_000$k.pfm" \
      "streamed-${name}_000$k.pfm"
  done
done
# The streamed collective path without --range (the range pass averages every step over the
# ranks), with the warm-up frame and a second run (--stats-json, --repeat 2) and without
# prefetching, on 4 ranks (one without pieces), against the steps in memory on 2 ranks.
three=(--field s --time all --view iso --size 96x96)
# Half an element as the step for the pair without --range (the default caps it at the diagonal /
# 256 on this 6^3 mesh: at 12 times the samples, the two orders' rounding reaches 1e-6).
mpiexec -n 2 --oversubscribe "$sm" render whole.vtu "${three[@]}" --step 0.0833 --out free-memory.pfm
mpiexec -n 4 --oversubscribe "$sm" render checker.pvtu "${three[@]}" --step 0.0833 --out free-pieces.pfm
mpiexec -n 4 --oversubscribe "$sm" render checker.pvtu "${three[@]}" --range 0.9,5 --repeat 2 \
  --stats-json repeat.json --out repeat.pfm
mpiexec -n 4 --oversubscribe "$sm" render checker.pvtu "${three[@]}" --range 0.9,5 --no-prefetch \
  --out noprefetch.pfm
for k in 0 1; do
  close "step $k streamed on 4 ranks, range from every step" "free-memory_000$k.pfm" "free-pieces_000$k.pfm"
  close "step $k streamed, --repeat 2" "streamed-memory_000$k.pfm" "repeat_000$k.pfm"
  close "step $k streamed, --no-prefetch" "streamed-memory_000$k.pfm" "noprefetch_000$k.pfm"
done
python3 -c "import json,sys; j=json.load(open('repeat.json'))['sequence']; sys.exit(0 if j['frames'] == 4 and j['runs'] == 2 else 1)" ||
  { echo "FAIL: --repeat 2 did not render 2 runs of 2 steps"; fails=$((fails + 1)); }
# Pieces holding the field as cell data on one rank and as point data on another stop every rank
# with one message naming both.
python3 - <<'PY'
import re
s = open('cells/series_0_1.vtu').read()
n = int(re.search(r'NumberOfPoints="(\d+)"', s).group(1))
s = re.sub(r'<CellData>.*?</CellData>',
           '<PointData><DataArray type="Float32" Name="c" format="ascii">%s</DataArray></PointData>'
           % ' '.join(['1'] * n), s, count=1, flags=re.S)
open('cells/mixed_1.vtu', 'w').write(s)
PY
printf '%s' '<?xml version="1.0"?><VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid><Piece Source="cells/series_0_0.vtu"/><Piece Source="cells/mixed_1.vtu"/></PUnstructuredGrid></VTKFile>' > mixed.pvtu
if out=$(mpiexec -n 2 --oversubscribe "$sm" render mixed.pvtu --field c --time all --size 32x32 --out mixed.png 2>&1); then
  echo "FAIL: pieces with cell and point data rendered"; fails=$((fails + 1))
elif grep -qF "mixed.pvtu: the pieces do not hold the same cell data: rank" <<<"$out" &&
  grep -qF "has 'c' (cell data) with 1 step" <<<"$out" && grep -qF "has 'c' with 1 step" <<<"$out" &&
  ! grep -qi "check failed\|internal" <<<"$out" && [ ! -e mixed.png ]; then
  echo "ok: cell data on one rank and point data on another refused on 2 ranks"
else
  echo "FAIL: mixed pieces: $out"; fails=$((fails + 1))
fi
# A non-finite value in a streamed step is warned about once, naming the step (loading checks
# step 0 only).
python3 - <<'PY'
import re
s = open('whole.vtu').read()
s = re.sub(r'(Name="s@t1" format="ascii">)(\S+)', lambda m: m.group(1) + 'nan', s, count=1)
open('nan.vtu', 'w').write(s)
PY
n=$("$sm" render nan.vtu --field s --time all --size 32x32 --out nan.png 2>&1 | grep -c "nan.vtu: cell data 's' step 1 has 1 non-finite values" || true)
if [ "$n" -eq 1 ]; then echo "ok: a NaN in streamed step 1 warned once"
else echo "FAIL: a NaN in streamed step 1 warned $n times"; fails=$((fails + 1)); fi
# generate --cell-data writes a solver-like series of cell data, which streams on 1 and 3 ranks.
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 3 --steps 2 --cell-data --out gen.pvd \
  | grep -qF "2 steps of cell data" || { echo "FAIL: generate --cell-data"; fails=$((fails + 1)); }
for ranks in 1 3; do
  mpiexec -n "$ranks" --oversubscribe "$sm" -v render gen.pvd --field vortex --time all \
    --view iso --size 64x64 --out "gen$ranks.pfm" 2>&1 | grep -qF "is streamed" ||
    { echo "FAIL: generated cell data not streamed on $ranks ranks"; fails=$((fails + 1)); }
done
for k in 0 1; do close "generated cell data step $k on 1 and 3 ranks" "gen1_000$k.pfm" "gen3_000$k.pfm"; done
# Ranks whose pieces hold different steps all stop, with one message naming both.
printf '%s' '<?xml version="1.0"?><VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid><Piece Source="cells/uneven_0.vtu"/><Piece Source="cells/uneven_1.vtu"/></PUnstructuredGrid></VTKFile>' > uneven.pvtu
if out=$(mpiexec -n 2 --oversubscribe "$sm" render uneven.pvtu --field s --size 32x32 --out uneven.png 2>&1); then
  echo "FAIL: uneven pieces rendered"; fails=$((fails + 1))
elif grep -qF "uneven.pvtu: the pieces do not hold the same cell data: rank" <<<"$out" &&
  grep -qF "(cells/uneven_0.vtu) has 's' (cell data) with 2 steps" <<<"$out" &&
  grep -qF "(cells/uneven_1.vtu) has 's' (cell data) with 3 steps" <<<"$out" && [ ! -e uneven.png ]; then
  echo "ok: uneven pieces refused on 2 ranks"
else
  echo "FAIL: uneven pieces: $out"; fails=$((fails + 1))
fi
check "cell data as the independently averaged point data" one.pfm oracle.pfm
check "a component of cell data (2c over twice the range)" one.pfm component.pfm
"$sm" render points.vtu --field 'w[1]' --view iso --size 96x96 --range 1.8,5 --out point-component.pfm
check "a component of point data, named by --field (2c over twice the range)" oracle.pfm point-component.pfm
# The viewer shows cell data, and a component, as the one field it was given: its headless
# screenshot is render's image.
small=(--view iso --size 48x48)
"$sm" render cells.pvtu --field c "${small[@]}" --range 0.9,2.5 --out render.png
env -u DISPLAY -u WAYLAND_DISPLAY "$sm" view cells.pvtu --field c "${small[@]}" --range 0.9,2.5 \
  --headless --frames 1 --screenshot view.png
check "view of cell data as render's image" render.png view.png
"$sm" render cells.pvtu --field 'v[1]' "${small[@]}" --range 1.8,5 --out render-v.png
env -u DISPLAY -u WAYLAND_DISPLAY "$sm" view cells.pvtu --field 'v[1]' "${small[@]}" --range 1.8,5 \
  --headless --frames 1 --screenshot view-v.png
check "view of a component of cell data as render's image" render-v.png view-v.png
# Without --field, a file of cell data alone renders its first cell array (as the viewer opens on
# it), on one rank and on three; the log says so.
for ranks in 1 3; do
  log=$(mpiexec -n $ranks --oversubscribe "$sm" -v render cells.pvtu "${small[@]}" --range 0.9,2.5 \
    --out "default$ranks.png" 2>&1)
  grep -qF -- "--field not given: rendering cell data 'c'" <<<"$log" ||
    { echo "FAIL: no default cell field on $ranks ranks: $log"; fails=$((fails + 1)); }
  mpiexec -n $ranks --oversubscribe "$sm" render cells.pvtu --field c "${small[@]}" --range 0.9,2.5 \
    --out "named$ranks.png"
  check "render without --field as --field c ($ranks ranks)" "named$ranks.png" "default$ranks.png"
done
# On three ranks, each reading its interlocked pieces, too.
mpiexec -n 3 --oversubscribe "$sm" render checker.pvtu --field c "${small[@]}" --range 0.9,2.5 \
  --out render3.png
env -u DISPLAY -u WAYLAND_DISPLAY mpiexec -n 3 --oversubscribe "$sm" view checker.pvtu --field c \
  "${small[@]}" --range 0.9,2.5 --headless --frames 1 --screenshot view3.png
check "view of cell data on 3 ranks as render's image" render3.png view3.png
# A later step of streamed cell data, read and averaged over the ranks when the viewer shows it.
mpiexec -n 3 --oversubscribe "$sm" render checker.pvtu --field s --time 1 "${small[@]}" --range 1.8,5 \
  --out render3s.png
printf 'key right\nframe\nquit\n' > step1.txt
env -u DISPLAY -u WAYLAND_DISPLAY mpiexec -n 3 --oversubscribe "$sm" view checker.pvtu --field s \
  "${small[@]}" --range 1.8,5 --headless --script step1.txt --screenshot view3s.png
check "view of step 1 of cell data on 3 ranks as render's image" render3s.png view3s.png
"$sm" render checker.pvtu --field s --time 0 "${small[@]}" --range 1.8,5 --out render3s0.png
if cmp -s render3s0.png view3s.png; then echo "FAIL: the viewer's step 1 is step 0"; fails=$((fails + 1)); fi
# Played, each frame shows the next step, read ahead while the frame before renders: the next
# step's cells are read on a thread and averaged over the ranks when its frame comes. Four frames
# of the two steps end on step 1, three of them read ahead.
played=$(env -u DISPLAY -u WAYLAND_DISPLAY mpiexec -n 3 --oversubscribe "$sm" view checker.pvtu \
  --field s "${small[@]}" --range 1.8,5 --headless --play --frames 4 --print-camera \
  --screenshot view3p.png)
check "view --play of cell data on 3 ranks: frame 4 as render's step 1" render3s.png view3p.png
if grep -qF '"prefetched_steps":3' <<<"$played" && grep -qF '"time":1' <<<"$played"; then
  echo "ok: view --play read 3 steps of cell data ahead on 3 ranks"
else
  echo "FAIL: view --play on 3 ranks: $played"; fails=$((fails + 1))
fi
# The image is not empty (a blank image would match the others too).
python3 - <<'PY' || fails=$((fails + 1))
import struct, sys
data = open('one.pfm', 'rb').read()
lines = data.split(b'\n', 3)
w, h = map(int, lines[1].split())
vals = struct.unpack('<%df' % (w * h * 3), lines[3][:w * h * 12])
lit = sum(1 for v in vals if v > 0.01)
print('lit values:', lit)
sys.exit(0 if lit > w * h else 1)
PY
exit $fails
