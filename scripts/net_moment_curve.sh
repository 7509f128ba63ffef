#!/usr/bin/env bash
# The probe stream's moment maps: bytes against a client's image error, per `ddish serve
# --moment-threshold` (docs/protocol.md, "The moment threshold"). For each threshold (and without
# maps, --probe-visibility 0): bytes, maps and probes per tick after the first 30 of a 150-tick
# run (Cornell box, 8x8x8 probes at 64 paths, uniform schedule, 30 ticks/s: every probe traced
# every tick), 30 x bytes per tick as bytes per second, and the PSNR of a `ddish view` that joins
# a server after 60 updates (so it holds the maps as the threshold left them) against `ddish
# render` of the same 60 updates, 256x256. Serve's defaults otherwise; extra serve options
# (--encoding fp16 --delta-threshold 0, say, to leave the maps the only difference) go in
# SERVE_EXTRA, the scene in SCENE (a name under scenes/, default cornell_box), the grid in GRID.
# Usage: bash scripts/net_moment_curve.sh [BUILD_DIR] [THRESHOLD ...] (default build/, 0 0.005
# 0.01 0.02 none); ports 24050-24069; about 1 minute a threshold.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
shift || true
THRESHOLDS=${*:-0 0.005 0.01 0.02 none}
D=$(mktemp -d /tmp/ddish_moment_curve.XXXX)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$D"' EXIT
S=scenes/${SCENE:-cornell_box}.gltf
GRID=${GRID:-8,8,8}
EXTRA=${SERVE_EXTRA:-}
IMAGE="--width 256 --height 256"
wait_for() { for _ in $(seq 1 900); do grep -q "$2" "$1" 2>/dev/null && return 0; sleep 0.1; done; echo "timeout: $2 in $1" >&2; return 1; }

echo "moment_threshold,bytes_per_tick_after_1s,bytes_per_second_at_30_ticks,maps_per_tick,probes_per_tick,psnr_vs_in_process_db"
R="--grid $GRID --probe-samples 64 --schedule uniform"
for vis in 8 0; do
  "$B/ddish" render $S $R $IMAGE --probe-visibility $vis --frames 60 --warmup-ms 0 --out "$D/curve_render$vis" >/dev/null 2>&1
done
port=24050
for T in $THRESHOLDS; do
  if [ $T = none ]; then opt="--probe-visibility 0"; vis=0; else opt="--moment-threshold $T"; vis=8; fi
  "$B/ddish" serve $S $R --bind tcp://127.0.0.1:$port --frames 150 --fps 30 --seconds 6 --timings "$D/curve.json" $opt $EXTRA >/dev/null 2>&1
  "$B/ddish" serve $S $R --bind tcp://127.0.0.1:$((port + 1)) --frames 60 --seconds 60 $opt $EXTRA >"$D/curve.log" 2>&1 &
  pid=$!
  wait_for "$D/curve.log" "update 60:"
  "$B/ddish" view $S --grid $GRID $IMAGE --wait-ms 10000 --connect tcp://127.0.0.1:$((port + 1)) --out "$D/curve_view" >/dev/null 2>"$D/view.log"
  kill -TERM $pid; wait $pid || true
  # A view that rendered before the snapshot came measures the wait, not the maps.
  grep -q "snapshot of frame" "$D/view.log" || { echo "threshold $T: the view rendered without the server's snapshot:" >&2; cat "$D/view.log" >&2; }
  psnr=$("$B/ddish" compare "$D/curve_view/frame_0000.exr" "$D/curve_render$vis/frame_0059.exr" | awk '/psnr/ {print $2}')
  python3 - "$D/curve.json" "$T" "$psnr" <<'PY'
import json, sys
t = [x for x in json.load(open(sys.argv[1]))["ticks"] if x["updated"]][30:]
n = max(1, len(t))
b = sum(x["bytes"] for x in t) / n
print(f'{sys.argv[2]},{b:.0f},{30 * b:.0f},{sum(x["maps_sent"] for x in t) / n:.1f},{sum(x["probes_sent"] for x in t) / n:.1f},{sys.argv[3]}')
PY
  port=$((port + 2))
done
