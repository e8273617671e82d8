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
# The bar: the longest run down a column of changed pixels that are neither ink (white) nor black
# (the text's anti-aliased edges are short runs); its top is viridis' last entry (yellow), its
# bottom the first (dark purple).
ink = ((1.0, 1.0, 1.0), (0.0, 0.0, 0.0))
def longest_run(x):
    best, run = [], []
    for y in range(h):
        run = run + [y] if plain[y][x] != legend[y][x] and legend[y][x] not in ink else []
        best = run if len(run) > len(best) else best
    return best
bar = {x: longest_run(x) for x in range(w)}
col = max(bar, key=lambda x: len(bar[x]))
ys = bar[col]
assert len(ys) >= h // 2 - 2, len(ys)
top, bottom = legend[min(ys)][col], legend[max(ys)][col]
assert top[0] > 0.9 and top[1] > 0.85 and top[2] < 0.2, top
assert bottom[0] < 0.3 and bottom[1] < 0.05 and bottom[2] > 0.3, bottom
PY
mpi 3 "$sm" render steps.pvtu "${view[@]}" --legend --time all --out seq.png
for k in 0 1; do [ -s seq_000$k.png ] || fail "frame $k of the sequence is missing"; done
# --background transparent: an RGBA PNG whose colour composited over black is the opaque image
# over black (to the 8-bit rounding); with --legend its bar is opaque and its text black.
"$sm" render steps.pvtu "${view[@]}" --out black.png
"$sm" render steps.pvtu "${view[@]/0,0,0/transparent}" --out clear.png
"$sm" render steps.pvtu "${view[@]/0,0,0/transparent}" --legend --out clear_legend.png
python3 - black.png clear.png clear_legend.png <<'PY' || fail "the transparent PNG is not the frame's alpha and colour"
import struct, sys, zlib
def png(path):
    data = open(path, 'rb').read()
    at, idat, head = 8, b'', None
    while at < len(data):
        n, kind = struct.unpack('>I4s', data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b'IHDR': head = struct.unpack('>IIBB', body[:10])
        if kind == b'IDAT': idat += body
        at += 12 + n
    w, h, depth, ctype = head
    ch = {2: 3, 6: 4}[ctype]
    raw, rows, prev = zlib.decompress(idat), [], bytearray(w * ch)
    for y in range(h):
        f, line = raw[y * (w * ch + 1)], bytearray(raw[y * (w * ch + 1) + 1:(y + 1) * (w * ch + 1)])
        for i in range(len(line)):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            p = a + b - c
            pred = [0, a, b, (a + b) // 2,
                    a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c][f]
            line[i] = (line[i] + pred) & 255
        rows.append([tuple(line[x * ch:(x + 1) * ch]) for x in range(w)])
        prev = line
    return ch, rows
ch_b, black = png(sys.argv[1])
ch_c, clear = png(sys.argv[2])
ch_l, legend = png(sys.argv[3])
assert (ch_b, ch_c, ch_l) == (3, 4, 4), (ch_b, ch_c, ch_l)
alphas = set(p[3] for row in clear for p in row)
assert 0 in alphas and len(alphas) > 10, sorted(alphas)[:20]  # empty corners, a range of opacity
worst = max(abs(round(p[c] * p[3] / 255) - q[c]) for r, s in zip(clear, black) for p, q in zip(r, s)
            for c in range(3))
assert worst <= 1, worst
opaque = sum(1 for r, s in zip(legend, clear) for p, q in zip(r, s) if p != q and p[3] == 255)
assert opaque > 100, opaque
ink = [p for r, s in zip(legend, clear) for p, q in zip(r, s) if p != q and p[3] == 255 and p[:3] == (0, 0, 0)]
assert len(ink) > 50, len(ink)  # black text and frame
PY
echo "legend: all checks passed"
