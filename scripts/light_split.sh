#!/usr/bin/env bash
# Where a probe-lit image's error comes from: the image split into three terms, each against the
# same term of the path-traced reference (docs/probe-visibility.md, "Where the excess light
# comes from"):
#   direct  the lights' direct light alone: `render --sky 0,0,0 --no-indirect` against
#           `reference --sky 0,0,0 --bounces 1` (shadow maps against shadow rays);
#   lights  what the lights add by interreflection: `render --sky 0,0,0` less the direct term,
#           against `reference --sky 0,0,0` less its direct term (the probes' part);
#   sky     what the sky adds, seen and reflected: the full image less the sky-less one, both
#           renderers.
# For each term: the mean over the image and over a 4 x 3 grid of tiles (top row first, mean of
# R, G, B on linear values), the render's, the reference's and their ratio. A term whose ratio is
# near 1 everywhere is right on average; the excess shows as a ratio above 1 and where it lies.
# Emissive surfaces count as lights: their light on other surfaces is in the reference's direct
# term but in the render's lights term (the renderer has it from the probes).
#
# Usage: bash scripts/light_split.sh SCENE CAMERA [OUT_DIR] [-- RENDER_OPTIONS...]
#   CAMERA: a camera node's name, or - for the scene's default camera. SIZE (160x120), SPP (512) and FRAMES (24) from the environment; the render runs at the
#   results report's settings (L2, hysteresis 0.95, 15 bounces, uniform schedule, no budget, no
#   warm-up, its last frame) plus RENDER_OPTIONS (--grid 8,4,4, --probe-placement fit, ...).
#   OUT_DIR (default: a temporary folder, removed) keeps the six images. Needs build/ddish and
#   oiiotool (openimageio-tools, scripts/bootstrap.sh). About 3 minutes for Sponza at 160x120.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: bash scripts/light_split.sh SCENE CAMERA [OUT_DIR] [-- RENDER_OPTIONS...]" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
D=${DDISH:-$root/build/ddish}
scene=$1
camera=$2
shift 2
out=""
if [ $# -gt 0 ] && [ "$1" != "--" ]; then
  out=$1
  shift
fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
extra=("$@")
if [ -z "$out" ]; then
  out=$(mktemp -d /tmp/ddish_light_split.XXXX)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
size=${SIZE:-160x120}
w=${size%x*}
h=${size#*x}
view=(--width "$w" --height "$h")
[ "$camera" != "-" ] && view+=(--camera "$camera")
ref=("$D" reference "$scene" "${view[@]}" --spp "${SPP:-512}")
render=("$D" render "$scene" "${view[@]}" --frames "${FRAMES:-24}" --sh-order 2 --hysteresis 0.95 --bounces 15
        --schedule uniform --budget-ms 0 --warmup-ms 0 "${extra[@]}")
step() {  # step NAME COMMAND...: runs one image, says so on stderr
  local name=$1
  shift
  echo "light_split: $name" >&2
  "$@" --out "$out/$name" >/dev/null 2>"$out/$name.log" || { cat "$out/$name.log" >&2; exit 1; }
}
step ref_full "${ref[@]}"
step ref_lights "${ref[@]}" --sky 0,0,0
step ref_direct "${ref[@]}" --sky 0,0,0 --bounces 1
step render_full "${render[@]}"
step render_lights "${render[@]}" --sky 0,0,0
step render_direct "${render[@]}" --sky 0,0,0 --no-indirect
last=$(printf 'frame_%04d.exr' $((${FRAMES:-24} - 1)))
for name in ref_full ref_lights ref_direct; do
  oiiotool --dumpdata "$out/$name/reference.exr" >"$out/$name.txt"
done
for name in render_full render_lights render_direct; do
  oiiotool --dumpdata "$out/$name/$last" >"$out/$name.txt"
done
python3 - "$out" "$scene" "$camera" <<'EOF'
import re, sys
out, scene, camera = sys.argv[1:4]
pixel = re.compile(r"Pixel \((\d+), (\d+)\): (\S+) (\S+) (\S+)")

def load(name):
    img = {}
    for line in open(f"{out}/{name}.txt"):
        m = pixel.search(line)
        if m:
            x, y = int(m.group(1)), int(m.group(2))
            img[(x, y)] = sum(float(m.group(k)) for k in (3, 4, 5)) / 3.0
    return img

imgs = {n: load(n) for n in ("ref_full", "ref_lights", "ref_direct", "render_full", "render_lights", "render_direct")}
W = 1 + max(x for x, _ in imgs["ref_full"])
H = 1 + max(y for _, y in imgs["ref_full"])
def term(a, b=None):
    return {p: imgs[a][p] - (imgs[b][p] if b else 0.0) for p in imgs[a]}
terms = [("direct", term("render_direct"), term("ref_direct")),
         ("lights", term("render_lights", "render_direct"), term("ref_lights", "ref_direct")),
         ("sky", term("render_full", "render_lights"), term("ref_full", "ref_lights")),
         ("all", term("render_full"), term("ref_full"))]
def mean(img, x0, x1, y0, y1):
    n = (x1 - x0) * (y1 - y0)
    return sum(img[(x, y)] for y in range(y0, y1) for x in range(x0, x1)) / n
def ratio(a, b):
    return f"{a / b:.2f}" if b > 1e-6 else "-"
print(f"light split: {scene}, {camera}, {W}x{H} (means of linear R, G, B; render / reference)")
print()
print("| term | image: render | reference | ratio | tile ratios, top row first (4 x 3) |")
print("| --- | ---: | ---: | ---: | --- |")
for name, r, f in terms:
    a, b = mean(r, 0, W, 0, H), mean(f, 0, W, 0, H)
    rows = []
    for ty in range(3):
        cells = []
        for tx in range(4):
            x0, x1, y0, y1 = tx * W // 4, (tx + 1) * W // 4, ty * H // 3, (ty + 1) * H // 3
            cells.append(ratio(mean(r, x0, x1, y0, y1), mean(f, x0, x1, y0, y1)))
        rows.append(" ".join(cells))
    print(f"| {name} | {a:.4f} | {b:.4f} | {ratio(a, b)} | {' / '.join(rows)} |")
EOF
