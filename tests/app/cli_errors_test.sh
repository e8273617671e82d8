#!/usr/bin/env bash
# Bad input gets one clear line naming the file or option, exit status 1 (2 for a command line the
# option parser refuses), and no output file.
set -uo pipefail
sm=$1 work=$2
mkdir -p "$work" && cd "$work"
"$sm" generate --analytic cube-tets6 --cube-n 2 --out ok.pvtu >/dev/null
fails=0
# expect_status STATUS "what the message must contain" command...: exactly STATUS (a crash or a
# sanitizer's abort after the right message is a failure), one error line, the message in it.
expect_status() {
  local status=$1 want=$2; shift 2
  local out rc
  out=$("$@" 2>&1); rc=$?
  local lines; lines=$(printf '%s\n' "$out" | grep -c 'error')
  if [ $rc -ne "$status" ] || ! grep -qF -- "$want" <<<"$out" || [ "$lines" -ne 1 ]; then
    echo "FAIL: '$*' exit $rc (wanted $status), wanted one error line with '$want', got:"; printf '%s\n' "$out"; fails=$((fails + 1))
  else
    echo "ok: $(grep error <<<"$out")"
  fi
}
expect() { expect_status 1 "$@"; }  # bad input: exit status 1
usage() { expect_status 2 "$@"; }   # a command line the option parser refuses: exit status 2
expect "missing.vtu" "$sm" render missing.vtu --out a.png
expect "--size" "$sm" render ok.pvtu --size 0x10 --out a.png
# A separator left at the end is not a missing number read as none.
expect "--size: '64x64x'" "$sm" render ok.pvtu --size 64x64x --out a.png
expect "--range: '1,3,'" "$sm" render ok.pvtu --range 1,3, --out a.png
expect "--eye: '3,3,3,'" "$sm" render ok.pvtu --eye 3,3,3, --out a.png
expect "--opacity: '0:0,1:1,' ends in ','" "$sm" render ok.pvtu --opacity 0:0,1:1, --out a.png
expect "--nan-color: '1,0' is not R,G,B or R,G,B,OPACITY" "$sm" render ok.pvtu --nan-color 1,0 --out a.png
expect "--nan-color: '1,0,2' has 2, outside [0, 1]" "$sm" render ok.pvtu --nan-color 1,0,2 --out a.png
expect "--nan-color: '1,0,0,x' is not 4 finite numbers" "$sm" render ok.pvtu --nan-color 1,0,0,x --out a.png
expect "--colormap" "$sm" render ok.pvtu --colormap nope --out a.png
expect "ok_0.vtu: has no point or cell array 'nope' (point arrays: linear, shock, vortex, density; cell data: none)" "$sm" render ok.pvtu --field nope --out a.png
expect "--out" "$sm" render ok.pvtu --out a.jpg
expect "--step" "$sm" render ok.pvtu --step -1 --out a.png
expect "--step" "$sm" render ok.pvtu --step inf --out a.png
# Finer than float positions along the rays resolve (sample indices would wrap): refused, not hung.
expect "use at least" "$sm" render ok.pvtu --step 1e-10 --out a.png
# Longer than the data: most rays would take no sample (an empty image); element-exact
# integration (the default) takes no samples and accepts it.
expect "--step: 100 is longer than the data's diagonal" "$sm" render ok.pvtu --step 100 \
  --integration sampled --out a.png
expect "--step: 100 is longer than the data's diagonal" "$sm" bench render --mesh ok.pvtu --step 100 \
  --no-vtk --sizes 16 --work-dir bw
"$sm" render ok.pvtu --step 100 --integration exact --size 16x16 --out exact.png ||
  { echo "FAIL: element-exact integration refuses a long step"; fails=$((fails + 1)); }
