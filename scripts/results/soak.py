#!/usr/bin/env python3
"""Section 6: the soak run. One long `ddish render` of the animated Cornell box (looping), the
budget scheduler on, an image every 100th frame, and per frame (from --timings) the resident
memory, the open file descriptors, the live Vulkan device-memory allocations and the frame time.

After the warm-up (the first WARMUP_FRACTION of the frames: pipelines, the probes' first passes,
the allocator reaching its working set), each resource must be flat: its median over the last
tenth of the rest at most 1 % above its median over the first tenth, and the frame time must
show no upward trend (least-squares slope over the post-warm-up frames, and the median of the
last tenth against the first tenth after the warm-up).

Standalone (bench/soak.sh): python3 scripts/results/soak.py [--frames N] [--build DIR]
[--size WxH] [--budget-ms MS] [--every N] [--out DIR]; prints the figures and exits 1 when a
resource grew or the frame time trends upward, 2 on a failed run.
"""

import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import ROOT, Runner, StepFailed, fmt, log, write_csv  # noqa: E402

SCENE = ROOT / "scenes" / "cornell_animated.gltf"
WARMUP_FRACTION = 0.1
GROWTH_LIMIT = 0.01  # the 1 %
RESOURCES = [("rss_kb", "resident memory (KiB)"), ("open_fds", "open file descriptors"),
             ("gpu_allocations", "Vulkan allocations"), ("gpu_bytes", "Vulkan bytes")]


def slope(xs, ys):
    """Least-squares slope of ys over xs."""
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0


