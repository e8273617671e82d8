#!/usr/bin/env bash
# Time steps streamed from disk (issue 6, item 1), run by ctest with
#   time_steps_test.sh SHELLMARCH IMAGE_DIFF REFERENCE_CHECK WORKDIR
# `render --time all` on a multi-step .pvtu under 1 and 3 ranks writes every frame; each frame
# equals the single render of its step and the CPU reference of that step; the statistics hold
# per-frame times, fps over runs and the wait for the prefetch, and geometry is built once per rank.
set -euo pipefail
sm=$1 diff=$2 refcheck=$3 work=$4
mkdir -p "$work"
cd "$work"
rm -f ./*.pfm ./*.json
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

W=64 H=48 STEP=0.02 UNIT=0.3 LO=0 HI=1 CMAP=viridis
EYE=2.2,-1.6,1.4 AT=0.5,0.5,0.5 UP=0,0,1 FOVY=35
view=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --range $LO,$HI --colormap $CMAP
      --eye $EYE --at $AT --up $UP --fovy $FOVY --background 0,0,0 --early-termination 1
      --integration sampled)  # the reference's samples
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --steps 4 --out steps.pvtu

# Single renders of each step, checked against the CPU reference of that step (an independent
# reader: readMesh with every step in memory); the vortex moves, so the steps differ.
for k in 0 1 2 3; do
  "$sm" render steps.pvtu "${view[@]}" --time $k --out single_$k.pfm
  "$refcheck" steps.pvtu vortex single_$k.pfm $W $H $STEP $UNIT $LO $HI $CMAP ${EYE//,/ } ${AT//,/ } \
    ${UP//,/ } $FOVY 0.0039 $k
done
"$diff" single_0.pfm single_3.pfm --min-max-abs 0.05

for n in 1 3; do
  mpi $n "$sm" render steps.pvtu "${view[@]}" --time all --stats --stats-json seq$n.json \
    --out seq$n.pfm | tee seq$n.log
  for k in 0 1 2 3; do "$diff" single_$k.pfm seq${n}_000$k.pfm --max-abs 1e-3; done
  grep -q "fps mean over runs" seq$n.log || fail "no fps line in seq$n.log"
  s=seq$n.json
  json $s "j['validation_errors'] == 0 and len(j['frames']) == 4"
  json $s "[f['step'] for f in j['sequence']['per_run'][0]['frames']] == [0, 1, 2, 3]"
  json $s "all(f['frame_ms'] >= f['render_ms'] > 0 for f in j['sequence']['per_run'][0]['frames'])"
  json $s "j['sequence']['fps_mean'] > 0 and j['sequence']['prefetch'] and j['sequence']['runs'] == 1"
  json $s "'scalar_wait_ms_mean' in j['sequence'] and 'prefetch_hidden' in j['sequence']"
  json $s "j['sequence']['geometry_builds'] == {'min': 1, 'max': 1}"
  # Every step's frame from the ray tracing pipeline tracer is the ray queries' bit for bit.
  mpi $n "$sm" render steps.pvtu "${view[@]}" --time all --tracer pipeline --out seq$n-pipeline.pfm >/dev/null
  for k in 0 1 2 3; do cmp seq${n}_000$k.pfm seq$n-pipeline_000$k.pfm; done
  json $s "j['sequence']['scalar_uploads'] == {'min': 4, 'max': 4}"
  # Host memory per rank: known on Linux, the peak after setup at least the peak after loading.
  json $s "0 < j['host_peak_bytes_after_load_per_rank']['min'] <= j['host_peak_bytes_after_setup_per_rank']['min']"
  grep -q "memory, largest rank: host peak .* MiB after loading" seq$n.log || fail "no memory line in seq$n.log"
done
# Every fragment is composited by exactly one rank, whichever owns its pixel.
json seq3.json "j['pixel_ownership'] == 'interleaved'"
json seq3.json "all(sum(r['fragments_composited'] for r in f['ranks']) == sum(r['fragments'] for r in f['ranks']) > 0 for f in j['frames'])"

# Several runs without prefetching: fps per run, images written once and unchanged.
mpi 3 "$sm" render steps.pvtu "${view[@]}" --time all --repeat 2 --no-prefetch --stats-json rep.json \
  --out rep.pfm
for k in 0 1 2 3; do "$diff" single_$k.pfm rep_000$k.pfm --max-abs 1e-3; done
json rep.json "j['sequence']['runs'] == 2 and len(j['sequence']['per_run']) == 2"
json rep.json "not j['sequence']['prefetch'] and j['sequence']['frames'] == 8"
json rep.json "j['sequence']['fps_stddev'] >= 0 and j['sequence']['fps_min'] <= j['sequence']['fps_max']"
json rep.json "j['sequence']['geometry_builds']['max'] == 1 and j['sequence']['scalar_uploads']['max'] == 8"

# The same steps written as solvers write a time series (a .pvtu per step, named by a .pvd with
# their times): streamed the same way, each frame bit for bit the .pvtu's frame on as many ranks.
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 5 --steps 4 --out series.pvd
"$sm" info series.pvd > series.info
grep -q "time series (ParaView .pvd) of 4 files" series.info || fail "info does not name the series"
grep -q "vortex: 4 steps" series.info || fail "info does not count the series' steps"
for n in 1 3; do
  mpi $n "$sm" render series.pvd "${view[@]}" --time all --stats-json series$n.json --out series$n.pfm
  for k in 0 1 2 3; do
    cmp series${n}_000$k.pfm seq${n}_000$k.pfm || fail "series frame $k on $n rank(s) is not the .pvtu's"
  done
  json series$n.json "j['sequence']['geometry_builds'] == {'min': 1, 'max': 1} and j['sequence']['prefetch']"
done
# --time picks steps by range and by time value (0, 1/3, 2/3, 1 here), the same frames as above;
# a time outside the data's is refused, on 1 rank and on 3, with nothing written.
mpi 1 "$sm" render steps.pvtu "${view[@]}" --time 1:3:2 --out range.pfm
[ ! -e range_0002.pfm ] || fail "--time 1:3:2 rendered step 2"
for k in 1 3; do "$diff" single_$k.pfm range_000$k.pfm --max-abs 1e-3; done
# A range or `all` is a numbered sequence even when it holds one step, so that a script's glob
# finds it; a single step K is the plain name.
mpi 1 "$sm" render steps.pvtu "${view[@]}" --time 2:2 --out one.pfm
[ -e one_0002.pfm ] && [ ! -e one.pfm ] || fail "--time 2:2 did not write one_0002.pfm alone"
"$diff" single_2.pfm one_0002.pfm --max-abs 1e-3
mpi 1 "$sm" render steps.pvtu "${view[@]}" --time t=0.3 --out at1.pfm
cmp at1.pfm single_1.pfm || fail "--time t=0.3 is not step 1"
mpi 3 "$sm" render series.pvd "${view[@]}" --time t=0.7 --out at2.pfm
cmp at2.pfm series3_0002.pfm || fail "--time t=0.7 of the series on 3 ranks is not its step 2"
for n in 1 3; do
  if mpi $n "$sm" render series.pvd "${view[@]}" --time t=1.5 --out late$n.pfm >late$n.log 2>&1; then
    fail "--time t=1.5 rendered on $n rank(s)"
  fi
  grep -q "\-\-time: 1.5 is outside the data's times (0 .. 1)" late$n.log || { cat late$n.log; fail "no --time message ($n rank(s))"; }
  [ ! -e late$n.pfm ] || fail "--time t=1.5 wrote an image ($n rank(s))"
done

# A step whose file holds another mesh is refused before any frame is written.
"$sm" generate --analytic cube-tets6 --cube-n 5 --clusters 5 --steps 4 --out smaller.pvd
sed 's|series/series_t2.pvtu|smaller/smaller_t2.pvtu|' series.pvd > grown.pvd
for n in 1 3; do
  if mpi $n "$sm" render grown.pvd "${view[@]}" --time all --out grown$n.pfm >grown$n.log 2>&1; then
    fail "a series whose step 2 is another mesh rendered on $n rank(s)"
  fi
  grep -q "grown.pvd: step 2 .* every step of a series must be the same mesh" grown$n.log ||
    { cat grown$n.log; fail "no message naming the series and the step ($n rank(s))"; }
  if ls grown${n}_*.pfm >/dev/null 2>&1; then fail "a frame was written ($n rank(s))"; fi
done

# A step whose points moved (the same counts: a moving mesh) is refused too, by the range pass that
# reads every step before the first frame; with --range (no such pass) when the step is read, its
# frame and later ones not written.
mkdir -p moved && cp -r series series.pvd moved/
python3 - moved/series/series_t2/series_t2_3.vtu <<'PY'
import re, struct, sys, zlib
path = sys.argv[1]
data = open(path, 'rb').read()
head, _, rest = data.partition(b'<AppendedData encoding="raw">')
start = rest.index(b'_') + 1
blob, tail = rest[start:], rest[rest.index(b'</AppendedData>'):]
arrays = [(m.group(1), int(m.group(2))) for m in re.finditer(rb'Name="([^"]+)"[^>]*offset="(\d+)"', head)]
ends = sorted(o for _, o in arrays) + [len(blob) - len(tail)]
out, offsets = b'', {}
for name, offset in sorted(arrays, key=lambda a: a[1]):
    raw = blob[offset:ends[ends.index(offset) + 1]]
    if name == b'Points':  # VTK's zlib blocks: count, block size, last size, sizes, then blocks
        n, bs, last = struct.unpack_from('<3Q', raw)
        sizes = struct.unpack_from('<%dQ' % n, raw, 24)
        at, values = 24 + 8 * n, b''
        for size in sizes:
            values += zlib.decompress(raw[at:at + size]); at += size
        xyz = list(struct.unpack('<%dd' % (len(values) // 8), values))
        xyz[0::3] = [x + 0.05 for x in xyz[0::3]]
        block = zlib.compress(struct.pack('<%dd' % len(xyz), *xyz))
        raw = struct.pack('<4Q', 1, len(xyz) * 8, len(xyz) * 8, len(block)) + block
    offsets[name] = len(out)
    out += raw
for name, offset in offsets.items():
    head = re.sub(rb'(Name="' + re.escape(name) + rb'"[^>]*offset=")\d+"', rb'\g<1>%d"' % offset, head)
open(path, 'wb').write(head + b'<AppendedData encoding="raw">\n   _' + out + b'\n  ' + tail)
PY
moving=(--field vortex --size ${W}x${H} --step $STEP --unit-distance $UNIT --colormap $CMAP
        --eye $EYE --at $AT --up $UP --fovy $FOVY)
for n in 1 3; do
  if mpi $n "$sm" render moved/series.pvd "${moving[@]}" --time all --out moved$n.pfm >moved$n.log 2>&1; then
    fail "a series whose step 2 moved its points rendered on $n rank(s)"
  fi
  grep -q "series.pvd: step 2 .*series_t2_3.vtu'.* at (.*), step 0 at (.*): every step of a series must be the same mesh" moved$n.log ||
    { cat moved$n.log; fail "no message naming the series, the step and the point ($n rank(s))"; }
  if ls moved${n}_*.pfm >/dev/null 2>&1; then fail "a frame was written ($n rank(s))"; fi
done
if "$sm" render moved/series.pvd "${view[@]}" --time all --out movedr.pfm >movedr.log 2>&1; then
  fail "a series whose step 2 moved its points rendered with --range"
fi
grep -q "series.pvd: step 2 .* every step of a series must be the same mesh" movedr.log || { cat movedr.log; fail "no message with --range"; }
cmp movedr_0001.pfm series1_0001.pfm || fail "the frame before the moved step is not the series' own"
if ls movedr_000[23].pfm >/dev/null 2>&1; then fail "a frame of the moved step or later was written"; fi
"$sm" render moved/series/series_t2.pvtu "${view[@]}" --out moved_alone.pfm  # the step's own mesh

# Pieces with different step counts are refused, naming the file and the counts, whether one
# rank reads them all or each rank its own: the outcome must not depend on the rank count. No
# frame is written.
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 2 --steps 4 --out four.pvtu
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 2 --steps 2 --out two.pvtu
cp two/two_1.vtu four/four_1.vtu
for n in 1 2; do
  if mpi $n "$sm" render four.pvtu "${view[@]}" --time all --out mixed$n.pfm >mixed$n.log 2>&1; then
    fail "pieces with 4 and 2 steps rendered on $n rank(s)"
  fi
  grep -q "four.pvtu: .*[24] time steps\|four.pvtu: .*with [24] steps" mixed$n.log || { cat mixed$n.log; fail "no message naming the file and the counts ($n rank(s))"; }
  if ls mixed${n}_*.pfm >/dev/null 2>&1; then fail "a frame was written ($n rank(s))"; fi
done
grep -q "four.pvtu: the pieces do not hold the same point fields: rank [01] (four/four_[01].vtu) has 'vortex' with [24] steps; rank [01] (four/four_[01].vtu) has 'vortex' with [24] steps" mixed2.log ||
  { cat mixed2.log; fail "the 2-rank message does not name the ranks, their pieces and counts"; }
# Pieces whose fields differ in a field not rendered are refused on any rank count too (one rank
# reading both pieces lists every field).
"$sm" generate --analytic cube-tets6 --cube-n 6 --clusters 2 --steps 2 --out lacks.pvtu
python3 - <<'PY'
import re
p = 'lacks/lacks_1.vtu'
b = open(p, 'rb').read()
head, sep, rest = b.partition(b'<AppendedData')
head = re.sub(rb'Name="shock@t', rb'Name="other@t', head)  # the same bytes, another field name
open(p, 'wb').write(head + sep + rest)
PY
for n in 1 2; do
  if mpi $n "$sm" render lacks.pvtu --size 32x32 --out lacks$n.png >lacks$n.log 2>&1; then
    fail "pieces with different fields rendered on $n rank(s)"
  fi
  grep -q "lacks.pvtu: .*shock\|lacks.pvtu: .*other" lacks$n.log || { cat lacks$n.log; fail "no message naming the fields ($n rank(s))"; }
  if ls lacks$n.png >/dev/null 2>&1; then fail "an image was written ($n rank(s))"; fi
done
# A field that is a scalar in one piece and a vector in the other, in a .pvtu that declares
# neither (no <PPointData>): one rank reading both refuses it against the first piece; two ranks,
# each reading one, would each read its own piece alike and render a scalar beside a vector's
# magnitude with no seam, so they compare what they read and refuse it naming both. The same for
# `view` (every step in memory, not streamed).
mkdir -p bare
python3 - <<'PY'
def tet(dx, comps):
    values = ' '.join(str(1 + i // comps) for i in range(4 * comps))
    return ('<VTKFile type="UnstructuredGrid" version="1.0"><UnstructuredGrid>'
            '<Piece NumberOfPoints="4" NumberOfCells="1"><Points><DataArray type="Float64" '
            'NumberOfComponents="3" format="ascii">%g 0 0 %g 0 0 %g 1 0 %g 0 1</DataArray></Points>'
            '<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>'
            '<DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>'
            '<DataArray type="UInt8" Name="types" format="ascii">10</DataArray></Cells>'
            '<PointData><DataArray type="Float32" Name="f" NumberOfComponents="%d" format="ascii">'
            '%s</DataArray></PointData></Piece></UnstructuredGrid></VTKFile>'
            % (dx, dx + 1, dx, dx, comps, values))
open('bare/p0.vtu', 'w').write(tet(0, 1))
open('bare/p1.vtu', 'w').write(tet(2, 3))
open('bare.pvtu', 'w').write('<VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid>'
                             '<Piece Source="bare/p0.vtu"/><Piece Source="bare/p1.vtu"/>'
                             '</PUnstructuredGrid></VTKFile>')
PY
if "$sm" render bare.pvtu --field f --size 16x16 --out bare1.png >bare1.log 2>&1; then
  fail "a scalar and a vector in two pieces rendered on 1 rank"
fi
grep -q "bare.pvtu: piece 'bare/p1.vtu' has 3 components in field 'f', the first piece" bare1.log ||
  { cat bare1.log; fail "no message naming the piece and the components (1 rank)"; }
if mpi 2 "$sm" render bare.pvtu --field f --size 16x16 --out bare2.png >bare2.log 2>&1; then
  fail "a scalar and a vector in two pieces rendered on 2 ranks"
fi
want="bare.pvtu: the pieces do not hold the same point fields: rank 0 (bare/p0.vtu) has 'f' with 1 step; rank 1 (bare/p1.vtu) has 'f' (the magnitude of 3 components) with 1 step"
grep -qF "$want" bare2.log || { cat bare2.log; fail "no message naming both ranks' fields (render)"; }
if mpi 2 "$sm" view bare.pvtu --field f --size 16x16 --headless --frames 1 >bare2v.log 2>&1; then
  fail "a scalar and a vector in two pieces were shown on 2 ranks"
fi
grep -qF "$want" bare2v.log || { cat bare2v.log; fail "no message naming both ranks' fields (view)"; }
if ls bare[12].png >/dev/null 2>&1; then fail "an image was written"; fi
echo "time steps: all checks passed"
