#!/usr/bin/env bash
# Installs every Debian package that ddish's build, tests and main job need.
# Idempotent: packages already present are left alone. Runs as root or through sudo.
set -euo pipefail

PACKAGES=(
  # toolchain
  cmake ninja-build g++ pkg-config git
  # Vulkan: loader, headers, CPU driver (lavapipe), validation layers, GLSL compiler
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools spirv-tools
  # math, scenes, images, options, logging, compression
  libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libopenimageio-dev openimageio-tools
  libcli11-dev libspdlog-dev libfmt-dev libzstd-dev libmeshoptimizer-dev
  # ray tracing and threads
  libembree-dev libtbb-dev
  # tests, plots
  libgtest-dev libgmock-dev gnuplot-nox python3
  # silences a broken-target warning in Debian's Imath CMake files (pulled in by OpenImageIO)
  python3-imath
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "bootstrap: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi

echo "bootstrap: installing ${#missing[@]} package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
