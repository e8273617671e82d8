#!/usr/bin/env bash
# SU2 meshes written by gmsh's SU2 writer (and a two-zone file written as text by gmsh_files.cpp:
# gmsh writes one zone only), read by shellmarch and by meshio 5.0 (/usr/bin/python3; VTK 9.1 has
# no SU2 reader), run by ctest as
#   su2_peers_test.sh SHELLMARCH MAKE_FORMAT_FILES WORKDIR
# Counts and bounds agree with meshio's and with the .msh gmsh wrote of the same mesh. No images:
# an SU2 mesh holds no fields and shellmarch renders fields only, which the render's one-line
# refusal checks (with a 2D file's).
set -euo pipefail
sm=$1 make_files=$2 work=$3
mkdir -p "$work"
cd "$work"
rm -rf ./*
source "$(dirname "${BASH_SOURCE[0]}")/../app/script_lib.sh"
trap 'echo "FAIL: line $LINENO: $BASH_COMMAND"; tail -5 stderr.log 2>/dev/null' ERR

"$make_files" gmsh files >/dev/null

# Single-zone files: points and volume cells per type as meshio reads them, no cell fixed.
for f in box mixed stack; do
  "$sm" info --json files/$f.su2 >$f.json 2>>stderr.log
  /usr/bin/python3 - files/$f.su2 $f.json <<'EOF' || fail "$f.su2: shellmarch and meshio disagree"
import json, sys, warnings
warnings.simplefilter("ignore")
import meshio
m, j = meshio.read(sys.argv[1]), json.load(open(sys.argv[2]))
kinds = {"tetra": "tets", "hexahedron": "hexes", "wedge": "wedges", "pyramid": "pyramids"}
counts = {k: 0 for k in kinds.values()}
for block in m.cells:
    if block.type in kinds:
        counts[kinds[block.type]] += len(block.data)
ok = j["points"] == len(m.points) and j["invertedFixed"] == 0 and j["pieces"] == 1
ok = ok and all(j[k] == n for k, n in counts.items())
ok = ok and j["bounds"]["lo"] == m.points.min(axis=0).tolist()
ok = ok and j["bounds"]["hi"] == m.points.max(axis=0).tolist()
if not ok:
    print(json.dumps(j, indent=1), counts, len(m.points))
sys.exit(0 if ok else 1)
EOF
  # The same mesh as gmsh's .msh of it (gmsh writes SU2 points with 17 digits: exact).
  "$sm" info --json files/$f.msh >$f-msh.json 2>>stderr.log
  python3 - $f.json $f-msh.json <<'EOF' || fail "$f.su2 is not the mesh of $f.msh"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
sys.exit(0 if all(a[k] == b[k] for k in ("points", "tets", "hexes", "wedges", "pyramids",
                                          "bounds")) else 1)
EOF
done

# Two zones: meshio 5.0 reads a multi-zone file as one zone (the first zone's points, both zones'
# elements), so the counts come from the text: 2 pieces of 5 tetrahedra and a triangle each, 8
# points each, of which the 4 of the shared face x = 1 are welded.
"$sm" info --json files/zones.su2 >zones.json 2>>stderr.log
json zones.json "j['pieces'] == 2 and j['clusters'] == 2 and j['tets'] == 10 and j['points'] == 12"
json zones.json "j['cellsPerCluster'] == [5, 5] and j['invertedFixed'] == 0"
json zones.json "j['bounds']['lo'] == [0, 0, 0] and j['bounds']['hi'] == [2, 1, 1]"

# Refused in one line, nothing written.
refused "has no point fields to render" box.png "$sm" render files/box.su2 --out box.png
printf 'NDIME= 2\nNELEM= 0\nNPOIN= 0\n' >flat.su2
refused "flat.su2: line 1: NDIME= 2: only 3D meshes" flat.png "$sm" render flat.su2 --out flat.png
head -c 3000 files/box.su2 >cut.su2
refused "cut.su2: line" cut.png "$sm" render cut.su2 --out cut.png
echo "su2 peers: all checks passed"
