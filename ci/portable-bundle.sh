#!/usr/bin/env bash
# Packs a Release build with every shared library it loads (glibc and its loader included) into one
# archive, so that shellmarch and its GPU tests run on a machine without Debian 12's packages: a
# cluster's GPU node, or a container image built for CUDA work. The Vulkan driver is the one
# thing not packed: the target machine's ICD (e.g. NVIDIA's) is found by the packed loader.
#
#   ci/portable-bundle.sh [BUILD_DIR] [OUT.tar.xz | OUT.tar]
#
# OUT.tar is written uncompressed (what the test does; xz takes two minutes on two cores).
#
# On the other machine: shellmarch/run PROGRAM [ARGS...] runs a packed program, and
# ci/gpu-check.sh runs the GPU test cases and the benchmarks (docs/BENCHMARKS.md, "On a GPU").
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-out/shellmarch-portable.tar.xz}
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
root=$stage/shellmarch
mkdir -p "$root/bin" "$root/lib" "$root/layers" "$root/share/shellmarch/bench"

# The app, and the test binaries whose cases need a Vulkan device (ctest label "gpu").
bins=("$build/bin/shellmarch" "$build/bin/shellmarch-bench" "$build/tests/render/test_render" "$build/tests/vk/test_vk"
  "$build/tests/compositor/test_compositor" "$build/tests/insitu/test_insitu"
  "$build/compositor/shellmarch_bench_compositor" "$build/tests/compositor/test_compositor_mpi")
