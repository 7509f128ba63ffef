"""Section 1's memory: peak resident memory of a multi-view render against its view count. Issue 20's
goal: beyond an N-independent base (scene, textures, BVH, pipelines, one batch's render target), at
most 32 bytes per quilt pixel; and the largest Looking Glass's quilt (65", 72 views of 1024x910)
measured on this machine."""

import shutil

from common import SCENE_NAMES, StepFailed, fmt, log, render


def _peak_mb(runner, path, out, args, what):
    """One single-frame render; its peak resident memory in MB (the process's own ru_maxrss)."""
    render(runner, path, out, [*args, "--frames", 1], what)
    shutil.rmtree(out, ignore_errors=True)
    return runner.last_peak_kib / 1024.0


def _per_pixel(base_mb, peak_mb, extra_pixels):
    return (peak_mb - base_mb) * 1024.0 * 1024.0 / extra_pixels if extra_pixels > 0 else None


def memory(runner, cfg, scenes, report, overhead=None):
    """Peak resident memory of single-frame renders of the rig at three view counts. What the
    views cost is the growth between the last two, both beyond the batch of views the renderer
    draws together into one reused target (Renderer::batch_size: at most 256 MB of targets, about
    3 Sponza views of 420x560 on lavapipe), so that the target's growth up to a full batch, part of
    the N-independent base, is not counted per view. Then the largest display's quilt against one
    of its views (one view a batch at that size) and, where the output-overhead pair ran, its
    multi-frame runs against the middle count (writing every frame holds a second frame's images
    while the writer encodes)."""
    m = cfg.get("memory")
    if not m:
        return None
    key = m["scene"]
    path = scenes[key]
    if not path.is_file():
        report.append(f"**Memory: skipped — {path} is absent.**\n")
        return None
    W, H = cfg["scaling_tile"]
    rig = ["--display", "looking-glass-portrait", "--width", W, "--height", H, "--msaa", cfg["scaling_msaa"]]
    one, lo, hi = m["views"]
    result = {"scene": key, "tile": (W, H), "views": (one, lo, hi)}
    try:
        peaks = {n: _peak_mb(runner, path, runner.work / f"memory_{key}_{n}", [*rig, "--views", n],
                             f"memory {key}, {n} views") for n in (one, lo, hi)}
        result["peak_mb"] = peaks
        result["bytes_per_pixel"] = _per_pixel(peaks[lo], peaks[hi], (hi - lo) * W * H)
        large = m.get("large")
        if large:
            lw, lh = large["tile"]
            disp = ["--display", large["display"], "--width", lw, "--height", lh]
            base = _peak_mb(runner, path, runner.work / f"memory_{key}_large_1", [*disp, "--views", 1],
                            f"memory {key}, {large['display']}, 1 view")
            full = _peak_mb(runner, path, runner.work / f"memory_{key}_large", disp,
                            f"memory {key}, {large['display']}, {large['views']} views")
            result["large"] = {"display": large["display"], "views": large["views"], "tile": (lw, lh),
                               "base_mb": base, "peak_mb": full,
                               "bytes_per_pixel": _per_pixel(base, full, (large["views"] - 1) * lw * lh)}
    except StepFailed as e:
        report.append(f"**Memory: failed: {e}**\n")
        log(str(e))
        return None

    lines = [f"Peak resident memory ({SCENE_NAMES[key]}, one frame, `ddish render` writing the quilt as "
             f"PNG and EXR; the process's own peak from `wait4`): {fmt(peaks[one])} MB at {one} view of "
             f"{W}x{H}, {fmt(peaks[lo])} MB at {lo}, {fmt(peaks[hi])} MB at {hi}, so each view beyond a "
             f"full batch adds **{fmt(result['bytes_per_pixel'])} bytes per quilt pixel** (goal: at most 32; "
             f"from {lo} to {hi} views)."]
    if "large" in result:
        L = result["large"]
        lw, lh = L["tile"]
        lines.append(f"The {L['display']} quilt ({L['views']} views of {lw}x{lh}, "
                     f"{fmt(L['views'] * lw * lh / 1e6)} Mpixels): {fmt(L['peak_mb'])} MB peak against "
                     f"{fmt(L['base_mb'])} MB for one of its views, "
                     f"**{fmt(L['bytes_per_pixel'])} bytes per extra quilt pixel**.")
    if overhead and overhead.get("peak_mb") and (overhead["scene"], overhead["views"]) == (key, hi):
        for name, label in (("last", "writing only the last frame"), ("every", "writing every frame")):
            mb = overhead["peak_mb"][name]
            lines.append(f"The output-overhead run, {label} ({overhead['frames']} frames): {fmt(mb)} MB, "
                         f"{fmt(_per_pixel(peaks[lo], mb, (hi - lo) * W * H))} bytes per quilt pixel "
                         f"beyond the {lo}-view run" + (" (the loop renders the next frame while the writer "
                                                       "still holds the last one's images)." if name == "every"
                                                       else "."))
        result["overhead_bytes_per_pixel"] = {
            n: _per_pixel(peaks[lo], overhead["peak_mb"][n], (hi - lo) * W * H) for n in ("last", "every")}
    report.append(" ".join(lines) + "\n")
    return result
