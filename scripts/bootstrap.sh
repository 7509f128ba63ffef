#!/usr/bin/env bash
# Installs every Debian package that ddish's build, tests and main job need.
# Idempotent: packages already present are left alone. Runs as root or through sudo.
set -euo pipefail

PACKAGES=(
  # toolchain
  cmake ninja-build g++ pkg-config git
  # compiler cache: .ci/run and scripts/sanitize.sh use it where it is installed
  ccache
  # Vulkan: loader, headers, CPU driver (lavapipe), validation layers, GLSL compiler
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools spirv-tools
  # math, scenes, images, options, logging, compression
  libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libopenimageio-dev openimageio-tools
  libcli11-dev libspdlog-dev libfmt-dev libzstd-dev libmeshoptimizer-dev
  # KHR_draco_mesh_compression (src/scene/gltf_draco.cpp); draco_transcoder writes the
  # Draco twin of scenes/draco_box.gltf (scripts/make_draco_box.sh)
  libdraco-dev draco
  # ray tracing and threads
  libembree-dev libtbb-dev
  # probe stream (src/net): ZeroMQ with CURVE, its C++ binding
  libzmq3-dev cppzmq-dev
  # headset path (src/xr, tests/xr_runtime): OpenXR loader and headers, Khronos core validation layer
  libopenxr-dev libopenxr-loader1 openxr-layer-corevalidation
  # tests, plots
  libgtest-dev libgmock-dev gnuplot-nox python3
  # fuzzing (scripts/fuzz.sh, every tests/fuzz target): clang 14 and its libFuzzer, ASan and UBSan runtimes
  clang-14 libclang-rt-14-dev
  # the live window (ddish render --window, src/window): SDL2 with its Vulkan surface; the window
  # tests run under a private Xvfb server and screenshot it with xwd (x11-apps)
  libsdl2-dev xvfb x11-apps
  # the window's key and minimise tests drive it as a user would (X key events, unmap / map)
  xdotool
  # silences a broken-target warning in Debian's Imath CMake files (pulled in by OpenImageIO)
  python3-imath
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

# The CPU Vulkan device is Mesa 25 lavapipe from bookworm-backports: 2.5-3x faster fragment
# shading than bookworm's Mesa 22.3, and it has the ray-tracing extensions (docs/conventions.md).
# The code keeps working on Mesa 22; this only picks the faster driver.
MESA_MIN_MAJOR=25
BACKPORTS_LIST=/etc/apt/sources.list.d/bookworm-backports.sources
# Empty when the driver is not installed (a clean machine): dpkg-query's failure must not end
# the script under set -e / pipefail.
mesa_major() {
  { dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true; } | cut -d. -f1
}
need_mesa=0
if [ "${DDISH_STOCK_MESA:-0}" != 1 ] && grep -q 'VERSION_CODENAME=bookworm' /etc/os-release 2>/dev/null; then
  major=$(mesa_major)
  [ -n "$major" ] && [ "$major" -ge "$MESA_MIN_MAJOR" ] 2>/dev/null || need_mesa=1
fi

if [ ${#missing[@]} -eq 0 ] && [ $need_mesa -eq 0 ]; then
  echo "bootstrap: all ${#PACKAGES[@]} packages present (mesa-vulkan-drivers $(dpkg-query -W -f='${Version}' mesa-vulkan-drivers))"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "bootstrap: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive

if [ $need_mesa -eq 1 ] && [ ! -f "$BACKPORTS_LIST" ] && ! grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "bootstrap: adding the bookworm-backports suite ($BACKPORTS_LIST)"
  printf 'Types: deb\nURIs: http://deb.debian.org/debian\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' |
    $SUDO tee "$BACKPORTS_LIST" >/dev/null
fi

$SUDO apt-get update -q
# libsdl2-dev pulls libdrm-dev and libgbm-dev, whose versions must equal the installed libdrm2 and
# libgbm1: with Mesa from bookworm-backports (now or about to be) they come from there too.
mesa_dev=()
if [ "${DDISH_STOCK_MESA:-0}" != 1 ] && { [ $need_mesa -eq 1 ] || dpkg-query -W -f='${Version}' libgbm1 2>/dev/null | grep -q bpo; }; then
  for p in libdrm-dev libgbm-dev; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || mesa_dev+=("$p/bookworm-backports")
  done
fi
if [ $need_mesa -eq 1 ]; then
  # apt pulls the matching libdrm, mesa-libgallium and every Mesa package already installed
  # (their versions must equal the driver's).
  echo "bootstrap: installing Mesa $MESA_MIN_MAJOR lavapipe from bookworm-backports"
  $SUDO apt-get install -y -q --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "bootstrap: installing ${#missing[@]} package(s): ${missing[*]}"
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" ${mesa_dev[@]+"${mesa_dev[@]}"}
fi
echo "bootstrap: mesa-vulkan-drivers $(dpkg-query -W -f='${Version}' mesa-vulkan-drivers)"