cp "${bins[@]}" "$root/bin/"
cp src/bench/*.py "$root/share/shellmarch/bench/"  # beside bin/, where bench looks
command -v vulkaninfo >/dev/null && cp "$(command -v vulkaninfo)" "$root/bin/"

layer_json=/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json
layer_lib=/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
if [ -f "$layer_json" ] && [ -f "$layer_lib" ]; then
  cp "$layer_json" "$root/layers/"
  cp "$layer_lib" "$root/lib/"
  bins+=("$layer_lib")
fi

# Every library the binaries (and the validation layer) load, resolved here; the dynamic loader
# itself too, since the target's glibc may be older than the one these were linked against.
for b in "${bins[@]}" "$root/bin/vulkaninfo"; do
  [ -f "$b" ] || continue
  ldd "$b" | awk '/=> \//{print $3} $1 ~ /^\/.*ld-linux/{print $1}'
done | sort -u | while read -r lib; do
  cp -L "$lib" "$root/lib/"
done
# glibc and Open MPI apart: the machine's own are used where they can be (see run below).
mkdir -p "$root/glibc" "$root/mpi"
for f in ld-linux-x86-64.so.2 libc.so.6 libm.so.6 libdl.so.2 libpthread.so.0 librt.so.1; do
  if [ -f "$root/lib/$f" ]; then mv "$root/lib/$f" "$root/glibc/"; fi
done
mv "$root"/lib/libmpi*.so.* "$root"/lib/libopen-rte.so.* "$root"/lib/libopen-pal.so.* \
  "$root"/lib/libhwloc.so.* "$root"/lib/libevent*.so.* "$root/mpi/"
# getconf, not `ldd --version | head`: ldd goes on writing after head exits, and its SIGPIPE ended
# this script (pipefail) about one time in three.
getconf GNU_LIBC_VERSION | awk '{print $2}' > "$root/glibc/version"
# The C++ runtime apart too: a machine's own libmpi_cxx may need a newer one than ours.
mkdir -p "$root/cxx"
mv "$root/lib/libstdc++.so.6" "$root/lib/libgcc_s.so.1" "$root/cxx/"
for b in "${bins[@]}"; do objdump -T "$b"; done | grep -oE 'GLIBCXX_[0-9.]+' | sort -uV | tail -1 \
  > "$root/cxx/version"

# glvnd's libraries, which NVIDIA's Vulkan driver loads through the machine's loader paths:
# ci/gpu-check.sh installs them where the machine has none.
mkdir -p "$root/glvnd"
for f in libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libGL.so.1 libOpenGL.so.0; do
  if [ -f "/usr/lib/x86_64-linux-gnu/$f" ]; then cp -L "/usr/lib/x86_64-linux-gnu/$f" "$root/glvnd/"; fi
done

# Which cases of those binaries are GPU cases, as ctest knows them, for ci/gpu-check.sh.
(cd "$build" && ctest -L gpu --show-only=json-v1) | python3 -c '
import collections, json, sys
cases = collections.defaultdict(list)
for t in json.load(sys.stdin)["tests"]:
    cmd = t.get("command") or [""]
    f = [a[len("--gtest_filter="):] for a in cmd if a.startswith("--gtest_filter=")]
    if f: cases[cmd[0].rsplit("/", 1)[-1]].append(f[0])
for b, names in sorted(cases.items()): print(b, ":".join(names))
' | while read -r b filter; do
  if [ -f "$root/bin/$b" ]; then echo "$b $filter"; fi
done > "$root/gpu-tests.txt"

cat > "$root/run" <<'RUN'
#!/usr/bin/env bash
# run PROGRAM [ARGS...]: runs bin/PROGRAM with the packed libraries, or the machine's where they
# fit (SHELLMARCH_PORTABLE_PACKED=1 takes the packed ones regardless):
# - Open MPI: the machine's libmpi.so.40 (4.x, the same ABI) when its loader would find one (in
#   LD_LIBRARY_PATH, as `module load` sets it, beside its mpiexec, or in ldconfig's cache), so
#   that its mpiexec and components match; else the packed one (single process only).
# - libstdc++: the machine's when it has every symbol version the programs need.
# - glibc: the machine's when it is at least as new as the packed one, else the packed loader
#   and glibc; then processes the program starts (mpiexec's) do not get them.
# Ours come before the machine's LD_LIBRARY_PATH, which must still find its Vulkan driver.
b=$(cd "$(dirname "$0")" && pwd)
packed=${SHELLMARCH_PORTABLE_PACKED:-0}
# `shellmarch bench` runs shellmarch-bench beside it; run that one directly here, so that it too
# gets the libraries and loader chosen below.
if [ "${1:-}" = shellmarch ] && [ "${2:-}" = bench ]; then set -- shellmarch-bench "${@:3}"; fi
export VK_LAYER_PATH=$b/layers${VK_LAYER_PATH:+:$VK_LAYER_PATH}
cache=$( (ldconfig -p || /sbin/ldconfig -p) 2>/dev/null)
machineHas() {  # machineHas LIB: the machine's loader would find LIB
  local d
  local IFS=:
  for d in $LD_LIBRARY_PATH ${mpiexecLib:-}; do [ -n "$d" ] && [ -e "$d/$1" ] && return 0; done
  awk -v lib="$1" '$1 == lib { found = 1 } END { exit !found }' <<<"$cache"
}
mpiexecLib=
if command -v mpiexec > /dev/null; then
  mpiexecLib=$(dirname "$(dirname "$(readlink -f "$(command -v mpiexec)")")")/lib
fi
path=$b/lib
if [ "$packed" != 0 ] || ! machineHas libmpi.so.40; then path=$path:$b/mpi; fi
cxx=$(awk '/libstdc\+\+\.so\.6 .*x86-64/{print $NF; exit}' <<<"$cache")
if [ "$packed" != 0 ] || [ -z "$cxx" ] || ! grep -qaF "$(cat "$b/cxx/version")" "$cxx"; then
  path=$path:$b/cxx
fi
have=$(getconf GNU_LIBC_VERSION 2>/dev/null | awk '{print $2}')
want=$(cat "$b/glibc/version")
if [ "$packed" = 0 ] && [ -n "$have" ] && [ "$(printf '%s\n%s\n' "$want" "$have" | sort -V | head -1)" = "$want" ]; then
  export LD_LIBRARY_PATH=$path${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  exec "$b/bin/$1" "${@:2}"
fi
exec "$b/glibc/ld-linux-x86-64.so.2" --library-path "$b/glibc:$path${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
  "$b/bin/$1" "${@:2}"
RUN
chmod +x "$root/run"

mkdir -p "$(dirname "$out")"
case "$out" in
  *.tar) tar -C "$stage" -cf "$out.tmp" shellmarch ;;
  *) tar -C "$stage" -cf - shellmarch | xz -T2 -6 > "$out.tmp" ;;
esac
mv "$out.tmp" "$out"
echo "wrote $out ($(du -h "$out" | cut -f1)): $(ls "$root/lib" | wc -l) libraries"
