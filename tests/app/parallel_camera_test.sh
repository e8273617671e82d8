#!/usr/bin/env bash
# Parallel projection (`--parallel`, `--parallel-scale`) and ParaView camera files (`--camera`,
# `view --save-camera`) on the command line, run by ctest with
#   parallel_camera_test.sh SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# A parallel render agrees on 1 and 2 ranks (interlocking METIS clusters), with the CPU reference,
# and between the two tracers bit for bit; a .pvcc in ParaView's format gives the render of the
# options it holds; the viewer writes a .pvcc that renders the frame it showed; bad files and
# combinations are one-line errors.
set -euo pipefail
sm=$1 diff=$2 refcheck=$3 work=$4
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.png ./*.json ./*.log ./*.pvcc
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

W=64 H=48 STEP=0.02 UNIT=0.3 LO=0 HI=1 CMAP=viridis
EYE=2.2,-1.6,1.4 AT=0.5,0.5,0.5 UP=0,0,1 FOVY=30 SCALE=0.8
tf=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
    --background 0,0,0 --early-termination 1 --integration sampled)  # the reference's samples
cam=(--eye $EYE --at $AT --up $UP --parallel-scale $SCALE)
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --out cube.pvtu >/dev/null

# 1 and 2 ranks; both tracers; the reference.
for n in 1 2; do
  mpi $n "$sm" render cube.pvtu "${tf[@]}" "${cam[@]}" --stats-json par$n.json --out par$n.pfm >/dev/null
  mpi $n "$sm" render cube.pvtu "${tf[@]}" "${cam[@]}" --tracer pipeline --out par$n-pipeline.pfm \
    >/dev/null
  cmp par$n.pfm par$n-pipeline.pfm || fail "$n rank(s): the pipeline tracer's parallel image differs"
done
"$diff" par1.pfm par2.pfm --max-abs 1e-5
json par1.json "j['tracer'] == 'query' and j['frames'][0]['lost_rays'] == 0"
json par2.json "j['frames'][0]['lost_rays'] == 0"
REFERENCE_CHECK_PARALLEL_SCALE=$SCALE "$refcheck" cube.pvtu vortex par1.pfm $W $H $STEP $UNIT \
  $LO $HI $CMAP ${EYE//,/ } ${AT//,/ } ${UP//,/ } $FOVY 0.0039 0
# It is not the perspective image (the reference would catch a perspective render too, but not
# by much at this distance).
"$sm" render cube.pvtu "${tf[@]}" --eye $EYE --at $AT --up $UP --out persp.pfm >/dev/null
"$diff" par1.pfm persp.pfm --min-max-abs 0.05

# --parallel alone frames the data as the perspective view does: the whole cube, centred.
"$sm" render cube.pvtu "${tf[@]}" --parallel --view +x --out framed.pfm >/dev/null
# frameBounds' scale: the radius, sqrt(3)/2, times 1.02 (the image is wider than high).
"$sm" render cube.pvtu "${tf[@]}" --parallel --view +x --parallel-scale 0.88334591186 --out scaled.pfm \
  >/dev/null
"$diff" framed.pfm scaled.pfm --max-abs 1e-4
"$sm" render cube.pvtu "${tf[@]}" --parallel --view +x --parallel-scale 0.6 --out tight.pfm >/dev/null
"$diff" framed.pfm tight.pfm --min-max-abs 0.05

# A camera file as ParaView writes it (File > Save Camera) holds the same camera.
cat > paraview.pvcc <<EOF
<?xml version="1.0"?>
<PVCameraConfiguration description="ParaView camera configuration" version="1.0">
  <Proxy group="views" type="RenderView" id="4872" servers="21">
    <Property name="CameraPosition" id="4872.CameraPosition" number_of_elements="3">
      <Element index="0" value="2.2"/>
      <Element index="1" value="-1.6"/>
      <Element index="2" value="1.4"/>
    </Property>
    <Property name="CameraFocalPoint" id="4872.CameraFocalPoint" number_of_elements="3">
      <Element index="0" value="0.5"/>
      <Element index="1" value="0.5"/>
      <Element index="2" value="0.5"/>
    </Property>
    <Property name="CameraViewUp" id="4872.CameraViewUp" number_of_elements="3">
      <Element index="0" value="0"/>
      <Element index="1" value="0"/>
      <Element index="2" value="1"/>
    </Property>
    <Property name="CenterOfRotation" id="4872.CenterOfRotation" number_of_elements="3">
      <Element index="0" value="0.5"/>
      <Element index="1" value="0.5"/>
      <Element index="2" value="0.5"/>
    </Property>
    <Property name="RotationFactor" id="4872.RotationFactor" number_of_elements="1">
      <Element index="0" value="1"/>
    </Property>
    <Property name="CameraViewAngle" id="4872.CameraViewAngle" number_of_elements="1">
      <Element index="0" value="30"/>
    </Property>
    <Property name="CameraParallelScale" id="4872.CameraParallelScale" number_of_elements="1">
      <Element index="0" value="0.8"/>
    </Property>
    <Property name="CameraParallelProjection" id="4872.CameraParallelProjection" number_of_elements="1">
      <Element index="0" value="1"/>
      <Domain name="bool" id="4872.CameraParallelProjection.bool"/>
    </Property>
  </Proxy>
</PVCameraConfiguration>
EOF
mpi 2 "$sm" render cube.pvtu "${tf[@]}" --camera paraview.pvcc --out file.pfm >/dev/null
"$diff" file.pfm par2.pfm --max-abs 1e-5
# Options override the file's values.
"$sm" render cube.pvtu "${tf[@]}" --camera paraview.pvcc --parallel-scale 1.1 --out over.pfm >/dev/null
"$sm" render cube.pvtu "${tf[@]}" --eye $EYE --at $AT --up $UP --parallel-scale 1.1 --out explicit.pfm \
  >/dev/null
cmp over.pfm explicit.pfm || fail "--parallel-scale did not override the camera file's"

# The viewer: starts from the file, writes the camera it ends with; rendering that file gives the
# frame it showed. The p key turns parallel off, keeping the size at the point looked at.
"$sm" view cube.pvtu "${tf[@]}" --camera paraview.pvcc --headless --frames 1 --screenshot view.png \
  --save-camera saved.pvcc --print-camera > view.json
json view.json "j['parallel'] is True and abs(j['parallel_scale'] - 0.8) < 1e-15"
json view.json "'--parallel-scale=0.80000000000000004' in j['render_args']"
grep -q '<PVCameraConfiguration description="ParaView camera configuration" version="1.0">' saved.pvcc ||
  fail "saved.pvcc is not a ParaView camera file"
"$sm" render cube.pvtu "${tf[@]}" --camera saved.pvcc --out saved.png >/dev/null
"$diff" view.png saved.png --max-abs 0.004
"$sm" render cube.pvtu "${tf[@]}" --camera saved.pvcc --out saved.pfm >/dev/null
cmp saved.pfm par1.pfm || fail "the saved camera renders another image"
printf 'key p\nframe\n' > toggle.txt
"$sm" view cube.pvtu "${tf[@]}" --camera paraview.pvcc --headless --script toggle.txt \
  --save-camera toggled.pvcc --print-camera > toggled.json
json toggled.json "j['parallel'] is False"
python3 - <<'PY' || fail "the p key did not keep the size at the point looked at"
import json, math
j = json.load(open('toggled.json'))
d = math.dist(j['eye'], j['at'])
assert abs(d * math.tan(math.radians(j['fovy']) / 2) - 0.8) < 1e-12, d
PY
grep -q 'name="CameraParallelProjection"' toggled.pvcc || fail "toggled.pvcc has no projection"

# Bad files and combinations: one line naming the file and the property, nothing written.
bad() { refused "$1" bad.pfm "$sm" render cube.pvtu "${tf[@]}" "${@:2}" --out bad.pfm; }
sed 's/name="CameraViewUp"/name="ViewUp"/' paraview.pvcc > noup.pvcc
bad "noup.pvcc: property CameraViewUp is missing" --camera noup.pvcc
sed 's/value="-1.6"/value="minus"/' paraview.pvcc > word.pvcc
bad "word.pvcc: property CameraPosition: element 1 value 'minus' is not a finite number" --camera word.pvcc
sed 's/PVCameraConfiguration/CustomViewpointsConfiguration/g' paraview.pvcc > root.pvcc
bad "root.pvcc: the root element is <CustomViewpointsConfiguration>" --camera root.pvcc
head -c 600 paraview.pvcc > cut.pvcc
bad "cut.pvcc: is not well-formed XML" --camera cut.pvcc
bad "missing.pvcc" --camera missing.pvcc
bad "--view and --camera: give one" --camera paraview.pvcc --view iso
bad "--parallel-scale: " --parallel-scale 0
bad "--parallel-scale: " --parallel-scale abc
echo "parallel camera: all checks passed"