expect "--view" "$sm" render ok.pvtu --view sideways --out a.png
# Options another one makes meaningless are refused, not silently ignored.
expect "--view and --eye" "$sm" render ok.pvtu --view +x --eye 3,3,3 --out a.png
expect "--k: slots are for fixed-length lists" "$sm" render ok.pvtu --k 4 --out a.png
expect "--k" "$sm" render ok.pvtu --lists drop --k 0 --out a.png
expect "--time" "$sm" render ok.pvtu --time 99 --out a.png
expect "--time: '18446744073709551616'" "$sm" render ok.pvtu --time 18446744073709551616 --out a.png
expect "--cube-n: 1000 makes 6000000000 cells" "$sm" generate --analytic cube-tets6 --cube-n 1000 --out big.pvtu
expect "--cube-n: 465 makes 100544625 cells" "$sm" generate --analytic cube-hex --cube-n 465 --out big.pvtu
expect "ok_0.vtu: has no pieces to choose from" "$sm" info ok/ok_0.vtu --pieces 0
usage "--meshes: must not be empty" "$sm" bench accuracy --meshes '' --work-dir acc
expect "--meshes: empty entry in 'demo,,lander'" "$sm" bench accuracy --meshes demo,,lander --work-dir acc
expect "--rounds: must be at least 1" "$sm" bench accuracy --rounds 0 --work-dir acc
if [ -e acc ]; then echo "FAIL: bench accuracy made its work folder for nothing"; fails=$((fails + 1)); fi
# A piece that is itself a .pvtu index: named when render sizes the pieces, before any reading.
printf '<?xml version="1.0"?><VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid><Piece Source="inner.vtu"/></PUnstructuredGrid></VTKFile>' >inner.vtu
cp inner.vtu outer.pvtu
expect "inner.vtu: is itself a .pvtu index" "$sm" render outer.pvtu --out nested.png
mkdir -p dirout.pvtu
expect "dirout.pvtu: cannot write" "$sm" generate --analytic cube-tets6 --cube-n 2 --out dirout.pvtu
if [ -e dirout ]; then echo "FAIL: generate left pieces behind"; fails=$((fails + 1)); fi
expect "--range" "$sm" render ok.pvtu --range 2,1 --out a.png
expect "--lists" "$sm" render ok.pvtu --lists maybe --out a.png
expect "--pixel-ownership" "$sm" render ok.pvtu --pixel-ownership tiles --out a.png
expect "--integration" "$sm" render ok.pvtu --integration perfect --out a.png
expect "(--k)" "$sm" render ok.pvtu --lists merge --k 9 --size 16384x16384 --out a.png
expect "--shading-params" "$sm" render ok.pvtu --shading-params 0.3,0.7,-1,20 --out a.png
# A field name with a newline and a terminal escape: the message stays one printable line.
cat > forged.vtu <<'VTU'
<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">
<PointData><DataArray type="Float32" Name="f&#10;shellmarch: error: forged&#27;[31m" format="ascii">0 1 2 3</DataArray></PointData>
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">10</DataArray></Cells>
</Piece></UnstructuredGrid></VTKFile>
VTU
expect 'f\x0ashellmarch: error: forged\x1b[31m' "$sm" render forged.vtu --field nosuch --out a.png
# A field with no finite value renders nothing: an error, not an empty image.
sed -e 's/Name="f&#10;shellmarch: error: forged&#27;\[31m"/Name="f"/' -e '/PointData/s/>0 1 2 3</>nan inf -inf nan</' \
  forged.vtu > nan.vtu
rm -f nan.png
expect "nan.vtu: field 'f' has no finite value in step 0" "$sm" render nan.vtu --field f --out nan.png
[ ! -e nan.png ] || { echo "FAIL: nan.png written"; fails=$((fails + 1)); }
expect "--early-termination" "$sm" render ok.pvtu --early-termination 2 --out a.png
expect "--early-termination" "$sm" render ok.pvtu --early-termination 0 --out a.png
expect "--background" "$sm" render ok.pvtu --background 2,-1,0 --out a.png
expect "--background" "$sm" render ok.pvtu --background clear --out a.png
expect "--background transparent: --out 'a.pfm' is a PFM" "$sm" render ok.pvtu --background transparent --out a.pfm
expect "--background transparent: for render only" "$sm" view ok.pvtu --background transparent --headless --frames 1
expect "--clusters" "$sm" render ok.pvtu --clusters 0 --out a.png
expect "--range" "$sm" render ok.pvtu --range -1e300,1e300 --out a.png
expect "--opacity-scale" "$sm" render ok.pvtu --opacity-scale nan --out a.png
# The option parser's own errors are one line too, with the usage status 2.
usage "--fovy" "$sm" render ok.pvtu --fovy abc --out a.png
# bench render makes render's checks instead of measuring a bad value.
expect "--opacity-scale" "$sm" bench render --mesh ok.pvtu --no-vtk --opacity-scale nan --work-dir bw
expect "--step" "$sm" bench render --mesh ok.pvtu --no-vtk --step 0 --work-dir bw
# An output in a missing folder is refused before anything is written (the image included).
expect "--stats-json" "$sm" render ok.pvtu --stats-json nodir/s.json --out a.png
expect "--l2-heatmap" "$sm" render ok.pvtu --l2-heatmap h.jpg --out a.png
# An output that is a folder, the input mesh (or one of its pieces) or another output: refused
# before anything is written, the input left as it was.
mkdir -p sdir.json hm_all.png
expect "--stats-json: 'sdir.json' is a folder" "$sm" render ok.pvtu --stats-json sdir.json --out a.png
expect "--heatmaps: 'hm_all.png' is a folder" "$sm" render ok.pvtu --heatmaps hm --out a.png
cp ok/ok_1.vtu piece.bak
expect "--stats-json: 'ok/ok_1.vtu' is the mesh being read" "$sm" render ok.pvtu --stats-json ok/ok_1.vtu --out a.png
expect "--dump-counts: 'ok.pvtu' is the mesh being read" "$sm" render ok.pvtu --dump-counts ok.pvtu --out a.png
if ! cmp -s piece.bak ok/ok_1.vtu; then echo "FAIL: the input piece was overwritten"; fails=$((fails + 1)); fi
expect "--stats-json: './a.png' is also the file of --out" "$sm" render ok.pvtu --stats-json ./a.png --out a.png
# The statistics may not be a numbered frame of a sequence either (--orbit 2 writes a_0000.png and
# a_0001.png, --heatmaps h h_0000_all.png ...).
expect "--stats-json: 'a_0001.png' is also the name of a numbered frame of --out" \
  "$sm" render ok.pvtu --orbit 2 --stats-json a_0001.png --out a.png
