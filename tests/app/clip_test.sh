#!/usr/bin/env bash
# Clip planes on the command line (`render --clip`, `view --clip`), run by ctest with
#   clip_test.sh SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# Clipped renders agree on 1 and 3 ranks (interlocking METIS clusters) and with the CPU reference
# clipped alike; the AXIS>V form is the 6-number plane it names; a cut that keeps everything is
# the plain render bit for bit; the viewer clips as render does; bad planes are one-line errors.
set -euo pipefail
sm=$1 diff=$2 refcheck=$3 work=$4
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.png ./*.json ./*.log ./*.txt
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

W=64 H=48 STEP=0.02 UNIT=0.3 LO=0 HI=1 CMAP=viridis
EYE=2.2,-1.6,1.4 AT=0.5,0.5,0.5 UP=0,0,1 FOVY=35
tf=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
    --eye $EYE --at $AT --up $UP --fovy $FOVY --background 0,0,0 --early-termination 1
    --integration sampled)  # the reference's samples
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --out cube.pvtu >/dev/null

CUT1=0.5,0.5,0.5,1,0.8,-0.6
for n in 1 3; do
  mpi $n "$sm" render cube.pvtu "${tf[@]}" --clip $CUT1 --clip 'x<0.8' --stats-json clip$n.json \
    --out clip$n.pfm >/dev/null
done
"$diff" clip1.pfm clip3.pfm --max-abs 1e-5
# The ray tracing pipeline's image is the ray queries' bit for bit, on 1 and 3 ranks.
for n in 1 3; do
  mpi $n "$sm" render cube.pvtu "${tf[@]}" --clip $CUT1 --clip 'x<0.8' --tracer pipeline \
    --stats-json clip$n-pipeline.json --out clip$n-pipeline.pfm >/dev/null
  cmp clip$n.pfm clip$n-pipeline.pfm || fail "$n rank(s): the pipeline tracer's clipped image differs"
done
json clip1.json "j['tracer'] == 'query'"
json clip3-pipeline.json "j['tracer'] == 'pipeline'"
json clip1.json "j['frames'][0]['lost_rays'] == 0"
json clip3.json "j['clip_planes'] == [{'point': [0.5, 0.5, 0.5], 'normal': [1, 0.8, -0.6]}, {'point': [0.8, 0, 0], 'normal': [-1, 0, 0]}]"
json clip3.json "j['frames'][0]['lost_rays'] == 0"
REFERENCE_CHECK_CLIP="$CUT1;0.8,0,0,-1,0,0" "$refcheck" cube.pvtu vortex clip1.pfm $W $H $STEP $UNIT \
  $LO $HI $CMAP ${EYE//,/ } ${AT//,/ } ${UP//,/ } $FOVY 0.0039 0

# The cut shows: the clipped image is not the plain one, and has fewer samples.
"$sm" render cube.pvtu "${tf[@]}" --stats-json plain.json --out plain.pfm >/dev/null
"$diff" plain.pfm clip1.pfm --min-max-abs 0.05
python3 -c "
import json, sys
s = lambda f: json.load(open(f))['frames'][0]['samples']
sys.exit(0 if s('clip1.json') < 0.8 * s('plain.json') else 1)" || fail "clipping did not reduce the samples"

# AXIS>V is the plane it names; a cut beyond the data keeps everything, bit for bit.
"$sm" render cube.pvtu "${tf[@]}" --clip 'y>0.4' --out axis.pfm >/dev/null
"$sm" render cube.pvtu "${tf[@]}" --clip 0,0.4,0,0,1,0 --out six.pfm >/dev/null
cmp axis.pfm six.pfm || fail "--clip 'y>0.4' differs from --clip 0,0.4,0,0,1,0"
"$sm" render cube.pvtu "${tf[@]}" --clip 'z>-5' --out all.pfm >/dev/null
cmp all.pfm plain.pfm || fail "a cut that keeps the whole volume changed the image"

# The viewer takes the same option and renders the same frame.
"$sm" view cube.pvtu "${tf[@]}" --clip $CUT1 --clip 'x<0.8' --headless --frames 1 --screenshot view.png \
  >/dev/null
"$sm" render cube.pvtu "${tf[@]}" --clip $CUT1 --clip 'x<0.8' --out render.png >/dev/null
"$diff" view.png render.png --max-abs 0.004

# Bad planes: one line naming --clip, a non-zero exit, nothing written.
bad() { refused "$1" bad.pfm "$sm" render cube.pvtu "${tf[@]}" "${@:2}" --out bad.pfm; }
bad "--clip: '0,0,0,0,0,0' has a zero normal" --clip 0,0,0,0,0,0
bad "--clip: '1,2,3' is not 6 finite numbers" --clip 1,2,3
bad "--clip: 'w>1' is not AXIS>VALUE or AXIS<VALUE" --clip 'w>1'
bad "--clip: 'nan' is not a finite number" --clip 'x>nan'
bad "--clip: 7 clip planes, at most 6" --clip 'x>0' --clip 'x>0' --clip 'x>0' --clip 'x>0' \
  --clip 'x>0' --clip 'x>0' --clip 'x>0'
echo "clip: all checks passed"
