#!/usr/bin/env bash
# Command-line tests of data-parallel rendering (issue 4): run by ctest with
#   compositing_test.sh CASE SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# The demo mesh is made once by the `demo` case (a ctest fixture) and shared.
set -euo pipefail
case_name=$1 sm=$2 diff=$3 refcheck=$4 work=$5 nested=${6:-}
mkdir -p "$work"
cd "$work"
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

# One camera and transfer function for every image, so that the CPU reference can redo them, and
# its samples (sampled integration).
W=96 H=72 STEP=0.06 UNIT=2.5 LO=0 HI=1 CMAP=cool-to-warm
EYE=-9,-11,6 AT=0.5,0,0 UP=0,0,1 FOVY=32
view=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
      --eye $EYE --at $AT --up $UP --fovy $FOVY --background 0,0,0 --early-termination 1
      --integration sampled)

case $case_name in
  demo)
    # The demo data set as the README's first command makes it.
    "$sm" generate --body capsule --elements 300000 --clusters 8 --steps 2 --hex-block --out demo.pvtu
    ;;
  partition-invariance)
    # docs/DESIGN.md invariant 4: any partition gives the same samples, so the composited image equals
    # the one-cluster image up to float rounding (1e-3 per channel), early termination off.
    "$sm" render demo.pvtu "${view[@]}" --clusters 1 --out one.pfm
    mpi 2 "$sm" render demo.pvtu "${view[@]}" --clusters 8 --out r2.pfm
    mpi 3 "$sm" render demo.pvtu "${view[@]}" --clusters 24 --out r3.pfm
    mpi 4 "$sm" render demo.pvtu "${view[@]}" --clusters 72 --stats --out r4.pfm
    for n in 2 3 4; do "$diff" one.pfm r$n.pfm --max-abs 1e-3; done
    # The ray tracing pipeline tracer gives the ray queries' images bit for bit on 1 to 4 ranks.
    "$sm" render demo.pvtu "${view[@]}" --clusters 1 --tracer pipeline --out one-pipeline.pfm
    mpi 2 "$sm" render demo.pvtu "${view[@]}" --clusters 8 --tracer pipeline --out r2-pipeline.pfm
    mpi 3 "$sm" render demo.pvtu "${view[@]}" --clusters 24 --tracer pipeline --out r3-pipeline.pfm
    mpi 4 "$sm" render demo.pvtu "${view[@]}" --clusters 72 --tracer pipeline --out r4-pipeline.pfm
    cmp one.pfm one-pipeline.pfm
    for n in 2 3 4; do cmp r$n.pfm r$n-pipeline.pfm; done
    # Which rank composites a pixel changes nothing in it: the paper's contiguous ranges give the
    # interleaved default's image bit for bit.
    mpi 3 "$sm" render demo.pvtu "${view[@]}" --clusters 24 --pixel-ownership ranges --out r3-ranges.pfm
    cmp r3.pfm r3-ranges.pfm
    # And the one-rank image is the CPU reference's.
    "$refcheck" demo.pvtu vortex one.pfm $W $H $STEP $UNIT $LO $HI $CMAP ${EYE//,/ } ${AT//,/ } ${UP//,/ } $FOVY
    ;;
  single-vs-deep)
    # Interleaved non-convex clusters on 3 ranks: deep compositing matches the one-rank image,
    # single-fragment (IceT-style) compositing visibly does not.
    "$sm" render demo.pvtu "${view[@]}" --clusters 1 --out one.pfm
    mpi 3 "$sm" render demo.pvtu "${view[@]}" --clusters 36 --out deep.pfm --l2-heatmap l2.png --heatmaps counts \
      --dump-counts counts.smfcnt
    mpi 3 "$sm" render demo.pvtu "${view[@]}" --clusters 36 --composite single --out single.pfm
    "$diff" one.pfm deep.pfm --max-abs 1e-3
    "$diff" one.pfm single.pfm --min-max-abs 0.02
    test -s l2.png && test -s counts_rank0.png && test -s counts_rank2.png && test -s counts_all.png
    # The frame's counts, for replaying the exchange at other rank counts: 3 ranks of W x H, every
    # rank with fragments (36 interleaved clusters), no unfinished part left behind.
    python3 - counts.smfcnt $W $H 3 <<'PY'
import struct, sys
path, w, h, ranks = sys.argv[1], *map(int, sys.argv[2:])
data = open(path, "rb").read()
assert data[:8] == b"SMFCNT01", "magic"
assert struct.unpack_from("<4I", data, 8) == (w, h, ranks, 0), "header"
assert len(data) == 24 + 4 * w * h * ranks, "size"
for r in range(ranks):
    counts = struct.unpack_from("<%dI" % (w * h), data, 24 + 4 * w * h * r)
    assert sum(counts) > 0, "rank %d has no fragments" % r
PY
    test ! -e counts.smfcnt.part
    ;;
  nested-and-empty)
    # Clusters enclosed by other clusters (an onion of three), one per rank: deep compositing gives
    # the one-rank image and the CPU reference's; single-fragment compositing does not. On 4 ranks
    # one rank holds no elements and still takes part.
    "$nested" nested.pvtu
    nview=(--size 80x64 --step 0.01 --unit-distance 0.3 --range 0,1 --colormap viridis
           --eye 2.2,-1.6,1.4 --at 0.5,0.5,0.5 --up 0,0,1 --fovy 35 --background 0,0,0 --early-termination 1
           --integration sampled)
    "$sm" render nested.pvtu --field vortex "${nview[@]}" --out n1.pfm
    mpi 3 "$sm" render nested.pvtu --field vortex "${nview[@]}" --stats --out n3.pfm | tee n3.log
    mpi 4 "$sm" render nested.pvtu --field vortex "${nview[@]}" --stats --out n4.pfm | tee n4.log
    # Without --field every rank renders rank 0's first field, the empty one too (it read none).
    "$sm" render nested.pvtu "${nview[@]}" --out n1first.pfm
    mpi 4 "$sm" render nested.pvtu "${nview[@]}" --out n4first.pfm
    mpi 3 "$sm" render nested.pvtu --field vortex "${nview[@]}" --composite single --out n3single.pfm
    grep -q "elements min 0 " n4.log || { echo "FAIL: no empty rank on 4 ranks"; exit 1; }
    "$diff" n1.pfm n3.pfm --max-abs 1e-3
    "$diff" n1.pfm n4.pfm --max-abs 1e-3
    "$diff" n1first.pfm n4first.pfm --max-abs 1e-3
    "$diff" n1.pfm n3single.pfm --min-max-abs 0.02
    "$refcheck" nested.pvtu vortex n1.pfm 80 64 0.01 0.3 0 1 viridis 2.2 -1.6 1.4 0.5 0.5 0.5 0 0 1 35
    ;;
  *) echo "unknown case $case_name" >&2; exit 2 ;;
esac
