#!/usr/bin/env bash
# Frame times of `ddish render --window` for every display profile in displays/ at the
# profile's own size, on the default Vulkan device (lavapipe on a machine without a GPU), under
# a private Xvfb of 8192 × 8192 (every image up to the 32-inch quilt of 8190 × 8190 is shown
# 1:1). Each profile shows its quilt (or its view, or its stereo pair); every profile with a
# panel also shows its lenticular panel image, from a calibration of the Portrait's lenticules
# at the panel's resolution (the cost depends on the panel's pixels, not on the unit's pitch).
# Each run is interactive (no --frames: no files, nothing read back) and is stopped with SIGTERM
# (a background job of a script ignores SIGINT) once it has logged FRAMES frames, finishing the
# frame it is in; the table gives the median over the frames after the first
# (the first classifies every probe and builds the shadow maps) of: probes (probe update +
# upload), raster (record + GPU passes + wait), present (GPU composition + copy + blit +
# present: the loop's "output" stage in window mode) and the whole frame; and the load average
# when the run ended, as the machine may be shared.
# Usage: bash bench/live_window.sh [BUILD_DIR] [SCENE] [FRAMES] [PROFILE...]
# (LENTICULAR_ONLY=1: only the panel images of the profiles given.)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
scene=${2:-scenes/cornell_box.gltf}
frames=${3:-3}
shift $(( $# < 3 ? $# : 3 ))
profiles=("$@")
if [ ${#profiles[@]} -eq 0 ]; then
  for f in displays/*.json; do profiles+=("$(basename "$f" .json)"); done
fi
out=$(mktemp -d /tmp/ddish_live_bench.XXXXXX)
trap 'kill $xvfb 2>/dev/null || true; rm -rf "$out"' EXIT
display=:$((150 + $$ % 50))
Xvfb "$display" -screen 0 8192x8192x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
sleep 1
panel() {  # the profile's panel "W H", or nothing
  python3 -c 'import json,sys; p=json.load(open(sys.argv[1])).get("panel"); print(p["width"], p["height"]) if p else None' \
    "displays/$1.json"
}
run() {
  local name=$1
  shift
  : >"$out/$name.log"  # before the job starts: the wait below reads it at once
  DISPLAY=$display "$build/ddish" render "$scene" --window "$@" --timings "$out/$name.json" \
    --out "$out/files" >/dev/null 2>"$out/$name.log" &
  local pid=$!
  while kill -0 $pid 2>/dev/null && [ "$(grep -c '^frame ' "$out/$name.log" || true)" -lt "$frames" ]; do
    sleep 0.5
  done
  kill -TERM $pid 2>/dev/null || true
  wait $pid || true
  local load
  load=$(cut -d' ' -f1 /proc/loadavg)
  if [ ! -s "$out/$name.json" ]; then
    echo "live_window: $name: no timings; its log ends:" >&2
    tail -n 5 "$out/$name.log" >&2
    return 0
  fi
  python3 - "$out/$name.json" "$name" "$load" <<'PY'
import json, statistics, sys
d = json.load(open(sys.argv[1]))
frames = d["frames"][1:] or d["frames"]
def med(f):
    return statistics.median(f(x["stages_ms"]) for x in frames)
probes = med(lambda s: s.get("tracer_update", 0) + s.get("probe_update", 0) + s.get("upload", 0))
raster = med(lambda s: sum(s.get(k, 0) for k in ("raster_record", "shadow_gpu", "forward_gpu", "tonemap_gpu", "raster_wait")))
present = med(lambda s: s.get("output", 0))
total = statistics.median(x["total_ms"] for x in frames)
disp = d["display"]
size = f'{disp["views"]}x{disp["tile_width"]}x{disp["tile_height"]}'
print(f"{sys.argv[2]:48} {size:>14} {len(d['frames']):4} {probes:10.1f} {raster:10.1f} {present:10.1f} {total:10.1f} {sys.argv[3]:>6}")
PY
}
# A calibration of the Portrait's lenticules for a W × H panel.
calibration() {
  cat >"$out/cal_$1x$2.json" <<JSON
{"pitch": {"value": 52.58737671470091}, "slope": {"value": -7.196136200157333},
 "center": {"value": 0.4321881363063158}, "DPI": {"value": 324.0}, "screenW": {"value": $1.0},
 "screenH": {"value": $2.0}, "invView": {"value": 1.0}, "flipImageX": {"value": 0.0},
 "flipImageY": {"value": 0.0}, "flipSubp": {"value": 0.0}}
JSON
  echo "$out/cal_$1x$2.json"
}
printf '%-48s %14s %4s %10s %10s %10s %10s %6s\n' display views frames probes_ms raster_ms present_ms frame_ms load
for p in "${profiles[@]}"; do
  [ "${LENTICULAR_ONLY:-0}" = 1 ] || run "$p" --display "$p"
  size=$(panel "$p")
  if [ -n "$size" ]; then
    read -r w h <<<"$size"
    run "$p lenticular ${w}x${h}" --display "$p" --calibration "$(calibration "$w" "$h")"
  fi
done
