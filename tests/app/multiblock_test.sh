#!/usr/bin/env bash
# Files as a solver's VTK export lays them out, run by ctest with
#   multiblock_test.sh SHELLMARCH WORKDIR
# A multiblock .vtm whose unstructured blocks are a .pvtu's pieces (beside a boundary surface
# that is left out) renders bit for bit as the .pvtu on 1 and 3 ranks; a .vtm.series of one .vtm
# per step renders `--time all` bit for bit as the same steps in one .pvtu.
set -euo pipefail
sm=$1 work=$2
mkdir -p "$work"
cd "$work"
rm -rf ./*
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

view=(--field vortex --size 48x40 --view iso --range 0,1 --colormap viridis --early-termination 1)
"$sm" generate --analytic cube-tets6 --cube-n 5 --clusters 3 --steps 3 --out steps.pvtu
"$sm" generate --analytic cube-tets6 --cube-n 5 --clusters 3 --steps 3 --out run.pvd

# One .vtm per step, its blocks the step's pieces (nested as ParaView nests them), plus a surface.
blocks() {  # blocks FOLDER STEM
  echo '<VTKFile type="vtkMultiBlockDataSet" version="1.0"><vtkMultiBlockDataSet>'
  echo "<Block index=\"0\" name=\"internal\"><DataSet index=\"0\" file=\"$1/${2}_0.vtu\"/>"
  echo "<DataSet index=\"1\" file=\"$1/${2}_1.vtu\"/></Block>"
  echo "<Block index=\"1\" name=\"boundary\"><DataSet index=\"0\" file=\"wall.vtp\"/></Block>"
  echo "<DataSet index=\"2\" file=\"$1/${2}_2.vtu\"/>"
  echo '</vtkMultiBlockDataSet></VTKFile>'
}
blocks steps steps > steps.vtm
for k in 0 1 2; do blocks run_t$k run_t$k > run/run_t$k.vtm; done  # relative to run/
echo '{"file-series-version": "1.0", "files": [
  {"name": "run/run_t0.vtm", "time": 0}, {"name": "run/run_t1.vtm", "time": 0.5},
  {"name": "run/run_t2.vtm", "time": 1}]}' > run.vtm.series

"$sm" info steps.vtm | grep -q "VTK XML multiblock (.vtm) of unstructured grids, 3 pieces" ||
  fail "info does not describe the .vtm"
for n in 1 3; do
  mpi $n "$sm" render steps.pvtu "${view[@]}" --time all --out pvtu$n.pfm
  mpi $n "$sm" render steps.vtm "${view[@]}" --time all --out vtm$n.pfm
  mpi $n "$sm" render run.vtm.series "${view[@]}" --time all --out series$n.pfm
  for k in 0 1 2; do
    cmp pvtu${n}_000$k.pfm vtm${n}_000$k.pfm || fail ".vtm frame $k on $n rank(s) is not the .pvtu's"
    cmp pvtu${n}_000$k.pfm series${n}_000$k.pfm ||
      fail ".vtm.series frame $k on $n rank(s) is not the .pvtu's"
  done
done

# Points no element uses (here one only a line uses, as a quadratic cell's mid-edge nodes are)
# count in the default range on any number of ranks: a file read whole and split among ranks keeps
# them on one rank, so 2 ranks render what 1 does, and both what the range through them gives.
{
  printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 13 double\n'
  printf '0 0 0 1 0 0 2 0 0 0 1 0 1 1 0 2 1 0 0 0 1 1 0 1 2 0 1 0 1 1 1 1 1 2 1 1 0.5 0.5 0.5\n'
  printf 'CELLS 3 21\n8 0 1 4 3 6 7 10 9\n8 1 2 5 4 7 8 11 10\n2 0 12\nCELL_TYPES 3\n12\n12\n3\n'
  printf 'CELL_DATA 3\nSCALARS cluster int\nLOOKUP_TABLE default\n0 1 0\n'
  printf 'POINT_DATA 13\nSCALARS f float\nLOOKUP_TABLE default\n0 0.1 0.2 0 0.1 0.2 0 0.1 0.2 0 0.1 0.2 100\n'
} > stray.vtk
# Half an element as the step (the default's cap at the diagonal / 256 would take 20 times the
# samples, and 2 ranks would then differ from 1 by compositing order's rounding).
plain=(--size 48x40 --view iso --colormap viridis --step 0.5)
mpi 1 "$sm" render stray.vtk "${plain[@]}" --out stray1.pfm 2>/dev/null
mpi 2 "$sm" render stray.vtk "${plain[@]}" --out stray2.pfm 2>/dev/null
"$sm" render stray.vtk "${plain[@]}" --range 0,100 --out stray-range.pfm 2>/dev/null
cmp stray1.pfm stray-range.pfm || fail "1 rank's default range leaves out a point no element uses"
cmp stray1.pfm stray2.pfm || fail "2 ranks' default range is not 1 rank's (a point no element uses)"
echo "multiblock: all checks passed"
