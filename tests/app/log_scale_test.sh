#!/usr/bin/env bash
# A log scale (`render --log-scale`, `view --log-scale`), run by ctest with
#   log_scale_test.sh SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# A field over a range of two and a half decades agrees with the CPU reference on the same scale
# and on 1 and 3 ranks, and differs from the linear image; --stats-json and the legend say so; the
# viewer's report carries the scale in its render arguments (render draws its screenshot with
# them) and drops it for a field whose range is not positive; element-exact integration takes it
# too; ranges that are not positive are one-line errors.
set -euo pipefail
sm=$1 diff=$2 refcheck=$3 work=$4
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.png ./*.json ./*.log ./*.txt
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

W=64 H=48 STEP=0.02 UNIT=0.3 LO=0.01 HI=4.2 CMAP=viridis
EYE=2.2,-1.6,1.4 AT=0.5,0.5,0.5 UP=0,0,1 FOVY=35
tf=(--field shock --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
    --eye $EYE --at $AT --up $UP --fovy $FOVY --background 0,0,0 --early-termination 1)
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --out cube.pvtu >/dev/null

# Sampled: the reference takes the same samples.
for n in 1 3; do
  mpi $n "$sm" render cube.pvtu "${tf[@]}" --log-scale --integration sampled --stats-json log$n.json \
    --out log$n.pfm >/dev/null
done
"$diff" log1.pfm log3.pfm --max-abs 1e-5
REFERENCE_CHECK_LOG=1 "$refcheck" cube.pvtu shock log1.pfm $W $H $STEP $UNIT $LO $HI \
  $CMAP ${EYE//,/ } ${AT//,/ } ${UP//,/ } $FOVY 0.0039 0
json log3.json "j['log_scale'] is True"
# Element-exact integration on the same scale, on 1 and 3 ranks; close to the sampled image (the
# step is small), and not the linear one.
for n in 1 3; do
  mpi $n "$sm" render cube.pvtu "${tf[@]}" --log-scale --integration exact --out exact$n.pfm >/dev/null
done
# Ranks work in their own rebased coordinates, so crossings and scalars differ by rounding, which
# the pre-integration's difference of cumulative tables amplifies for the smallest changes it takes
# (PreintegrationTable::kSmallDelta): measured 2.6e-6 at most (1.9e-5 while the log scale's
# threshold was ln(hi / lo) times finer than the linear one's).
"$diff" exact1.pfm exact3.pfm --max-abs 1e-5
"$diff" exact1.pfm log1.pfm --max-rmse 0.01
# The linear image of the same range is another one (the field's values sit in its first tenth).
"$sm" render cube.pvtu "${tf[@]}" --stats-json linear.json --out linear.pfm >/dev/null
"$diff" linear.pfm log1.pfm --min-max-abs 0.05
json linear.json "j['log_scale'] is False"
# The legend's title says "(log)": it is wider, so the two legends differ.
"$sm" render cube.pvtu "${tf[@]}" --log-scale --legend --out legend_log.png >/dev/null
"$sm" render cube.pvtu "${tf[@]}" --legend --out legend_linear.png >/dev/null
"$diff" legend_log.png legend_linear.png --min-max-abs 0.5

# The viewer: its render arguments carry the scale, and render draws its screenshot with them.
view() {
  "$sm" view cube.pvtu "${tf[@]}" --log-scale --headless --print-camera "$@"
}
view --frames 1 --screenshot view.png > view.json
args=$(python3 -c "import json; print(' '.join(json.loads(open('view.json').read().splitlines()[-1])['render_args']))")
[[ " $args " == *" --log-scale "* ]] || fail "the viewer's render arguments lack --log-scale: $args"
# shellcheck disable=SC2086
"$sm" render cube.pvtu $args --background 0,0,0 --out render.png >/dev/null
"$diff" view.png render.png --max-abs 0.004
# The next field is 'linear', over [0, 1]: no log scale for it, and none in its arguments.
printf 'key f\nframe\nquit\n' > next_field.txt
view --script next_field.txt --screenshot next.png > next.json
python3 - <<'PY' || fail "the viewer kept the log scale for a field whose range starts at 0"
import json
report = json.loads(open('next.json').read().splitlines()[-1])
args = report['render_args']
assert '--field=linear' in args, args
assert '--log-scale' not in args, args
PY

# The g key turns the scale on in a viewer started without it (and off again), with opacity
# points too, whose table entries move with the scale: render draws each screenshot from the
# viewer's render arguments.
keyed() {  # NAME SCRIPT: the screenshot NAME.png and the render arguments in NAME.json
  printf "$2" > "$1.txt"
  "$sm" view cube.pvtu "${tf[@]}" --opacity 1:0,1.5:0.8,4:0.2 --headless --print-camera \
    --script "$1.txt" --screenshot "$1.png" > "$1.json"
  python3 -c "import json; print(' '.join(json.loads(open('$1.json').read().splitlines()[-1])['render_args']))"
}
on=$(keyed key_on 'key g\nframe\nquit\n')
off=$(keyed key_off 'key g\nframe\nkey g\nframe\nquit\n')
[[ " $on " == *" --log-scale "* ]] || fail "g did not turn the log scale on: $on"
[[ " $off " != *" --log-scale "* ]] || fail "g again did not turn it off: $off"
# shellcheck disable=SC2086
"$sm" render cube.pvtu $on --background 0,0,0 --out render_key_on.png >/dev/null
# shellcheck disable=SC2086
"$sm" render cube.pvtu $off --background 0,0,0 --out render_key_off.png >/dev/null
"$diff" key_on.png render_key_on.png --max-abs 0.004
"$diff" key_off.png render_key_off.png --max-abs 0.004
"$diff" key_on.png key_off.png --min-max-abs 0.05

# Bad combinations: one line naming --log-scale, a non-zero exit, nothing written.
bad() { refused "$1" bad.pfm "$sm" render cube.pvtu "${@:2}" --size 16x16 --out bad.pfm; }
bad "--log-scale: field 'linear' has the range 0 .. 1, and a log scale needs a positive one" \
  --field linear --log-scale
# Without --field, the message names the field shown (the file's first).
bad "--log-scale: field 'linear' has the range 0 .. 1, and a log scale needs a positive one" \
  --log-scale
bad "--log-scale: field 'shock' has the range -1 .. 4, and a log scale needs a positive one" \
  --field shock --range -1,4 --log-scale
refused "--log-scale: field 'linear' has the range 0 .. 1" bad.png \
  "$sm" view cube.pvtu --field linear --log-scale --headless --frames 1 --screenshot bad.png
echo "log scale: all checks passed"
