#!/usr/bin/env bash
# `render --legend`, run by ctest with  legend_test.sh SHELLMARCH IMAGE_DIFF WORKDIR
# The legend changes only the right-hand part of the image, where its bar shows the colour map
# from the range's low end at the bottom to its high end at the top; the images on 1 and 3 ranks
# agree (to the compositing's float rounding), and every frame of a sequence has one.
set -euo pipefail
sm=$1 diff=$2 work=$3
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.png
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --steps 2 --out steps.pvtu
view=(--field vortex --size 160x120 --range 0,1 --colormap viridis --view iso --background 0,0,0)
"$sm" render steps.pvtu "${view[@]}" --out plain.pfm
for n in 1 3; do mpi $n "$sm" render steps.pvtu "${view[@]}" --legend --out legend$n.pfm; done
"$diff" legend1.pfm legend3.pfm --max-abs 1e-5
python3 - plain.pfm legend1.pfm <<'PY' || fail "the legend is not where and what it should be"
import struct, sys
def pfm(path):
    data = open(path, 'rb').read()
    head = data.split(b'\n', 3)
    w, h = map(int, head[1].split())
    vals = struct.unpack('<%df' % (w * h * 3), head[3][:w * h * 12])
    rows = [vals[r * w * 3:(r + 1) * w * 3] for r in range(h)][::-1]  # PFM is bottom row first
    return w, h, [[tuple(row[3 * x:3 * x + 3]) for x in range(w)] for row in rows]
w, h, plain = pfm(sys.argv[1])
_, _, legend = pfm(sys.argv[2])
changed = [(x, y) for y in range(h) for x in range(w) if plain[y][x] != legend[y][x]]
assert len(changed) > 300, len(changed)
assert min(x for x, _ in changed) >= w // 2, min(x for x, _ in changed)
# The bar: the column with the most changed pixels that are neither ink (white) nor black; its
# top is viridis' last entry (yellow), its bottom the first (dark purple).
ink = ((1.0, 1.0, 1.0), (0.0, 0.0, 0.0))
bar = {x: [y for y in range(h) if plain[y][x] != legend[y][x] and legend[y][x] not in ink]
       for x in range(w)}
col = max(bar, key=lambda x: len(bar[x]))
ys = bar[col]
assert len(ys) >= h // 2 - 2, len(ys)
top, bottom = legend[min(ys)][col], legend[max(ys)][col]
assert top[0] > 0.9 and top[1] > 0.85 and top[2] < 0.2, top
assert bottom[0] < 0.3 and bottom[1] < 0.05 and bottom[2] > 0.3, bottom
PY
mpi 3 "$sm" render steps.pvtu "${view[@]}" --legend --time all --out seq.png
for k in 0 1; do [ -s seq_000$k.png ] || fail "frame $k of the sequence is missing"; done
echo "legend: all checks passed"
