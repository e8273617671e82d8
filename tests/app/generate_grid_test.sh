#!/usr/bin/env bash
# `generate --method grid`: the summary states all four element types, interlocking clusters and
# the nested one; the file reads back as stated; two ranks (the clusters interlock and one sits
# inside another) render the image one rank does; sizes that cannot fit memory or disk are refused
# before anything is written.
set -uo pipefail
sm=$1 image_diff=$2 work=$3
source "$(dirname "$0")/script_lib.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

"$sm" generate --method grid --elements 200000 --steps 2 --out grid.pvtu >gen.log || fail "generate"
cat gen.log
for want in tetrahedra pyramids wedges hexahedra "8 clusters" "cluster 7 nested in cluster" \
  "random lines cross"; do
  grep -qF "$want" gen.log || fail "summary lacks '$want'"
done
# The pieces were renamed into place: no staged file is left.
[ -z "$(find grid -name '*.staged')" ] || fail "staged pieces left"
elements=$(sed -E 's/.*: ([0-9]+) elements.*/\1/' gen.log)
"$sm" info grid.pvtu >info.log || fail "info"
cells=$(awk '/tetrahedra|pyramids|wedges|hexahedra/ {s += $2} END {print s}' info.log)
[ "$cells" = "$elements" ] || fail "info counts $cells elements, generate said $elements"
grep -q "inverted cells    0 fixed" info.log || fail "generate wrote inverted cells"
grep -q "clusters          8" info.log || fail "not 8 clusters"

# The default: auto is gmsh up to a million elements, the grid above (named in the summary).
"$sm" generate --elements 1100000 --clusters 9 --out auto.pvtu >auto.log || fail "auto"
grep -qF "grid method" auto.log || fail "auto above a million did not use the grid"

render() {
  mpi "$1" "$sm" render grid.pvtu --field density --time 1 --size 96x96 --out "$2" --quiet ||
    fail "render on $1 ranks"
}
render 1 one.pfm
render 2 two.pfm
"$image_diff" one.pfm two.pfm --max-abs 1e-5 || fail "2 ranks differ from 1 on interlocking clusters"

# Refused before any work, nothing written.
refused "--method: expected auto, gmsh or grid" bad.pvtu "$sm" generate --method fast --out bad.pvtu
refused "--body: applies to gmsh meshes" bad.pvtu \
  "$sm" generate --method grid --body lander --out bad.pvtu
refused "a .pvd series needs --method gmsh" bad.pvd \
  "$sm" generate --method grid --elements 100000 --out bad.pvd
refused "--elements: the grid generator makes 10000 to 2000000000 elements" bad.pvtu \
  "$sm" generate --method grid --elements 500 --out bad.pvtu
refused "--compress: expected auto, on or off" bad.pvtu \
  "$sm" generate --method grid --compress maybe --out bad.pvtu
# One piece of two billion elements cannot be held in any memory this runs on.
refused "use at least --clusters" bad.pvtu \
  "$sm" generate --method grid --elements 2000000000 --clusters 1 --out bad.pvtu
[ ! -e bad ] || fail "a refused generate left a pieces folder"
# Two billion elements need about a hundred GiB of disk: more than a memory file system holds.
shm_free=$(df -k --output=avail /dev/shm 2>/dev/null | tail -1)
if [ -n "$shm_free" ] && [ "$shm_free" -lt 80000000 ]; then
  refused "on disk" /dev/shm/sm-bad.pvtu \
    "$sm" generate --method grid --elements 2000000000 --out /dev/shm/sm-bad.pvtu
  [ ! -e /dev/shm/sm-bad ] || fail "a refused generate left a pieces folder in /dev/shm"
else
  echo "skipped the disk check: /dev/shm has ${shm_free:-no} free KiB"
fi
echo "generate-grid: ok"
