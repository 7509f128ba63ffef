#!/usr/bin/env bash
# The error of the first frames against the converged image, with and without the probe
# warm-up (README, "No blotchy first seconds"). CSV on stdout:
#   frame,psnr_cold,psnr_warm,ssim_cold,ssim_warm,rmse_cold,rmse_warm
# Usage: bash bench/warmup_error.sh [SCENE] [FRAMES] [EYE_W] [EYE_H]   (DDISH_BUILD_DIR, default build/)
# Defaults: the Cornell box, 30 frames, 320x356 eyes: the issue's stereo-hmd case (11.1 ms budget).
set -euo pipefail
cd "$(dirname "$0")/.."
ddish=${DDISH_BUILD_DIR:-build}/ddish
scene=${1:-scenes/cornell_box.gltf}
frames=${2:-30}
w=${3:-320}
h=${4:-356}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
stem=$(basename "${scene%.*}")
common=(--display stereo --width "$w" --height "$h")
# Converged: no budget, every active probe traced each frame at 1024 samples, 12 frames.
"$ddish" render "$scene" "${common[@]}" --frames 12 --budget-ms 0 --probe-samples 1024 --warmup-ms 0 --out "$out/conv" >/dev/null 2>"$out/conv.log"
ref=$(ls "$out"/conv/*.png)
"$ddish" render "$scene" "${common[@]}" --frames "$frames" --every --warmup-ms 0 --out "$out/cold" >/dev/null 2>"$out/cold.log"
"$ddish" render "$scene" "${common[@]}" --frames "$frames" --every --out "$out/warm" >/dev/null 2>"$out/warm.log"
grep -h "warm-up:" "$out/warm.log" >&2 || true
echo "frame,psnr_cold,psnr_warm,ssim_cold,ssim_warm,rmse_cold,rmse_warm"
for ((k = 0; k < frames; ++k)); do
  tag=$(printf '%04d' "$k")
  row="$k"
  for metric in psnr ssim rmse; do
    for run in cold warm; do
      v=$("$ddish" compare "$out/$run/${stem}_${tag}_sbs_"*.png "$ref" --json 2>/dev/null |
          python3 -c "import json,sys; d=json.load(sys.stdin); print(d['$metric'] if '$metric' in d else d['images'][0]['$metric'])")
      row="$row,$v"
    done
  done
  echo "$row"
done
