#!/usr/bin/env bash
# Frame times of `ddish render --window` per display mode at the profiles' own sizes, on the
# default Vulkan device (lavapipe on a machine without a GPU), under a private Xvfb large enough
# for every window to show its image 1:1. Each mode runs interactively (no --frames: no files,
# nothing read back) for SECONDS and is stopped with SIGINT; the table gives the median over the
# frames after the first of: probes (probe update + upload), raster (record + GPU passes + wait),
# present (GPU composition + copy + blit + present: the loop's "output" stage in window mode) and
# the whole frame.
# Usage: bash bench/live_window.sh [BUILD_DIR] [SCENE] [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
scene=${2:-scenes/cornell_box.gltf}
seconds=${3:-60}
out=$(mktemp -d)
trap 'kill $xvfb 2>/dev/null || true; rm -rf "$out"' EXIT
display=:$((150 + $$ % 50))
Xvfb "$display" -screen 0 4096x4096x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
sleep 1
# A Portrait calibration of the usual magnitudes (each unit's visual.json differs a little).
cat >"$out/portrait.json" <<'JSON'
{"pitch": {"value": 52.58737671470091}, "slope": {"value": -7.196136200157333},
 "center": {"value": 0.4321881363063158}, "DPI": {"value": 324.0}, "screenW": {"value": 1536.0},
 "screenH": {"value": 2048.0}, "invView": {"value": 1.0}, "flipImageX": {"value": 0.0},
 "flipImageY": {"value": 0.0}, "flipSubp": {"value": 0.0}}
JSON
run() {
  local name=$1
  shift
  DISPLAY=$display timeout -s INT "$seconds" "$build/ddish" render "$scene" --window "$@" \
    --timings "$out/$name.json" --out "$out/files" >/dev/null 2>"$out/$name.log" || true
  python3 - "$out/$name.json" "$name" <<'PY'
import json, statistics, sys
d = json.load(open(sys.argv[1]))
frames = d["frames"][1:] or d["frames"]
def med(f):
    return statistics.median(f(x["stages_ms"]) for x in frames)
probes = med(lambda s: s.get("tracer_update", 0) + s.get("probe_update", 0) + s.get("upload", 0))
raster = med(lambda s: sum(s.get(k, 0) for k in ("raster_record", "shadow_gpu", "forward_gpu", "tonemap_gpu", "raster_wait")))
present = med(lambda s: s.get("output", 0))
total = statistics.median(x["total_ms"] for x in frames)
print(f"{sys.argv[2]:34} {len(d['frames']):4} {probes:10.1f} {raster:10.1f} {present:10.1f} {total:10.1f}")
PY
}
printf '%-34s %4s %10s %10s %10s %10s\n' mode frames probes_ms raster_ms present_ms frame_ms
run single-512x512 --width 512 --height 512
run stereo-hmd-2x1440x1600 --display stereo
run portrait-quilt-3360x3360 --display looking-glass-portrait
run portrait-lenticular-1536x2048 --display looking-glass-portrait --calibration "$out/portrait.json"
