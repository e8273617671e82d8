#!/usr/bin/env bash
# Installs every Debian package shellmarch needs. Idempotent: safe to run on every CI start.
# Stock bookworm Mesa (22.3) lacks VK_KHR_ray_query on lavapipe, so Mesa comes from bookworm-backports.
#   ci/install-deps.sh [--build-only]
# --build-only (ci/demo.sh): what configuring, building and running shellmarch need, without what
# only the tests, fuzzers, sanitizer runs and Python benchmark peers need (about 150 packages and
# 190 MB to download fewer); a later run without it installs the rest.
set -euo pipefail
build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; fi

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

backports=/etc/apt/sources.list.d/shellmarch-backports.list
if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "deb http://deb.debian.org/debian bookworm-backports main" | $SUDO tee "$backports" >/dev/null
fi

# GoogleTest is in the build set: configuring with the tests on (ci/build.sh) finds it.
packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libvulkan-dev vulkan-tools glslang-tools spirv-tools
  libopenmpi-dev openmpi-bin
  libglfw3-dev libglm-dev libgtest-dev googletest
  libgmsh-dev libmetis-dev libcgns-dev libexodusii-dev
  libpugixml-dev nlohmann-json3-dev libcli11-dev libstb-dev zlib1g-dev liblz4-dev liblzma-dev libpng-dev
  fonts-dejavu-core                                # the legend's font
  python3-dev python3-numpy pybind11-dev python3-mpi4py  # the Python module
  help2man                                         # man pages from --help
)
test_packages=(
  vulkan-validationlayers
  clang libclang-rt-14-dev
  xvfb xauth
  python3 python3-vtk9 python3-numpy python3-matplotlib python3-meshio
)
if [ $build_only = 0 ]; then packages+=("${test_packages[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
mesa_ok=0
if dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null | grep -q '^[0-9]*:\?2[5-9]\.'; then mesa_ok=1; fi

if [ ${#missing[@]} -gt 0 ] || [ $mesa_ok = 0 ]; then
  $SUDO apt-get update -qq
  if [ ${#missing[@]} -gt 0 ]; then
    $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
  $SUDO apt-get install -y -qq --no-install-recommends -t bookworm-backports \
    mesa-vulkan-drivers libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libgbm1
fi

if ! vulkaninfo --summary 2>/dev/null | grep -q llvmpipe; then
  echo "install-deps: lavapipe (llvmpipe) is not visible to vulkaninfo" >&2
  exit 1
fi
echo "install-deps: all packages present"
