#!/usr/bin/env bash
# Builds the .deb with cpack into WORK and checks what a user installing it gets: the program, its
# man pages and bash completion, the in-situ library with its header, CMake package and pkg-config
# file, the Python module, and dependencies on the Vulkan driver and MPI.
# Usage: deb_check.sh CPACK CPACK_CONFIG WORK
set -u
cpack=$1 config=$2 work=$3
fail() { echo "deb_check: FAILED: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
"$cpack" -G DEB --config "$config" -B "$work" >"$work/cpack.log" 2>&1 ||
  { tail -n 20 "$work/cpack.log"; fail "cpack -G DEB"; }
deb=$(find "$work" -maxdepth 1 -name 'shellmarch_*.deb' | head -n 1)
[ -n "$deb" ] || fail "cpack wrote no shellmarch_*.deb in $work"
contents=$(dpkg-deb -c "$deb" | awk '{print $NF}' | sed 's|^\./|/|')
for path in /usr/bin/shellmarch /usr/share/man/man1/shellmarch.1 \
  /usr/share/man/man1/shellmarch-render.1 /usr/share/bash-completion/completions/shellmarch \
  /usr/include/shellmarch/insitu.h /usr/lib/pkgconfig/shellmarch-insitu.pc \
  /usr/lib/cmake/shellmarch/shellmarchConfig.cmake /usr/lib/python3/dist-packages/shellmarch/__init__.py; do
  grep -qx "$path" <<<"$contents" || fail "the package lacks $path"
done
grep -q '^/usr/lib/libshellmarch_insitu\.so' <<<"$contents" || fail "the package lacks the library"
# Nothing of the build or test tree leaks in.
leaked=$(grep -E 'gtest|/test_|spv_embed|fuzz' <<<"$contents" | head -n 3)
[ -z "$leaked" ] || fail "test or build files in the package: $leaked"
depends=$(dpkg-deb -f "$deb" Depends)
for dep in mesa-vulkan-drivers openmpi-bin libvulkan1 libcgns; do
  grep -q "$dep" <<<"$depends" || fail "Depends lacks $dep: $depends"
done
# The packaged man page is a real page of the program's options.
dpkg-deb -x "$deb" "$work/root" || fail "dpkg-deb -x"
zcat -f "$work/root/usr/share/man/man1/shellmarch-render.1"* | grep -q -- 'colormap' ||
  fail "shellmarch-render.1 does not describe --colormap"
echo "deb_check: passed ($(basename "$deb"), $(du -h "$deb" | cut -f1); Depends: $depends)"
