#!/usr/bin/env bash
# Installs Tandem's build and test dependencies from Debian 12 packages.
# Idempotent and non-interactive: packages already present are skipped.
set -euo pipefail
pkgs=(
  build-essential cmake ninja-build ccache pkg-config
  libembree-dev libtbb-dev libhwy-dev libtinygltf-dev libtinyobjloader-dev libstb-dev libdraco-dev
  libopenexr-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-openimageio
  libopenmpi-dev openmpi-bin gnuplot-nox
  libglfw3-dev libimgui-dev libgl-dev xvfb xauth libgl1-mesa-dri
  libvulkan-dev libvulkan-volk-dev glslc spirv-tools vulkan-validationlayers mesa-vulkan-drivers
)
if [ "${TANDEM_FUZZ_DEPS:-0}" = 1 ]; then pkgs+=(clang libclang-rt-14-dev); fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#pkgs[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: installed ${missing[*]}"
