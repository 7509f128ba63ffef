"""Section 1's output overhead: what writing every frame's images adds to the wall time of a
multi-view run (issue 20's goal: at most 10 % for a 10-frame 48-view Sponza run with --every)."""

import shutil
import time

from common import SCENE_NAMES, StepFailed, fmt, log, render


def output_overhead(runner, cfg, scenes, report):
    """Runs the same render twice, writing only the last frame and writing every frame (`--every`),
    in that order, and reports both wall times (the whole process: start, frames, writer drain)."""
    o = cfg.get("output_overhead")
    if not o:
        return None
    key = o["scene"]
    path = scenes[key]
    if not path.is_file():
        report.append(f"**Output overhead: skipped — {path} is absent.**\n")
        return None
    W, H = cfg["scaling_tile"]
    args = ["--display", "looking-glass-portrait", "--views", o["views"], "--width", W, "--height", H,
            "--msaa", cfg["scaling_msaa"], "--frames", o["frames"]]
    walls, peaks = {}, {}
    try:
        for name, extra in (("last frame", []), ("every frame", ["--every"])):
            out = runner.work / f"output_{key}_{name.split()[0]}"
            t0 = time.monotonic()
            t = render(runner, path, out, [*args, *extra], f"output overhead {key}, {name}")
            walls[name] = (time.monotonic() - t0, sum(1 for f in t["frames"] if f.get("read_back")))
            peaks[name.split()[0]] = runner.last_peak_kib / 1024.0
            shutil.rmtree(out, ignore_errors=True)
    except StepFailed as e:
        report.append(f"**Output overhead: failed: {e}**\n")
        log(str(e))
        return None
    last, every = walls["last frame"][0], walls["every frame"][0]
    overhead = (every - last) / last
    report.append(
        f"Output overhead ({SCENE_NAMES[key]}, {o['views']} views, {o['frames']} frames, the rig above; "
        f"wall time of the whole `ddish render` process): writing only the last frame "
        f"{fmt(last, 1)} s, writing every frame (`--every`: {walls['every frame'][1]} quilts, PNG and EXR) "
        f"{fmt(every, 1)} s, so output adds **{fmt(100 * overhead, 1)} %** (one pair of runs; the "
        f"writer thread encodes while the next frames render).\n")
    return {"scene": key, "views": o["views"], "frames": o["frames"], "last_s": last, "every_s": every,
            "overhead": overhead, "peak_mb": peaks}
