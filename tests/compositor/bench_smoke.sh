#!/usr/bin/env bash
# Smoke test of shellmarch_bench_compositor (a benchmark, so no timing is asserted): a sweep over
# 1 and 2 ranks with both pixel ownerships, and the replay, write the rows docs/COMPOSITOR.md
# describes; under interleaved ownership the synthetic ball's compositing is balanced, under
# contiguous ranges it is not.
#   bench_smoke.sh BENCH WORKDIR
set -euo pipefail
bench=$1 work=$2
mkdir -p "$work"
cd "$work"
"$bench" sweep --max-ranks 2 --sizes 64 --frames 1 --ownerships interleaved,ranges --json sweep.json >sweep.log
"$bench" replay --ranks 3,8 --width 96 --height 64 --json replay.json >replay.log
grep -q "ownership" sweep.log && grep -q "ranges" replay.log
python3 - <<'PY'
import json
rows = json.load(open("sweep.json"))
one = [r for r in rows if r["ranks"] == 1]
two = [r for r in rows if r["ranks"] == 2]
assert one and all(r["countBytes"] == 0 and r["fragmentBytes"] == 0 for r in one), "one rank sends nothing"
own = {r["ownership"] for r in two}
assert own == {"interleaved", "ranges"}, own
for r in two:
    assert r["fragments"] > 0 and r["fragmentBytes"] > 0 and r["ms"] > 0, r
inter = max(r["compositeImbalance"] for r in two if r["ownership"] == "interleaved")
assert inter < 1.05, "interleaved ownership balances the ball: %g" % inter
for r in json.load(open("replay.json")):
    assert r["compositeImbalance"] < 1.05, r
    assert r["compositeImbalanceRanges"] > r["compositeImbalance"], r
print("bench smoke: all checks passed")
PY