expect "--stats-json: 'h_0001_all.png' is also the name of a numbered frame of --heatmaps" \
  "$sm" render ok.pvtu --orbit 2 --heatmaps h --stats-json h_0001_all.png --out a.png
# --time all of a single step is a sequence all the same: seq_0000.png, not seq.png.
"$sm" render ok.pvtu --time all --size 16x16 --out seq.png
[ -e seq_0000.png ] && [ ! -e seq.png ] ||
  { echo "FAIL: --time all of one step did not write seq_0000.png alone"; fails=$((fails + 1)); }
# Without --step the step comes from the mesh: faults name the mesh or the view, not --step.
sed -e 's/0 0 0 1 0 0 0 1 0 0 0 1/0 0 0 1 0 0 0 1 0 1 1 0/' -e 's/Name="f&#10;[^"]*"/Name="f"/' forged.vtu > flat.vtu
expect "flat.vtu: every element has zero volume" "$sm" render flat.vtu --out a.png
expect "--step: the default sample step" "$sm" render ok.pvtu --eye 1e9,0,0 --out a.png
mkdir -p cmap.json
expect "cmap.json" "$sm" render ok.pvtu --colormap cmap.json --out a.png
# A preset file of several maps: FILE.json:NAME picks one; a name it lacks is refused, naming those
# it holds.
echo '[{"Name": "a", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]}, {"Name": "b", "RGBPoints": [0, 1, 0, 0, 1, 0, 0, 1]}]' > presets.json
cp presets.json PRESETS.JSON  # the extension in capitals, as ParaView on Windows may write it
"$sm" render ok.pvtu --colormap PRESETS.JSON:b --size 16x16 --out preset.png ||
  { echo "FAIL: --colormap presets.json:b"; fails=$((fails + 1)); }
expect "presets.json: has no colour map named 'c' (it holds 'a', 'b')" "$sm" render ok.pvtu --colormap presets.json:c --out a.png
# Cell data only (what finite-volume solvers write): a .vtu's renders without --field, its first
# array (app.cell-data renders it: this test runs no renders, as the sanitizer build runs it and
# the driver leaks); a legacy file's, whose cell data is known only by reading it, is named as
# cell data, not as a missing field, when no field is given.
sed -e '/Name="f&#10;/{s/Name="[^"]*"/Name="pressure"/;s/>0 1 2 3</>7</;}' -e 's/PointData/CellData/g' forged.vtu > cells.vtu
printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nCELL_DATA 1\nSCALARS pressure float 1\nLOOKUP_TABLE default\n7\n' > cells.vtk
expect "cells.vtk: has no point fields to render; its cell data (pressure) is read when --field names it" "$sm" render cells.vtk --out a.png
if ! "$sm" info cells.vtu | grep -q "cell data  *pressure (--field NAME renders it"; then
  echo "FAIL: info does not list the cell data"; fails=$((fails + 1))
