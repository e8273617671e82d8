#!/usr/bin/env bash
# ci/check_layers.py passes on the tree and catches each kind of violation in a copy of it.
set -u
root=$1 work=$2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
python3 "$root/ci/check_layers.py" "$root" || fail "the source tree breaks its own layer rules"

rm -rf "$work" && mkdir -p "$work"
(cd "$root" && tar cf - docs/ARCHITECTURE.md vk comm compositor src python/src python/CMakeLists.txt) |
  tar xf - -C "$work"
expect() {  # expect MESSAGE: the check fails and says MESSAGE
  local out
  if out=$(python3 "$root/ci/check_layers.py" "$work" 2>&1); then
    fail "check passed despite: $1"
  elif ! grep -qF -- "$1" <<<"$out"; then
    fail "expected '$1' in: $out"
  fi
}
h=$work/src/mesh/cell_type.h
cp "$h" "$h.orig"
echo '#include <vulkan/vulkan.h>' >>"$h"
expect "src/mesh/cell_type.h: includes <vulkan/vulkan.h>: Vulkan belongs in vk/"
cp "$h.orig" "$h" && echo '#include "pipeline/rank_share.h"' >>"$h"
expect "src/mesh/cell_type.h: includes pipeline/rank_share.h of shellmarch_pipeline, which shellmarch_mesh does not depend on"
cp "$h.orig" "$h" && echo '#include <mpi.h>' >>"$h"
expect "includes <mpi.h>: MPI belongs in comm/mpi/ or in situ"
cp "$h.orig" "$h" && echo 'inline void f(VkCommandBuffer c) { vkCmdDispatch(c, 1, 1, 1); }' >>"$h"
expect "calls vkCmdDispatch: Vulkan calls belong in vk/"
cp "$h.orig" "$h"
sed -i 's/| `shellmarch_prep` | `src\/prep` | \(.*\) | mesh |/| `shellmarch_prep` | `src\/prep` | \1 | mesh, scene |/' "$work/docs/ARCHITECTURE.md"
expect "shellmarch_prep depends on ['mesh', 'scene'] in the table but on ['mesh'] in CMake"
cp "$root/docs/ARCHITECTURE.md" "$work/docs/ARCHITECTURE.md"
sed -i 's/target_link_libraries(shellmarch_partition PUBLIC shellmarch_mesh/target_link_libraries(shellmarch_partition PUBLIC shellmarch_mesh shellmarch_scene/' \
  "$work/src/partition/CMakeLists.txt"
expect "shellmarch_partition links shellmarch_scene PUBLIC but none of its headers includes it"
cp "$root/src/partition/CMakeLists.txt" "$work/src/partition/CMakeLists.txt"
yes '// filler' | head -n 12000 >"$work/src/partition/filler.cpp"
expect "more than 15%: split it by what its parts hold"
rm "$work/src/partition/filler.cpp"
r=$work/src/render/step_limits.h
cp "$r" "$r.orig" && echo '#include "mesh/unstructured_mesh.h"' >>"$r"
expect "src/render/step_limits.h: includes mesh/unstructured_mesh.h: the renderer takes boxes, not meshes"
cp "$r.orig" "$r"
[ $fails -eq 0 ] && echo "layer check: passes on the tree, catches 8 kinds of violation"
exit $((fails > 0))
