#!/usr/bin/env bash
# Camera orbits (`render --orbit N`), run by ctest with
#   orbit_test.sh SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# One step: N frames, one turn about the up axis through the point looked at, numbered from 0;
# several steps: a frame per step, numbered by step, the camera turning 360/N degrees a frame.
# Each frame is bit for bit the single render from the eye its statistics report, on 1 rank and
# on 3, and agrees with the CPU reference from that eye; bad counts are one-line errors.
set -euo pipefail
sm=$1 diff=$2 refcheck=$3 work=$4
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.json ./*.log
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"
# Frame k's eye as the statistics wrote it (every digit: the same double on the command line).
eye() { python3 -c "import json,sys; print(','.join(repr(v) for v in json.load(open(sys.argv[1]))['frames'][int(sys.argv[2])]['eye']))" "$1" "$2"; }

W=64 H=48 STEP=0.02 UNIT=0.3 LO=0 HI=1 CMAP=viridis
EYE=2.2,-1.6,1.4 AT=0.5,0.5,0.5 UP=0,0,1 FOVY=35
tf=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
    --at $AT --up $UP --fovy $FOVY --background 0,0,0 --early-termination 1
    --integration sampled)  # the reference's samples
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --steps 4 --out steps.pvtu

# One step: four frames a quarter turn apart. The eye keeps its height and its distance to the
# point looked at, and turns counter-clockwise seen from above (up = +z).
for n in 1 3; do
  mpi $n "$sm" render steps.pvtu "${tf[@]}" --eye $EYE --orbit 4 --stats --stats-json orbit$n.json \
    --out orbit$n.pfm > orbit$n.log
  [ ! -e orbit${n}_0004.pfm ] || fail "--orbit 4 wrote a fifth frame ($n rank(s))"
  json orbit$n.json "[f['frame'] for f in j['frames']] == [0, 1, 2, 3] and all(f['step'] == 0 for f in j['frames'])"
  # Only the camera changes: the scene is built once and its scalars uploaded once.
  json orbit$n.json "j['sequence']['geometry_builds'] == {'min': 1, 'max': 1} and j['sequence']['scalar_uploads']['max'] == 1"
  grep -q "^  frame 1 (step 0, eye 2.6,2.2,1.4): " orbit$n.log || { cat orbit$n.log; fail "no line for frame 1 in orbit$n.log"; }
  grep -q "sequence: 4 frames x 1 run(s)" orbit$n.log || fail "no sequence line in orbit$n.log"
  json orbit$n.json "[[round(v, 9) for v in f['eye']] for f in j['frames']] == [[2.2, -1.6, 1.4], [2.6, 2.2, 1.4], [-1.2, 2.6, 1.4], [-1.6, -1.2, 1.4]]"
  for k in 0 1 2 3; do
    mpi $n "$sm" render steps.pvtu "${tf[@]}" --eye "$(eye orbit$n.json $k)" --out single${n}_$k.pfm
    cmp single${n}_$k.pfm orbit${n}_000$k.pfm || fail "orbit frame $k on $n rank(s) is not the render from its eye"
  done
done
for k in 0 1 2 3; do
  "$diff" orbit1_000$k.pfm orbit3_000$k.pfm --max-abs 1e-5
  IFS=, read -r ex ey ez <<< "$(eye orbit1.json $k)"
  "$refcheck" steps.pvtu vortex orbit1_000$k.pfm $W $H $STEP $UNIT $LO $HI $CMAP $ex $ey $ez ${AT//,/ } \
    ${UP//,/ } $FOVY 0.0039 0
done
"$diff" orbit1_0000.pfm orbit1_0002.pfm --min-max-abs 0.05  # the views differ

# --orbit 1: one frame, the camera as given, written as a single image.
"$sm" render steps.pvtu "${tf[@]}" --eye $EYE --orbit 1 --out one.pfm
[ -e one.pfm ] || fail "--orbit 1 did not write one.pfm"
cmp one.pfm single1_0.pfm || fail "--orbit 1 is not the plain render"

# Several steps: a frame per step, numbered by step, an eighth of a turn apart.
mpi 3 "$sm" render steps.pvtu "${tf[@]}" --eye $EYE --time all --orbit 8 --stats-json turn.json --out turn.pfm
json turn.json "[f['step'] for f in j['frames']] == [0, 1, 2, 3]"
for k in 0 1 2 3; do
  mpi 3 "$sm" render steps.pvtu "${tf[@]}" --eye "$(eye turn.json $k)" --time $k --out turnstep_$k.pfm
  cmp turnstep_$k.pfm turn_000$k.pfm || fail "time-and-orbit frame $k is not step $k from its eye"
done
cmp turn_0002.pfm orbit3_0001.pfm && fail "step 2 looks like step 0"
python3 -c "
import json, math
f = json.load(open('turn.json'))['frames']
d = [math.atan2(e['eye'][1] - 0.5, e['eye'][0] - 0.5) for e in f]
steps = [(b - a) % (2 * math.pi) for a, b in zip(d, d[1:])]
assert all(abs(s - math.pi / 4) < 1e-9 for s in steps), steps
" || fail "frames of --time all --orbit 8 are not an eighth of a turn apart"

# Bad counts: one line naming the option, a non-zero exit, nothing written.
for bad in 0 -3 x; do
  if "$sm" render steps.pvtu "${tf[@]}" --eye $EYE --orbit $bad --out bad.pfm >bad.log 2>&1; then
    fail "--orbit $bad rendered"
  fi
  grep -q -- "--orbit" bad.log || { cat bad.log; fail "no message naming --orbit for $bad"; }
  [ "$(wc -l < bad.log)" -le 2 ] || { cat bad.log; fail "--orbit $bad: more than a line of error"; }
  if ls bad*.pfm >/dev/null 2>&1; then fail "--orbit $bad wrote an image"; fi
done
echo "orbit: all checks passed"