fi
# The bounds are those of what renders: a far point only a line uses is not in them, and a file of
# surfaces alone has none.
printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 double\n0 0 0 1 0 0 0 1 0 0 0 1 1e38 0 0 0 0 0\nCELLS 3 12\n4 0 1 2 3\n2 3 4\n3 0 1 2\nCELL_TYPES 3\n10\n3\n5\n' > stray.vtk
if ! "$sm" info stray.vtk 2>/dev/null | grep -q "bounds  *x \[0, 1\]  y \[0, 1\]  z \[0, 1\]$"; then
  echo "FAIL: info's bounds include a point no element uses"; fails=$((fails + 1))
fi
printf '# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n' > surface.vtk
if ! "$sm" info surface.vtk 2>/dev/null | grep -q "bounds  *none (no volume elements)"; then
  echo "FAIL: info on surfaces alone does not say there are no bounds"; fails=$((fails + 1))
fi
if ! "$sm" info surface.vtk --json 2>/dev/null | grep -q '"bounds": null'; then
  echo "FAIL: info --json on surfaces alone does not give null bounds"; fails=$((fails + 1))
fi
# A component of a vector field is a field when named (FORMATS.md; app.cell-data renders one).
sed -e '/Name="f&#10;/{s/Name="[^"]*"/Name="v" NumberOfComponents="2"/;s/>0 1 2 3</>0 1 2 3 4 5 6 7</;}' forged.vtu > vec.vtu
expect "vec.vtu: field 'v[2]': point array 'v' has 2 components" "$sm" render vec.vtu --field 'v[2]' --out a.png
# Camera and option faults are named for the option at fault, before the step is derived from them.
expect "--fovy: 0 degrees is not in (0, 180)" "$sm" render ok.pvtu --fovy 0 --out a.png
expect "--view and --up: give one" "$sm" render ok.pvtu --view +z --up 0,1,0 --out a.png
expect "--up: 0,0,0 is the zero vector" "$sm" render ok.pvtu --eye 3,3,3 --up 0,0,0 --out a.png
expect "--eye: components beyond 1e30" "$sm" render ok.pvtu --eye 1e39,0,1 --step 1e38 --out a.png
expect "--eye: 0.5,0.5,0.5 is the centre of the data" "$sm" render ok.pvtu --eye 0.5,0.5,0.5 --out a.png
expect "in [0, 100]" "$sm" render ok.pvtu --shading-params 1e39,0,0,20 --out a.png
expect "--steps: must be between 1 and 10000" "$sm" generate --analytic single-tet --steps 100000000 --out s.pvtu
# Standard output that cannot be written (a full disk): an error, not a truncated success.
if out=$("$sm" info ok.pvtu 2>&1 >/dev/full); then echo "FAIL: info > /dev/full exited 0"; fails=$((fails + 1)); fi
grep -qF "cannot write to standard output" <<<"$out" || { echo "FAIL: no message for /dev/full: $out"; fails=$((fails + 1)); }
# A flag that prints and ends the run is not an error.
if ! "$sm" view --help-script >/dev/null 2>err.txt || [ -s err.txt ]; then
  echo "FAIL: view --help-script:"; cat err.txt; fails=$((fails + 1))
fi
# Names from a file are printed as one printable line by info too.
if "$sm" info forged.vtu 2>/dev/null | grep -q '^shellmarch: error: forged'; then
  echo "FAIL: info printed a field name's newline"; fails=$((fails + 1))
fi
expect "ok.pvtu: its pieces are its clusters; a cluster array ('x')" "$sm" render ok.pvtu --cluster-array x --out a.png
expect "--clusters and --cluster-array: give one" "$sm" render ok.pvtu --cluster-array x --clusters 2 --out a.png
usage "--field: must not be empty" "$sm" render ok.pvtu --field '' --out a.png
usage "--device: must not be empty" "$sm" render ok.pvtu --device '' --out a.png
# Every option that takes a value refuses an empty one (an unset shell variable), in either form;
# bench's --exact '' means "no such runs" and stays allowed.
usage "--range: must not be empty" "$sm" render ok.pvtu --range '' --out a.png
usage "--step: must not be empty" "$sm" render ok.pvtu --step '' --out a.png
usage "--opacity: must not be empty" "$sm" render ok.pvtu --opacity= --out a.png
usage "--eye: must not be empty" "$sm" view ok.pvtu --headless --eye '' --script s.txt
usage "--sizes: must not be empty" "$sm" bench render --sizes '' --exact ''
expect "nope.vtu: cannot open" "$sm" bench render --exact= --coarser= --mesh nope.vtu --no-vtk --work-dir bw
# No Vulkan driver at all (the loader finds none to load): said in words, not as a raw VkResult.
# Without validation, whose messenger would add the loader's own lines.
expect "no Vulkan driver could be loaded" env -u SHELLMARCH_VALIDATION VK_DRIVER_FILES=/nonexistent/icd.json \
  VK_ICD_FILENAMES=/nonexistent/icd.json "$sm" render ok.pvtu --out nodriver.png
