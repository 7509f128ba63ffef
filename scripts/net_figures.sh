#!/usr/bin/env bash
# Figures of the probe stream (docs/protocol.md), from the built binaries on loopback:
#   1. bytes per L2 probe per encoding (the first update of an 8x8x8 grid, every probe sent, with
#      its 8x8 distance-moment map, 256 bytes of it, and without: --probe-visibility 0) and the
#      PSNR of a view's image against the in-process render of the same probes (visibility as
#      the server's);
#   2. bytes per second, static (cornell_box) against animated (cornell_animated), change-driven
#      stream at the default threshold, uniform schedule (every probe traced every tick), 30 ticks/s;
#   3. probe age at a client (server trace end -> upload, ms): median and 95th percentile;
#   4. the server's work per tick (update + publish + requests, not idling) against 1, 2, 4 and 8
#      clients (64x64 views each, visibility schedule), median over the ticks after the first 30;
#   5. reconnection times from the 4-client x 10-restart fault test (tests/app), per client;
#   6. what a relay forwards (bench/net_relay: bricks at 30 ticks/s to 1 and 4 clients).
# (scripts/net_moment_curve.sh: the moment maps' bytes against a client's image error.)
# Usage: bash scripts/net_figures.sh [BUILD_DIR] (default build/); ports 24000-24039 and 24100-24107; ~4 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
D=$(mktemp -d /tmp/ddish_net_figures.XXXX)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$D"' EXIT
PROBES="--grid 8,8,8 --probe-samples 128 --schedule uniform"
IMAGE="--width 256 --height 256"
S=scenes/cornell_box.gltf
wait_for() { for _ in $(seq 1 600); do grep -q "$2" "$1" 2>/dev/null && return 0; sleep 0.1; done; echo "timeout: $2 in $1" >&2; return 1; }

for vis in 8 0; do
  "$B/ddish" render $S $PROBES $IMAGE --probe-visibility $vis --frames 5 --warmup-ms 0 --out "$D/render$vis" >/dev/null 2>&1