def analyse(timings):
    """The soak figures of a --timings document (see the module's docstring for the rules)."""
    frames = timings["frames"]
    n = len(frames)
    if n < 20:
        raise StepFailed(f"soak: only {n} frames in the timings")
    w = max(1, int(n * WARMUP_FRACTION))
    after = frames[w:]
    out = {"frames": n, "warmup_frames": w, "rows": []}
    flat = True
    tenth = max(1, len(after) // 10)
    for key, name in RESOURCES:
        values = [f["resources"][key] for f in after]
        start = statistics.median(values[:tenth])
        end = statistics.median(values[-tenth:])
        growth = (end - start) / start if start > 0 else (0.0 if end <= 0 else float("inf"))
        ok = growth < GROWTH_LIMIT
        flat = flat and ok
        out["rows"].append({"resource": name, "first_tenth": start, "last_tenth": end,
                            "peak": max(values), "growth_pct": 100.0 * growth,
                            "flat": "yes" if ok else "NO"})
    ms = [f["frame_ms"] for f in after]
    xs = list(range(len(ms)))
    first, last = statistics.median(ms[:tenth]), statistics.median(ms[-tenth:])
    per_1000 = 1000.0 * slope(xs, ms)
    # "No upward trend": the last tenth's median within 5 % of the first's, or a slope that adds
    # less than 5 % of the median frame over the whole post-warm-up run.
    median_ms = statistics.median(ms)
    rise = per_1000 * len(ms) / 1000.0
    trend_ok = last <= 1.05 * first or rise <= 0.05 * median_ms
    out.update({"frame_ms_median": median_ms, "frame_ms_first_tenth": first,
                "frame_ms_last_tenth": last, "frame_ms_slope_per_1000": per_1000,
                "within_budget": sum(1 for f in after if f["scheduler"].get("budget_ms", 0) <= 0 or
                                     f["frame_ms"] <= f["scheduler"]["budget_ms"]) / len(after),
                "trend_ok": trend_ok, "flat": flat})
    return out


def frame_ms(frame):
    return frame.get("total_ms", sum(frame["stages_ms"].values()))


def run(runner, frames, size, budget_ms, every, out):
    tj = Path(str(out) + ".timings.json")
    shutil.rmtree(out, ignore_errors=True)
    w, h = size
    runner.run([runner.exe("ddish"), "render", SCENE, "--frames", frames, "--loop",
                f"--every={every}", "--width", w, "--height", h, "--budget-ms", budget_ms,
                "--schedule", "visibility", "--out", out, "--timings", tj],
               f"soak: {frames} frames", timeout=6 * 3600)
    doc = json.loads(tj.read_text())
    for f in doc["frames"]:
        f["frame_ms"] = frame_ms(f)
    written = sorted(Path(out).glob("*.png"))
    result = analyse(doc)
    result["images"] = len(written)
    result["budget_ms"] = budget_ms
    result["size"] = f"{w}×{h}"
    return result, doc


def report_lines(r, every):
    lines = [f"`ddish render scenes/cornell_animated.gltf --frames {r['frames']} --loop "
             f"--every={every} --budget-ms {r['budget_ms']} --schedule visibility` at {r['size']}: "
             f"{r['images']} images written. The first {r['warmup_frames']} frames are the warm-up; "
             "a resource is flat when its median over the last tenth of the rest is within 1 % of "
             "its median over the first tenth (medians, so that a file open while an image is "
             "written is not taken for a leak; the peak is shown too).\n",
             "| resource | first tenth after warm-up | last tenth | peak | growth % | flat |",
             "| --- | --- | --- | --- | --- | --- |"]
    for row in r["rows"]:
        lines.append(f"| {row['resource']} | {row['first_tenth']:.0f} | {row['last_tenth']:.0f} | "
                     f"{row['peak']} | {row['growth_pct']:.3f} | {row['flat']} |")
    lines.append("")
    lines.append(f"Frame time after the warm-up: median {fmt(r['frame_ms_median'], 2)} ms; first tenth "
                 f"{fmt(r['frame_ms_first_tenth'], 2)} ms, last tenth {fmt(r['frame_ms_last_tenth'], 2)} ms; "
                 f"least-squares slope {r['frame_ms_slope_per_1000']:+.3f} ms per 1000 frames; "
                 f"{100 * r['within_budget']:.1f} % of frames within the budget. Upward trend: "
                 f"{'none' if r['trend_ok'] else 'YES'}.\n")
    return lines


def section_soak(runner, cfg, results_dir, report):
    report.append("## 6. Soak\n")
    s = cfg["soak"]
    result, doc = run(runner, s["frames"], s["size"], s["budget_ms"], s["every"],
                      runner.work / "soak")
    rows = [{"frame": f["frame"], "frame_ms": f["frame_ms"], **f["resources"]} for f in doc["frames"]]
    write_csv(results_dir / "soak.csv", ["frame", "frame_ms", "rss_kb", "open_fds",
                                         "gpu_allocations", "gpu_bytes"], rows)
    report += report_lines(result, s["every"])
    report.append("Per-frame figures: [soak.csv](results/soak.csv).\n")
    log(f"soak: flat {result['flat']}, trend ok {result['trend_ok']}")
    return result


def main():
    ap = argparse.ArgumentParser(description="soak run: resources and frame time over a long render")
    ap.add_argument("--frames", type=int, default=10000)
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--budget-ms", type=float, default=30.0)
    ap.add_argument("--every", type=int, default=100)
    ap.add_argument("--build", default=os.environ.get("DDISH_BUILD_DIR", str(ROOT / "build")))
    ap.add_argument("--out", default=None, help="keep the images and timings in OUT (default: a temporary folder)")
    a = ap.parse_args()
    try:
        w, h = (int(v) for v in a.size.lower().split("x"))
    except ValueError:
        print(f"soak: error: --size needs WxH, got '{a.size}'", file=sys.stderr)
        return 2
    build = Path(a.build).resolve()
    work = Path(a.out).resolve() if a.out else Path(tempfile.mkdtemp(prefix="ddish-soak-"))
    work.mkdir(parents=True, exist_ok=True)
    runner = Runner(build, work, work / "commands.txt")
    if runner.exe("ddish") is None:
        print(f"soak: error: {build / 'ddish'} is not built", file=sys.stderr)
        return 2
    try:
        result, _ = run(runner, a.frames, (w, h), a.budget_ms, a.every, work / "soak")
    except StepFailed as e:
        print(f"soak: error: {e}", file=sys.stderr)
        return 2
    print("\n".join(report_lines(result, a.every)))
    if not a.out:
        shutil.rmtree(work, ignore_errors=True)
    return 0 if result["flat"] and result["trend_ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
