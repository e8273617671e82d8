#!/usr/bin/env bash
# CGNS files written by libcgns (make_format_files cgns) read by shellmarch and by VTK 9.1's
# vtkCGNSReader, run by ctest as
#   cgns_peers_test.sh SHELLMARCH MAKE_FORMAT_FILES WORKDIR
# For each file VTK can read: the same points, volume cells and Temperature range (step 0) in
# `shellmarch info --json`, and the same image from the .cgns as from the .vtu VTK writes of its
# own reading (its zones appended, their points not merged). Then 2 ranks render what 1 does, and a
# damaged file is refused with one line.
set -euo pipefail
sm=$1 make_files=$2 work=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$work"
cd "$work"
rm -rf ./*
source "$here/../app/script_lib.sh"

"$make_files" cgns . >/dev/null

# VTK's reading of FILE.cgns at its first time step (every base, zone and array): FILE.vtu, and its
# counts as JSON on stdout.
vtk_read() {
  /usr/bin/python3 - "$1" <<'EOF'
import json, sys, vtk
path = sys.argv[1]
r = vtk.vtkCGNSReader()
r.SetFileName(path)
r.UpdateInformation()
r.EnableAllBases()
r.EnableAllPointArrays()
r.EnableAllCellArrays()
r.SetLoadBndPatch(False)
r.SetDoublePrecisionMesh(True)
r.UpdateTimeStep(0.0)
append = vtk.vtkAppendFilter()  # structured zones become hexahedra; points are not merged
it = r.GetOutput().NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    append.AddInputData(it.GetCurrentDataObject())
    it.GoToNextItem()
append.Update()
grid = append.GetOutput()
w = vtk.vtkXMLUnstructuredGridWriter()
w.SetFileName(path.replace(".cgns", ".vtu"))
w.SetInputData(grid)
w.Write()
volume = sum(1 for c in range(grid.GetNumberOfCells()) if grid.GetCell(c).GetCellDimension() == 3)
t = grid.GetPointData().GetArray("Temperature")
print(json.dumps({"points": grid.GetNumberOfPoints(), "volume": volume,
                  "range": list(t.GetRange()) if t else None}))
EOF
}

view=(--field Temperature --size 64x48 --view iso --colormap viridis --range 0,12)
for f in mixed poly; do
  vtk_read $f.cgns > $f.vtk.json
  "$sm" info --json $f.cgns > $f.sm.json
  python3 - $f <<'EOF' || fail "$1: shellmarch and VTK disagree (see $f.*.json)"
import json, sys
f = sys.argv[1]
v = json.load(open(f + ".vtk.json"))
s = json.load(open(f + ".sm.json"))
t = [x for x in s["fields"] if x["name"] == "Temperature"][0]
split = s["polyhedraSplit"]["polyhedra"]
# Polyhedra are split into tetrahedra (counted apart); VTK keeps them whole.
cells = s["cells"] - s["polyhedraSplit"]["tets"] + split
ok = s["points"] == v["points"] and cells == v["volume"]
# shellmarch's range covers every step: Temperature + 10 s, s < steps; VTK's is step 0's.
lo, hi = t["range"]
ok = ok and abs(lo - v["range"][0]) < 1e-5 and abs(hi - 10 * (t["steps"] - 1) - v["range"][1]) < 1e-5
print(f, "points", s["points"], v["points"], "cells", cells, v["volume"], "range",
      t["range"], v["range"])
sys.exit(0 if ok else 1)
EOF
  # The same mesh and values in both files: equal up to rounding of the interpolation (VTK writes
  # the double coordinates it read; shellmarch reads both the same way), so 2 levels on 1% of the
  # pixels, for edges where the zones' cluster boundaries change the order of sums.
  "$sm" render $f.cgns "${view[@]}" --out $f-cgns.pfm 2>/dev/null
  "$sm" render $f.vtu "${view[@]}" --out $f-vtk.pfm 2>/dev/null
  "$sm" compare $f-cgns.pfm $f-vtk.pfm --tolerance 2 --max-share 0.01 ||
    fail "$f.cgns does not render as VTK's reading of it"
done

# Ranks read their zones only; the composited image is 1 rank's within a level (compositing order).
mpi 1 "$sm" render mixed.cgns "${view[@]}" --out rank1.pfm 2>/dev/null
mpi 2 "$sm" render mixed.cgns "${view[@]}" --out rank2.pfm 2>/dev/null
"$sm" compare rank2.pfm rank1.pfm --tolerance 1 --max-share 0 ||
  fail "2 ranks do not render mixed.cgns as 1 does"

refused "bad-vertex.cgns: base 'Base' zone 'T' section 'Tet'" bad.png \
  "$sm" render bad-vertex.cgns "${view[@]}" --out bad.png
echo "cgns peers: all checks passed"