done
echo "encoding,zstd,moment_maps,bytes_first_update,probes_sent,bytes_per_probe,psnr_vs_in_process_db"
port=24000
for run in fp16:8 shared-exponent:8 compact:8 fp16:0 compact:0; do
  enc=${run%:*} vis=${run#*:}
  for z in "" "--zstd"; do
    "$B/ddish" serve $S $PROBES --probe-visibility $vis --bind tcp://127.0.0.1:$port --frames 5 --seconds 30 \
      --encoding $enc $z --delta-threshold 0 --moment-threshold 0 --timings "$D/serve.json" >"$D/serve.log" 2>&1 &
    pid=$!
    wait_for "$D/serve.log" "update 5:"
    "$B/ddish" view $S --grid 8,8,8 $IMAGE --connect tcp://127.0.0.1:$port --out "$D/view" >/dev/null 2>&1
    kill -TERM $pid; wait $pid || true
    psnr=$("$B/ddish" compare "$D/view/frame_0000.exr" "$D/render$vis/frame_0004.exr" | awk '/psnr/ {print $2}')
    python3 - "$D/serve.json" "$enc" "${z:+yes}" "$psnr" "$vis" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
t = d["ticks"]
first = next(x for x in t if x["probes_sent"] > 0)
headers = 100 * d["summary"]["bricks"]  # one frame per brick (4x4x4 probes) per tick
maps = f'{sys.argv[5]}x{sys.argv[5]}' if sys.argv[5] != "0" else "none"
print(f'{sys.argv[2]},{sys.argv[3] or "no"},{maps},{first["bytes"]},{first["probes_sent"]},{(first["bytes"] - headers) / first["probes_sent"]:.2f},{sys.argv[4]}')
PY
    port=$((port + 2))
  done
done

echo
echo "scene,bytes_per_second,ticks,mean_probes_sent_per_tick_after_1s,mean_maps_sent_per_tick_after_1s"
for scene in cornell_box cornell_animated; do
  "$B/ddish" serve scenes/$scene.gltf --grid 8,8,8 --probe-samples 64 --schedule uniform --bind tcp://127.0.0.1:$port \
    --frames 150 --fps 30 --seconds 6 --timings "$D/rate.json" >/dev/null 2>&1
  python3 - "$D/rate.json" "$scene" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
t = [x for x in d["ticks"] if x["updated"]]
late = t[30:]
n = max(1, len(late))
print(f'{sys.argv[2]},{d["summary"]["bytes_per_second"]:.0f},{len(d["ticks"])},{sum(x["probes_sent"] for x in late) / n:.1f},'
      f'{sum(x["maps_sent"] for x in late) / n:.1f}')
PY
  port=$((port + 2))
done

echo
echo "probe_age_ms_median,probe_age_ms_p95,frames"
"$B/ddish" serve $S --grid 8,8,8 --probe-samples 64 --bind tcp://127.0.0.1:$port --fps 30 --seconds 20 >"$D/age.log" 2>&1 &
pid=$!
sleep 1
"$B/ddish" view $S --grid 8,8,8 --width 128 --height 128 --connect tcp://127.0.0.1:$port --frames 90 \
  --frame-wait-ms 40 --out "$D/age" --timings "$D/age.json" >/dev/null 2>&1
kill -TERM $pid; wait $pid || true
python3 - "$D/age.json" <<'PY'
import json, sys, statistics
a = sorted(f["stream"]["probe_age_ms"] for f in json.load(open(sys.argv[1]))["frames"][10:] if f["stream"]["probe_age_ms"] is not None)
print(f'{statistics.median(a):.1f},{a[int(0.95 * (len(a) - 1))]:.1f},{len(a)}')
PY

echo
echo "clients,server_busy_ms_median,server_probe_ms_median,ticks_with_all_clients"
port=24030
for n in 1 2 4 8; do
  "$B/ddish" serve $S --grid 8,8,8 --probe-samples 64 --bind tcp://127.0.0.1:$port --fps 30 --seconds 40 \
    --timings "$D/tick$n.json" >"$D/tick.log" 2>&1 &
  pid=$!
  wait_for "$D/tick.log" " on tcp://"
  views=()
  for c in $(seq 1 $n); do
    "$B/ddish" view $S --grid 8,8,8 --width 64 --height 64 --msaa 1 --connect tcp://127.0.0.1:$port --frames 150 \
      --frame-wait-ms 40 --out "$D/tick_view$c" >/dev/null 2>&1 &
    views+=($!)
  done
  wait "${views[@]}" || true
  kill -TERM $pid 2>/dev/null || true; wait $pid || true
  python3 - "$D/tick$n.json" "$n" <<'PY'
import json, sys, statistics
n = int(sys.argv[2])
t = [x for x in json.load(open(sys.argv[1]))["ticks"] if x["clients"] == n and x["updated"]][30:]
print(f'{n},{statistics.median(x["busy_ms"] for x in t):.2f},{statistics.median(x["probe_ms"] for x in t):.2f},{len(t)}')
PY
done

echo
echo "client,reconnections,median_s,max_s"
DDISH_RECONNECT_FIGURE="$D/reconnect.json" "$B/tests/test_app" --gtest_filter='ServeRestart.*' >"$D/restart.log" 2>&1 ||
  { tail -20 "$D/restart.log" >&2; exit 1; }
python3 - "$D/reconnect.json" <<'PY'
import json, sys, statistics
for name, c in json.load(open(sys.argv[1])).items():
    r = c["reconnect_s"]
    print(f'{name},{len(r)},{statistics.median(r):.3f},{max(r):.3f}')
PY

echo
"$B/bench/net_relay" --grid 16 --fps 30 --seconds 3 --clients 1,4 --port 24100

