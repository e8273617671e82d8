#!/usr/bin/env bash
# Installs the in-situ component into a fresh prefix, checks that only the public header and no
# internal symbol ship, then configures, builds and runs an outside project that uses
# find_package(shellmarch) and shellmarch::insitu.
# Usage: install_check.sh CMAKE BUILD_DIR CONSUMER_SOURCE WORK_DIR GENERATOR CXX_COMPILER
set -u
cmake=$1 build=$2 consumer=$3 work=$4 generator=$5 cxx=$6
fail() { echo "install_check: FAILED: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
prefix=$work/prefix

"$cmake" --install "$build" --component insitu --prefix "$prefix" || fail "cmake --install"
headers=$(cd "$prefix/include" && find . -type f | sort)
[ "$headers" = "./shellmarch/insitu.h" ] || fail "installed headers are not just the public one: $headers"
lib=$(find "$prefix" -name 'libshellmarch_insitu.so' | head -n 1)
[ -n "$lib" ] || fail "no libshellmarch_insitu.so under $prefix"
# Everything the library exports is the public API: internals and their dependencies stay hidden.
exported=$(nm -DC --defined-only "$lib" | cut -c18-)
others=$( (grep -v 'shellmarch::insitu::' <<<"$exported"; grep 'Renderer::Impl' <<<"$exported") | head -n 5)
[ -z "$others" ] || fail "the library exports symbols outside shellmarch::insitu, e.g.:
$others"
grep -q 'shellmarch::insitu::Renderer::render' <<<"$exported" ||
  fail "the library does not export shellmarch::insitu::Renderer::render"

"$cmake" -S "$consumer" -B "$work/build" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; fail "configuring the consumer with find_package(shellmarch)"; }
"$cmake" --build "$work/build" || fail "building the consumer"
"$work/build/consumer" "$work/consumer.png" || fail "running the consumer"
[ -s "$work/consumer.png" ] || fail "the consumer wrote no image"
# The same program built the Makefile way, through pkg-config.
pc_dir=$(dirname "$(find "$prefix" -name shellmarch-insitu.pc | head -n 1)")
[ -f "$pc_dir/shellmarch-insitu.pc" ] || fail "no shellmarch-insitu.pc under $prefix"
flags=$(PKG_CONFIG_PATH=$pc_dir pkg-config --cflags --libs shellmarch-insitu) ||
  fail "pkg-config --cflags --libs shellmarch-insitu"
# shellcheck disable=SC2086
"$cxx" -std=c++20 -O1 "$consumer/main.cpp" $flags -Wl,-rpath,"$(dirname "$lib")" \
  -o "$work/consumer-pc" || fail "building the consumer with pkg-config ($flags)"
"$work/consumer-pc" "$work/consumer-pc.png" || fail "running the pkg-config consumer"
cmp -s "$work/consumer.png" "$work/consumer-pc.png" ||
  fail "the pkg-config consumer's image differs from the CMake consumer's"
echo "install_check: passed ($lib; pkg-config: $flags)"
