#!/usr/bin/env bash
# Opacity control points (`render --opacity`, `view --opacity`), run by ctest with
#   opacity_test.sh SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# A window of the field's values made opaque agrees with the CPU reference given the same points
# and on 1 and 3 ranks; zero opacity everywhere leaves no fragment; the viewer's report carries
# the points in its render arguments and render draws its screenshot with them; bad points are
# one-line errors.
set -euo pipefail
sm=$1 diff=$2 refcheck=$3 work=$4
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.png ./*.json ./*.log
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

W=64 H=48 STEP=0.02 UNIT=0.3 LO=0 HI=1 CMAP=viridis
EYE=2.2,-1.6,1.4 AT=0.5,0.5,0.5 UP=0,0,1 FOVY=35
tf=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
    --eye $EYE --at $AT --up $UP --fovy $FOVY --background 0,0,0 --early-termination 1
    --integration sampled)  # the reference's samples
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --out cube.pvtu >/dev/null

POINTS=0.3:0,0.45:0.9,0.6:0.9,0.7:0
for n in 1 3; do
  mpi $n "$sm" render cube.pvtu "${tf[@]}" --opacity $POINTS --out window$n.pfm >/dev/null
done
"$diff" window1.pfm window3.pfm --max-abs 1e-5
REFERENCE_CHECK_OPACITY=$POINTS "$refcheck" cube.pvtu vortex window1.pfm $W $H $STEP $UNIT $LO $HI \
  $CMAP ${EYE//,/ } ${AT//,/ } ${UP//,/ } $FOVY 0.0039 0
# The points replace the colour map's ramp: the image is not the default one.
"$sm" render cube.pvtu "${tf[@]}" --out ramp.pfm >/dev/null
"$diff" ramp.pfm window1.pfm --min-max-abs 0.05

# Nothing opaque, nothing drawn: no fragment on any rank.
mpi 3 "$sm" render cube.pvtu "${tf[@]}" --opacity 0:0 --stats-json none.json --out none.pfm >/dev/null
json none.json "sum(r['fragments'] for r in j['frames'][0]['ranks']) == 0"
json none.json "j['opacity_points'] == [[0, 0]]"

# The viewer: its render arguments carry the points, and render draws its screenshot with them.
"$sm" view cube.pvtu "${tf[@]}" --opacity $POINTS --headless --frames 1 --print-camera \
  --screenshot view.png > view.json
args=$(python3 -c "import json; print(' '.join(json.loads(open('view.json').read().splitlines()[-1])['render_args']))")
[[ "$args" == *"--opacity=0.29999999999999999:0,0.45000000000000001:0.90000000000000002"* ]] ||
  fail "the viewer's render arguments lack the opacity points: $args"
# shellcheck disable=SC2086
"$sm" render cube.pvtu $args --background 0,0,0 --out render.png >/dev/null
"$diff" view.png render.png --max-abs 0.004

# Bad points: one line naming --opacity, a non-zero exit, nothing written.
bad() { refused "$1" bad.pfm "$sm" render cube.pvtu "${tf[@]}" "${@:2}" --out bad.pfm; }
bad "--opacity: '0.5' is not VALUE:OPACITY" --opacity 0.5
bad "--opacity: point 2 (0.5:1.5) needs a finite value and an opacity in [0, 1]" --opacity 0:0,0.5:1.5
bad "--opacity: point 2 (value 0.2) comes before point 1 (value 0.4)" --opacity 0.4:1,0.2:0
bad "--opacity: 'x' is not a finite number" --opacity x:1
echo "opacity: all checks passed"
