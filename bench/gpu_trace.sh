#!/usr/bin/env bash
# The GPU probe tracer's speed on a machine with a GPU (issue 17): builds ddish's tracer bench
# and times one probe update of Sponza's 16x8x8 grid and the Breakfast room's 8x4x8 grid (the
# DDISH-GI paper's), 256 paths per probe, with the Vulkan ray-tracing tracer beside Embree on the
# same probes (bench/trace_vk_rate: median of 4 timed updates after a classifying one, CSV).
# The paper's figure: 1.68 ms for 1024 probes x 256 paths on an RTX 3090; goal <= 2 ms.
# Usage: bash bench/gpu_trace.sh [BUILD_DIR] (default build-gpu/). DDISH_SCENES (default
# ../shared/scenes beside the checkout) holds the scenes; --device N (DEVICE=N) picks the GPU;
# ENVIRONMENT=FILE.exr|.hdr adds a run of each scene lit by that map (importance-sampled).
# Then bench/probe_handoff times the GPU-resident hand-off on the same grids: per update, the
# conversion of the traced probes on the device against the read-back path's copy into the CPU
# volume plus the upload from there (medians, CSV).
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build-gpu}
SCENES=${DDISH_SCENES:-../shared/scenes}
cmake -S . -B "$B" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$B" --target trace_vk_rate probe_handoff ddish -j"$(nproc)"
"$B/ddish" devices
DEV=${DEVICE:+--device $DEVICE}
run() {  # scene grid
  if [ ! -f "$SCENES/$1" ]; then echo "skipped: $SCENES/$1 not found" >&2; return 0; fi
  "$B/bench/trace_vk_rate" "$SCENES/$1" --grid "$2" --samples 256 --updates 5 $DEV
  if [ -n "${ENVIRONMENT:-}" ]; then
    "$B/bench/trace_vk_rate" "$SCENES/$1" --grid "$2" --samples 256 --updates 5 $DEV --environment "$ENVIRONMENT"
  fi
}
run sponza/Sponza.gltf 16,8,8
run breakfast_room/BreakfastRoom.gltf 8,4,8
handoff() {  # scene grid
  if [ ! -f "$SCENES/$1" ]; then return 0; fi
  "$B/bench/probe_handoff" "$SCENES/$1" --grid "$2" --samples 256 --bounces 15 --rounds 8 $DEV
}
handoff sponza/Sponza.gltf 16,8,8
handoff breakfast_room/BreakfastRoom.gltf 8,4,8
