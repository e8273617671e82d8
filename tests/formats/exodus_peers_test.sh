#!/usr/bin/env bash
# Exodus II files written by libexodusii (make_format_files exodus), read by shellmarch and by
# VTK 9.1's vtkExodusIIReader, run by ctest as
#   exodus_peers_test.sh SHELLMARCH MAKE_FORMAT_FILES WORKDIR
# Counts and field ranges from `shellmarch info --json` must be VTK's; the image of each mesh must
# be the image of the .vtu VTK writes from its own reading; a decomposed mesh renders on 2 ranks
# as on 1; damaged files are refused with one line.
set -euo pipefail
sm=$1 make_files=$2 work=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$work"
cd "$work"
rm -rf ./*
source "$here/../app/script_lib.sh"
py=/usr/bin/python3  # the system Python: it has VTK 9.1

"$make_files" exodus files >/dev/null

# vtk_peer INFO_JSON OUT_VTU STEP FILE...: reads FILE... (the files of one mesh) with
# vtkExodusIIReader, every block and every nodal and element variable on, and checks the counts and
# ranges in INFO_JSON (shellmarch info --json) against it; writes step STEP as one .vtu.
vtk_peer() {
  "$py" - "$@" <<'EOF'
import json, math, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy

info_path, out, step, files = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
info = json.load(open(info_path))
VOLUME = {10: "tets", 24: "tets", 12: "hexes", 25: "hexes", 29: "hexes", 13: "wedges",
          26: "wedges", 14: "pyramids", 27: "pyramids"}
SURFACE, LINE = {5, 7, 9, 22, 23, 28}, {1, 3, 21}

def read(path, k):
    r = vtk.vtkExodusIIReader()
    r.SetFileName(path)
    r.UpdateInformation()
    for kind in (r.ELEM_BLOCK,):
        for i in range(r.GetNumberOfObjects(kind)):
            r.SetObjectStatus(kind, i, 1)
    r.SetAllArrayStatus(r.NODAL, 1)
    r.SetAllArrayStatus(r.ELEM_BLOCK, 1)
    r.SetTimeStep(k)
    r.Update()
    grids, it = [], r.GetOutput().NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        grids.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return r, grids

r0, _ = read(files[0], 0)
steps = r0.GetNumberOfTimeSteps()
counts = {"tets": 0, "hexes": 0, "wedges": 0, "pyramids": 0}
surface = line = quadratic = 0
corners, ranges, cell_arrays = set(), {}, set()
for k in range(max(steps, 1)):
    for path in files:
        _, grids = read(path, k)
        for g in grids:
            pd, cd = g.GetPointData(), g.GetCellData()
            # vtkExodusIIReader joins NAME_x, NAME_y, NAME_z into one vector "NAME_": its
            # components are shellmarch's scalars NAME_x ...
            for a in range(pd.GetNumberOfArrays()):
                arr = pd.GetArray(a)
                name, nc = arr.GetName(), arr.GetNumberOfComponents()
                if name in ("PedigreeNodeId", "GlobalNodeId") or arr.GetNumberOfTuples() == 0:
                    continue
                v = vtk_to_numpy(arr).reshape(-1, nc)
                for c in range(nc):
                    key = name if nc == 1 else name.rstrip("_") + "_" + "xyz"[c]
                    lo, hi = ranges.get(key, (math.inf, -math.inf))
                    ranges[key] = (min(lo, float(v[:, c].min())), max(hi, float(v[:, c].max())))
            for a in range(cd.GetNumberOfArrays()):
                if cd.GetArray(a).GetName() not in ("ObjectId", "GlobalElementId", "PedigreeElementId"):
                    cell_arrays.add(cd.GetArray(a).GetName())
            if k > 0:
                continue
            for c in range(g.GetNumberOfCells()):
                t = g.GetCellType(c)
                if t in VOLUME:
                    counts[VOLUME[t]] += 1
                    quadratic += t not in (10, 12, 13, 14)
                    ids = g.GetCell(c).GetPointIds()
                    for i in range(ids.GetNumberOfIds()):
                        corners.add(g.GetPoint(ids.GetId(i)))
                elif t in SURFACE:
                    surface += 1
                elif t in LINE:
                    line += 1
                else:
                    sys.exit(f"{path}: VTK cell type {t} not expected in the test files")

def check(what, ours, theirs):
    if ours != theirs:
        sys.exit(f"{files[0]}: {what}: shellmarch {ours}, VTK {theirs}")

for key in counts:
    check(key, info[key], counts[key])
check("skipped 2D cells", info["skipped"]["surface"], surface)
check("skipped line cells", info["skipped"]["lineOrVertex"], line)
check("quadratic cells", info["quadraticReduced"], quadratic)
# Nodes of the volume elements (mid-edge ones too), merged where coordinates are equal.
check("points", info["points"], len(corners))
times = r0.GetOutputInformation(0).Get(vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS())
check("time values", info["timeValues"], [float(t) for t in times or []])
check("cell data", sorted(info["cellArrays"]), sorted(cell_arrays))
fields = {f["name"]: f for f in info["fields"]}
check("point fields", sorted(fields), sorted(ranges))
for name, (lo, hi) in ranges.items():
    ours = fields[name]["range"]
    if fields[name]["steps"] != steps or abs(ours[0] - lo) > 1e-5 or abs(ours[1] - hi) > 1e-5:
        sys.exit(f"{files[0]}: field {name}: shellmarch {fields[name]}, VTK range {lo}..{hi} "
                 f"over {steps} steps")

# The step rendered, as VTK read it, all files and blocks joined (points merged) into one .vtu.
append = vtk.vtkAppendFilter()
append.MergePointsOn()
for path in files:
    for g in read(path, step)[1]:
        append.AddInputData(g)
append.Update()
w = vtk.vtkXMLUnstructuredGridWriter()
w.SetFileName(out)
w.SetInputData(append.GetOutput())
w.SetDataModeToBinary()
if not w.Write():
    sys.exit(f"cannot write {out}")
EOF
}

# Small images keep this quick; the range is fixed so that both sides use the same colours.
view=(--size 64x48 --view iso --colormap viridis --early-termination 1)

# blocks.exo: hexahedra, tetrahedra, wedges, a pyramid, a HEX20, a shell and a bar block, 3 steps.
"$sm" info --json files/blocks.exo >blocks.json 2>/dev/null
vtk_peer blocks.json vtk-blocks.vtu 2 files/blocks.exo || fail "blocks.exo differs from VTK's reading"
"$sm" render files/blocks.exo --field temp --time 2 --range 20,30 "${view[@]}" --out blocks.pfm \
  2>/dev/null
"$sm" render vtk-blocks.vtu --field temp --range 20,30 "${view[@]}" --out vtk-blocks.pfm 2>/dev/null
# Same cells, same points, same values: only the order of the cells in memory differs (blocks as
# clusters, VTK's appended grid as one), which changes how equal-depth fragments round when
# composited. 2 levels of 255 on at most 1% of the pixels covers that rounding, and no more: a
# wrong cell or value changes hundreds of pixels by tens of levels.
"$sm" compare blocks.pfm vtk-blocks.pfm --tolerance 2 --max-share 0.01 >/dev/null ||
  fail "blocks.exo does not render as VTK's reading of it"

# The same as netCDF-4 (HDF5) with 64-bit node numbers: the same counts and ranges as VTK's.
"$sm" info --json files/blocks-nc4.exo >nc4.json 2>/dev/null
vtk_peer nc4.json vtk-nc4.vtu 2 files/blocks-nc4.exo || fail "blocks-nc4.exo differs from VTK's"

# The decomposed mesh (3 files; given by its first file, and by NAME.e, which does not exist).
"$sm" info --json files/decomp.e.3.0 >decomp.json 2>/dev/null
vtk_peer decomp.json vtk-decomp.vtu 1 files/decomp.e.3.{0,1,2} ||
  fail "decomp.e.3.* differ from VTK's reading"
json decomp.json 'j["pieces"] == 3 and j["cellsPerCluster"] == [4, 4, 6]'
"$sm" info --json files/decomp.e >decomp-base.json 2>/dev/null
json decomp-base.json 'j["points"] == 36 and j["hexes"] == 10 and j["wedges"] == 4'
"$sm" render files/decomp.e.3.1 --field temp --time 1 --range 1,14 "${view[@]}" --out decomp.pfm \
  2>/dev/null
"$sm" render vtk-decomp.vtu --field temp --range 1,14 "${view[@]}" --out vtk-decomp.pfm 2>/dev/null
"$sm" compare decomp.pfm vtk-decomp.pfm --tolerance 2 --max-share 0.01 >/dev/null ||
  fail "decomp.e.3.* do not render as VTK's reading of them"
# 2 ranks read their own files (pieces) and composite: the image of 1 rank. Not bit for bit: the
# ranks' partial sums along a ray are added in another order than 1 rank adds them, which moves
# channels by float rounding, measured below 0.01 of a level; 0.05 levels on every pixel allows
# that and nothing a missing or misplaced file would do (whole slabs, tens of levels).
mpi 2 "$sm" render files/decomp.e.3.0 --field temp --time 1 --range 1,14 "${view[@]}" \
  --out rank2.pfm 2>/dev/null
"$sm" compare decomp.pfm rank2.pfm --tolerance 0.05 >/dev/null ||
  fail "decomposed mesh: 2 ranks render another image than 1"

# Damaged and unsupported files: one line naming the file and the place, nothing written.
refused "badconn.exo: block 7 'broken': element 1 refers to node 99" bad.png \
  "$sm" render files/badconn.exo "${view[@]}" --out bad.png
refused "flat2d.exo: is a 2D mesh" flat.png "$sm" render files/flat2d.exo "${view[@]}" --out flat.png
head -c 6000 files/blocks.exo >cut.exo
refused "cut.exo: is truncated" cut.png "$sm" render cut.exo "${view[@]}" --out cut.png
mkdir partial && cp files/decomp.e.3.0 files/decomp.e.3.2 partial/
refused "partial/decomp.e.3.1: is missing" p.png "$sm" render partial/decomp.e.3.2 --out p.png
echo "exodus peers: all checks passed"
