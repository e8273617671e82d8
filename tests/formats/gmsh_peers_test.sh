#!/usr/bin/env bash
# Gmsh .msh 4.1 files written by gmsh itself, read by shellmarch and by meshio 5.0 (/usr/bin/python3;
# VTK 9.1 has no .msh 4.1 reader), run by ctest as
#   gmsh_peers_test.sh SHELLMARCH MAKE_FORMAT_FILES WORKDIR
# Counts and field ranges agree with meshio's; each file renders as the .vtu meshio writes from its
# own reading; the partitioned file renders as the whole one, and on 2 ranks as on 1 (within
# float rounding); a .msh 2.2
# file is refused in one line.
set -euo pipefail
sm=$1 make_files=$2 work=$3
mkdir -p "$work"
cd "$work"
rm -rf ./*
source "$(dirname "${BASH_SOURCE[0]}")/../app/script_lib.sh"
# Messages go to stderr.log (warnings about skipped surface cells are expected); a command that
# fails shows its line and the log's end.
trap 'echo "FAIL: line $LINENO: $BASH_COMMAND"; tail -5 stderr.log 2>/dev/null' ERR

"$make_files" gmsh files >/dev/null

# meshio's reading of FILE as JSON (volume cell counts, points, field ranges of the last step, as
# meshio keeps only the last $NodeData of a name), and its .vtu of it. meshio 5.0 refuses
# $ElementData that covers only the volume elements (as gmsh writes it for our 3D views), so those
# sections are cut out of its copy first; it cannot read partitioned files at all.
peer() {  # peer FILE STEM
  /usr/bin/python3 - "$1" "$2" <<'EOF'
import json, re, sys, warnings
import numpy as np
warnings.simplefilter("ignore")
import meshio
src, stem = sys.argv[1], sys.argv[2]
data = re.sub(rb"\$ElementData\n.*?\n\$EndElementData\n", b"", open(src, "rb").read(), flags=re.S)
open(stem + "-meshio.msh", "wb").write(data)
m = meshio.read(stem + "-meshio.msh")
kinds = {"tetra": "tets", "hexahedron": "hexes", "wedge": "wedges", "pyramid": "pyramids"}
counts = {k: 0 for k in kinds.values()}
for block in m.cells:
    base = re.sub(r"[0-9]+$", "", block.type)
    if base in kinds:
        counts[kinds[base]] += len(block.data)
ranges = {}
for name, v in m.point_data.items():
    if name.startswith("gmsh:"):
        continue
    v = np.linalg.norm(v, axis=1) if v.ndim > 1 else v
    ranges[name] = [float(v.min()), float(v.max())]
json.dump({"points": len(m.points), "cells": counts, "ranges": ranges}, open(stem + ".peer.json", "w"))
m.point_data = {k: v for k, v in m.point_data.items() if not k.startswith("gmsh:")}
m.cell_data = {}
m.cell_sets = {}
meshio.write(stem + "-meshio.vtu", m)
EOF
}

# Counts and ranges: shellmarch's info against meshio's. Ranges: shellmarch's span every step,
# meshio's the last one, which holds the largest temperatures (step k adds k); velocity has one
# step. Values are float32 in shellmarch, hence the 1e-6 relative slack.
check_counts() {  # check_counts FILE STEM
  "$sm" info --json "$1" >"$2.json" 2>>stderr.log
  python3 - "$2.json" "$2.peer.json" <<'EOF' || fail "$1: shellmarch and meshio disagree"
import json, sys
j, p = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
ok = j["points"] == p["points"] and j["invertedFixed"] == 0
for kind, n in p["cells"].items():
    ok = ok and j[kind] == n
fields = {f["name"]: f["range"] for f in j["fields"]}
for name, (lo, hi) in p["ranges"].items():
    r = fields.get(name)
    ok = ok and r is not None and abs(r[1] - hi) <= 1e-6 * max(1, abs(hi))
    if name == "velocity":
        ok = ok and abs(r[0] - lo) <= 1e-6
if not ok:
    print(json.dumps(j, indent=1), json.dumps(p, indent=1))
sys.exit(0 if ok else 1)
EOF
}

# Images: the same fixed range and step for both. The two meshes are the same cells on the same
# points (meshio parses the same digits to the same doubles), but meshio's .vtu keeps gmsh's
# prism order, which shellmarch's .vtu reader finds inverted and fixes, and holds the
# higher-order elements as VTK's quadratic cells: identical geometry after reduction, so the
# images may differ only by float rounding in the traversal. Tolerance 2 levels on at most 1% of
# the pixels covers that; a wrong cell, point or value moves whole regions.
view=(--size 64x48 --view iso --colormap viridis)
render_pair() {  # render_pair STEM FIELD: the .msh's last step against meshio's .vtu
  local range=0,9 t=2
  [ "$2" = velocity ] && range=0,2.5 t=0
  "$sm" render files/$1.msh --field $2 --range $range "${view[@]}" --time $t --out $1-$2.pfm \
    2>>stderr.log
  # meshio's .vtu holds the last step only.
  "$sm" render $1-meshio.vtu --field $2 --range $range "${view[@]}" --out $1-$2-meshio.pfm \
    2>>stderr.log
  "$sm" compare $1-$2.pfm $1-$2-meshio.pfm --tolerance 2 --max-share 0.01 >cmp.log ||
    { cat cmp.log; fail "$1.msh $2 does not render as meshio's .vtu of it"; }
}
for f in box box-binary mixed mixed-order2; do
  peer files/$f.msh $f
  check_counts files/$f.msh $f
done
render_pair box temperature
render_pair box-binary velocity
render_pair mixed temperature
render_pair mixed-order2 temperature
peer files/stack.msh stack
check_counts files/stack.msh stack
peer files/box-order2.msh box-order2
check_counts files/box-order2.msh box-order2

# The partitioned file: 3 pieces, the whole mesh's counts; it renders as the unpartitioned file
# (same nodes; the welded partition faces leave no seam), and on 2 ranks as on 1.
"$sm" info --json files/box-part.msh >part.json 2>>stderr.log
json part.json "j['pieces'] == 3 and j['clusters'] == 3 and j['tets'] == 1125 and j['points'] == 339"
"$sm" info --json files/box-part-binary.msh >part-binary.json 2>>stderr.log
json part-binary.json "j['pieces'] == 3 and j['tets'] == 1125"
pview=(--field temperature --range 0,9 --size 64x48 --view iso --colormap viridis --time 1)
mpi 1 "$sm" render files/box-part.msh "${pview[@]}" --out part1.pfm 2>>stderr.log
mpi 2 "$sm" render files/box-part.msh "${pview[@]}" --out part2.pfm 2>>stderr.log
mpi 1 "$sm" render files/box.msh "${pview[@]}" --out whole1.pfm 2>>stderr.log
# Not bit for bit: each rank composites its partitions' fragments, so float sums run in another
# order (measured: at most 6e-5 of an 8-bit level). 0.001 levels on every pixel allows that and
# nothing a wrong piece or point would do.
"$sm" compare part2.pfm part1.pfm --tolerance 0.001 >cmp.log ||
  { cat cmp.log; fail "the partitioned .msh on 2 ranks is not the 1-rank image"; }
# Clusters change the traversal's compositing order: rounding only (tolerance 1 level, 1%).
"$sm" compare part1.pfm whole1.pfm --tolerance 1 --max-share 0.01 >cmp.log ||
  { cat cmp.log; fail "the partitioned .msh does not render as the whole one"; }

# Refused in one line, nothing written: a .msh 2.2 file and a cut one.
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n' >old.msh
refused "only version 4.1 is read" old.png "$sm" render old.msh --out old.png
head -c 20000 files/box.msh >cut.msh
refused "cut.msh: line" cut.png "$sm" render cut.msh --out cut.png
echo "gmsh peers: all checks passed"