if [ -e nodriver.png ]; then echo "FAIL: an image was written without a driver"; fails=$((fails + 1)); fi
# A benchmark's --json is checked before it measures anything.
usage "--json: 'nodir/x.json' is in a folder that does not exist" "$sm" bench prep --json nodir/x.json --no-vtk --work-dir bp
usage "--json: 'sdir.json' is a folder" "$sm" bench render --json sdir.json --no-vtk --work-dir bw
if [ -e bp ]; then echo "FAIL: bench prep worked before refusing --json"; fails=$((fails + 1)); fi
usage "--screenshot: 'v.jpg' must end in .png" "$sm" view ok.pvtu --headless --frames 1 --screenshot v.jpg
# The reliability tests' fault hook refuses what it cannot do, in one line, before any image.
expect "SHELLMARCH_FAULT: action=stall goes with at=read-ahead" \
  env SHELLMARCH_FAULT=at=read-ahead,action=kill "$sm" render ok.pvtu --out a.png
expect "SHELLMARCH_FAULT: action=stall goes with at=read-ahead" \
  env SHELLMARCH_FAULT=at=frame,frame=0,action=stall "$sm" render ok.pvtu --out a.png
expect "SHELLMARCH_FAULT: action=close or next-field goes with at=range-pass" \
  env SHELLMARCH_FAULT=at=range-pass,action=throw "$sm" render ok.pvtu --out a.png
expect "SHELLMARCH_FAULT: action=close or next-field goes with at=range-pass" \
  env SHELLMARCH_FAULT=at=write,action=close "$sm" render ok.pvtu --out a.png
expect "SHELLMARCH_FAULT: action=close or next-field goes with at=range-pass" \
  env SHELLMARCH_FAULT=at=frame,frame=0,action=next-field "$sm" render ok.pvtu --out a.png
expect "SHELLMARCH_FAULT: cannot use 'at=bogus'" \
  env SHELLMARCH_FAULT=at=bogus,action=kill "$sm" render ok.pvtu --out a.png
# Tracers: a bad name, a device without the tracer asked for (ray queries hidden from lavapipe),
# one with neither, and a ray tracing pipeline the driver fails to create.
expect "--tracer: 'rtx' is not auto, query or pipeline" "$sm" render ok.pvtu --tracer rtx --out a.png
expect "--tracer: 'rtx' is not auto, query or pipeline" "$sm" bench render --mesh ok.pvtu --tracer rtx \
  --no-vtk --sizes 16 --work-dir bw
expect "for the query tracer: [0] llvmpipe" \
  env SHELLMARCH_HIDE=ray_query "$sm" render ok.pvtu --tracer query --out a.png
expect "lacks ray queries (VK_KHR_ray_query (hidden)) and a ray tracing pipeline (VK_KHR_ray_tracing_pipeline (hidden))" \
  env SHELLMARCH_HIDE=ray_query,ray_tracing_pipeline "$sm" render ok.pvtu --out a.png
expect "SHELLMARCH_HIDE: 'rt_cores' is not ray_query" env SHELLMARCH_HIDE=rt_cores "$sm" render ok.pvtu --out a.png
expect "failed to create the ray tracing pipeline 'trace and march (count, store) (ray tracing pipeline)' (VK_ERROR_INITIALIZATION_FAILED)" \
  env SHELLMARCH_FAIL_RAY_TRACING_PIPELINE=1 "$sm" render ok.pvtu --tracer pipeline --out a.png
expect "--tracers: llvmpipe" env SHELLMARCH_HIDE=ray_tracing_pipeline "$sm" bench tracers --analytic cube-tets6 \
  --cube-n 2 --tracers pipeline --sizes 16
printf 'not a mesh' > garbage.vtu
expect "garbage.vtu" "$sm" render garbage.vtu --out a.png
if ls a.png a.jpg 2>/dev/null | grep -q .; then echo "FAIL: an output image was written"; fails=$((fails + 1)); fi
exit $fails
