#!/usr/bin/env bash
# `ddish xr` under the headless test runtime: the per-frame time split, the pose-to-submit
# latency and the fraction of frames within the runtime's display period. One CSV row on stdout:
#   scene,eye_w,eye_h,frames,probe_ms,upload_ms,raster_ms,submit_ms,frame_ms,pose_to_submit_median_ms,within_period
# (means over the frames after the first, which classifies probes and builds pipelines).
# Usage: bash bench/xr_frame_split.sh SCENE EYE_W EYE_H [FRAMES] [extra ddish xr options]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${DDISH_BUILD_DIR:-build}
scene=$1 w=$2 h=$3 frames=${4:-20}
shift 4 || shift $#
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '{"eye_width": %d, "eye_height": %d, "record_images": false}\n' "$w" "$h" >"$out/script.json"
XR_RUNTIME_JSON=$build/xr_runtime/ddish_test_runtime.json DDISH_XR_SCRIPT=$out/script.json DDISH_XR_OUT=$out \
  "$build/ddish" xr "$scene" --frames "$frames" --timings "$out/t.json" "$@" >/dev/null 2>"$out/log"
python3 - "$out/t.json" "$scene" "$w" "$h" <<'PY'
import json, statistics, sys
t = json.load(open(sys.argv[1]))
frames = t["frames"][1:]
xr = [f["xr"] for f in frames]
def mean(f): return statistics.mean(f(x) for x in frames)
st = lambda x, n: x["stages_ms"].get(n, 0.0)
raster = lambda x: sum(st(x, n) for n in ("raster_record", "shadow_gpu", "forward_gpu", "tonemap_gpu", "raster_wait", "readback"))
within = sum(1 for r in xr if r["within_period"]) / len(xr)
print(",".join(str(v) for v in [sys.argv[2].split("/")[-1], sys.argv[3], sys.argv[4], len(frames),
      round(mean(lambda x: st(x, "probe_update")), 2), round(mean(lambda x: st(x, "upload")), 2),
      round(mean(raster), 2), round(mean(lambda x: st(x, "output")), 2),
      round(statistics.mean(r["frame_ms"] for r in xr), 2),
      round(statistics.median(r["pose_to_submit_ms"] for r in xr), 2), round(within, 3)]))
PY
