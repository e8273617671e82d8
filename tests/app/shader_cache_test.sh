#!/usr/bin/env bash
# The shader cache across processes (docs/ARCHITECTURE.md, "Startup"), run by ctest with
#   shader_cache_test.sh SHELLMARCH WORKDIR
# A cold run compiles and stores, a warm run takes every shader from the cache, and both images
# are the pipelines' bit for bit; 2 ranks share one folder; a truncated, corrupt, foreign or newer
# cache file is ignored with one warning and rebuilt; a folder that cannot be written costs a
# warning, not the image; 'none' stores nothing.
#
# Shader objects are what lavapipe's binaries are kept as, and Debian 12's validation layer
# (1.3.239) predates VK_EXT_shader_object: the runs that use them go unvalidated here
# (SHELLMARCH_VALIDATION=0); the pipelines' reference run is validated.
set -euo pipefail
sm=$1 work=$2
mkdir -p "$work"
cd "$work"
rm -rf ./cache* ./*.png ./*.json ./*.log ./blocker
source "$(dirname "${BASH_SOURCE[0]}")/script_lib.sh"

"$sm" generate --analytic cube-tets6 --cube-n 5 --clusters 4 --out cube.pvtu >/dev/null
args=(cube.pvtu --field vortex --size 48x40 --view iso)
render() {  # render TAG [env...]: the image TAG.png and statistics TAG.json
  local tag=$1; shift
  env "$@" "$sm" render "${args[@]}" --out $tag.png --stats-json $tag.json 2>$tag.log >/dev/null
}
objects=(SHELLMARCH_VALIDATION=0 SHELLMARCH_CACHE_DIR=$work/cache)
render pipelines SHELLMARCH_HIDE=shader_object SHELLMARCH_CACHE_DIR=none
json pipelines.json "not j['startup']['shader_objects'] and j['startup']['cache_folder'] == ''"
render cold "${objects[@]}"
render warm "${objects[@]}"
cmp pipelines.png cold.png || fail "the shader objects' image is not the pipelines'"
cmp cold.png warm.png || fail "the image from cached shaders differs"
json cold.json "j['startup']['shader_objects'] and j['startup']['pipelines_from_cache_rank0'] == 0"
json warm.json "len(j['startup']['pipelines_rank0']) > 0 and j['startup']['pipelines_from_cache_rank0'] == len(j['startup']['pipelines_rank0'])"
json warm.json "j['startup']['cache_files_rejected'] == 0"
[ ! -s warm.log ] || { cat warm.log; fail "a warm run printed something"; }
ls cache/shader-*.bin >/dev/null || fail "no shader binary stored"
ls cache/*.tmp.* 2>/dev/null && fail "temporary files left in the cache"

# Two ranks on one folder: the first 2-rank run compiles the exchange's pipelines (more than one
# rank's) on both ranks at once, each storing the same files; the second finds all of them whole.
for run in 1 2; do
  mpi 2 env "${objects[@]}" "$sm" render "${args[@]}" --out two$run.png --stats-json two$run.json \
    2>two$run.log >/dev/null
  [ ! -s two$run.log ] || { cat two$run.log; fail "2 ranks, run $run: printed something"; }
done
# (How many of run 1's rank 0 found depends on which rank stored a shader first.)
json two1.json "len(j['startup']['pipelines_rank0']) > len(json.load(open('warm.json'))['startup']['pipelines_rank0'])"
json two2.json "j['startup']['pipelines_from_cache_rank0'] == len(j['startup']['pipelines_rank0'])"
cmp two1.png two2.png || fail "2 ranks: the image from cached shaders differs"
# The ray tracing pipeline tracer beside compute shader objects: the same image.
env "${objects[@]}" "$sm" render "${args[@]}" --tracer pipeline --out rt.png >/dev/null
cmp cold.png rt.png || fail "the pipeline tracer beside shader objects gives another image"

# Damaged files: each ignored with one warning naming the file and why, the image unchanged,
# the file rebuilt so that the next run is warm and silent.
big=$(ls -S cache/shader-*.bin | head -1)
damage() {  # damage HOW WANT: HOW changes $big; the next run warns with WANT
  local how=$1 want=$2
  cp "$big" saved.bin
  eval "$how"
  render damaged "${objects[@]}"
  cmp cold.png damaged.png || fail "$how: the image changed"
  [ "$(grep -c warning damaged.log)" -eq 1 ] || { cat damaged.log; fail "$how: not one warning"; }
  grep -qF "$big" damaged.log || { cat damaged.log; fail "$how: the warning names no file"; }
  grep -qF "$want" damaged.log || { cat damaged.log; fail "$how: no '$want'"; }
  json damaged.json "j['startup']['cache_files_rejected'] == 1"
  render again "${objects[@]}"
  [ ! -s again.log ] || { cat again.log; fail "$how: the file was not rebuilt"; }
  cmp -s "$big" saved.bin || fail "$how: the rebuilt file differs from the first"
}
damage 'head -c 1000 saved.bin >"$big"' "truncated"
damage 'head -c 30 saved.bin >"$big"' "truncated"
damage 'python3 -c "import sys; b=bytearray(open(sys.argv[1],\"rb\").read()); b[-100]^=1; open(sys.argv[1],\"wb\").write(b)" "$big"' "corrupt"
damage 'python3 -c "import sys; b=bytearray(open(sys.argv[1],\"rb\").read()); b[16]^=1; open(sys.argv[1],\"wb\").write(b)" "$big"' "another device or driver"
damage 'python3 -c "import sys,struct; b=bytearray(open(sys.argv[1],\"rb\").read()); b[8:12]=struct.pack(\"<I\",99); open(sys.argv[1],\"wb\").write(b)" "$big"' "newer shellmarch"
damage 'echo "this is not a shellmarch cache file at all" >"$big"' "not a shellmarch cache file"

# A folder that cannot be made: one warning, the same image, exit 0.
echo file >blocker
render unwritable SHELLMARCH_VALIDATION=0 SHELLMARCH_CACHE_DIR=$work/blocker/cache
cmp cold.png unwritable.png || fail "an unwritable cache changed the image"
[ "$(grep -c warning unwritable.log)" -eq 1 ] || { cat unwritable.log; fail "not one warning"; }
grep -qF "cannot write the shader cache in $work/blocker/cache" unwritable.log || fail "no folder named"

# --cache-dir names the folder; 'none' keeps nothing.
"$sm" render "${args[@]}" --cache-dir "$work/cache-opt" --out opt.png >/dev/null 2>&1
ls cache-opt/pipelines-*.bin >/dev/null || fail "--cache-dir stored no pipeline cache"
env SHELLMARCH_VALIDATION=0 "$sm" render "${args[@]}" --cache-dir none --out none.png \
  --stats-json none.json >/dev/null
json none.json "j['startup']['cache_folder'] == '' and j['startup']['pipelines_from_cache_rank0'] == 0"
cmp cold.png none.png || fail "--cache-dir none changed the image"
echo "shader cache: ok"
