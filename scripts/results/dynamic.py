"""Section 3: dynamic light (error over time after the scene changes, per hysteresis and blend)."""

import json
import os
import shutil
import statistics
import struct
from pathlib import Path

from common import (StepFailed, compare_many, fmt, log, median, only_exr, plot, reference, render, write_csv)


def posed_copy(src, t, dest_dir):
    """A static copy of an animated glTF posed at time t (linear translation channels sampled
    here), with its buffer and sidecar beside it, so `ddish reference` can render that instant."""
    doc = json.loads(Path(src).read_text())
    bins = {}
    def accessor(i):
        acc = doc["accessors"][i]
        bv = doc["bufferViews"][acc["bufferView"]]
        buf = doc["buffers"][bv["buffer"]]
        if bv["buffer"] not in bins:
            bins[bv["buffer"]] = (Path(src).parent / buf["uri"]).read_bytes()
        data = bins[bv["buffer"]]
        comps = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[acc["type"]]
        if acc.get("componentType") != 5126:
            raise StepFailed("posed copy: only float keyframes are supported")
        off = bv.get("byteOffset", 0) + acc.get("byteOffset", 0)
        stride = bv.get("byteStride", 4 * comps)
        return [struct.unpack_from(f"<{comps}f", data, off + k * stride) for k in range(acc["count"])]
    for anim in doc.get("animations", []):
        for ch in anim["channels"]:
            sampler = anim["samplers"][ch["sampler"]]
            if ch["target"]["path"] != "translation" or sampler.get("interpolation", "LINEAR") != "LINEAR":
                raise StepFailed("posed copy: only linear translation channels are supported")
            times = [x[0] for x in accessor(sampler["input"])]
            values = accessor(sampler["output"])
            if t <= times[0]:
                v = values[0]
            elif t >= times[-1]:
                v = values[-1]
            else:
                k = max(i for i in range(len(times)) if times[i] <= t)
                a = (t - times[k]) / (times[k + 1] - times[k])
                v = tuple(values[k][j] * (1 - a) + values[k + 1][j] * a for j in range(3))
            doc["nodes"][ch["target"]["node"]]["translation"] = list(v)
    doc.pop("animations", None)
    stem = f"{Path(src).stem}_t{t:g}".replace(".", "p")
    dest_dir.mkdir(parents=True, exist_ok=True)
    for buf in doc["buffers"]:
        shutil.copyfile(Path(src).parent / buf["uri"], dest_dir / buf["uri"])
    sidecar = Path(src).with_name(Path(src).stem + ".ddish.json")
    if sidecar.is_file():
        shutil.copyfile(sidecar, dest_dir / f"{stem}.ddish.json")
    out = dest_dir / f"{stem}.gltf"
    out.write_text(json.dumps(doc))
    # The copies carry the source's modification time, so the reference cache (keyed by name,
    # size and time) finds a posed reference again in the next run.
    stamp = Path(src).stat().st_mtime
    for p in dest_dir.glob(f"{stem}*"):
        os.utime(p, (stamp, stamp))
    for buf in doc["buffers"]:
        os.utime(dest_dir / buf["uri"], (stamp, stamp))
    return out


def recovery(errors, steady):
    """Frames until the 5-frame moving average of errors is within 10 % of steady (None: never)."""
    smooth = [statistics.fmean(errors[max(0, i - 2):i + 3]) for i in range(len(errors))]
    return next((i for i in range(len(errors)) if smooth[i] <= 1.1 * steady), None)


def frames_text(frames, fps, n):
    if frames is None:
        return f"not within {n} frames"
    return f"{frames} ({frames / fps * 1000:.0f} ms of scene time)"


def section_dynamic(runner, cfg, scenes, cache, results_dir, report):
    d = cfg["dynamic"]
    path = scenes["animated"]
    W, H = d["size"]
    stop = d["moving_frames"]
    total = stop + d["static_frames"]
    t0 = d["start_time"]
    report.append("## 3. Dynamic light: the animated Cornell box\n")
    report.append(
        f"`scenes/cornell_animated.gltf`: the short block slides to the red wall (t = 0–2 s) and back "
        f"(2–4 s), then rests where it started. Each run renders {total} frames at {d['fps']:g} fps from "
        f"t = {t0:g} s (`--time {t0:g} --every`), {W}×{H}, {d['samples']} paths per probe: frames "
        f"0–{stop - 1} while the block moves back, frames {stop}–{total - 1} after it has stopped "
        f"(t ≥ 4 s, the rest pose). Every frame after the stop is compared with a {d['ref_spp']}-spp "
        "reference of the rest pose. *Steady* is the median RMSE of the last third of the frames; "
        "*frames to recover* counts frames after the stop until the 5-frame moving average of the RMSE "
        "is within 10 % of the steady value (the light lags the geometry by this much).\n")
    try:
        rest_ref, rest_meta = reference(runner, cache, "animated_rest", path, (W, H), d["ref_spp"])
    except StepFailed as e:
        report.append(f"**Dynamic light: reference failed: {e}**\n")
        return None
    motion_refs = {}
    for t in d["motion_times"]:
        try:
            posed = posed_copy(path, t, runner.work / "posed")
            motion_refs[t] = reference(runner, cache, f"animated_t{t:g}", posed, (W, H), d["ref_spp"])[0]
        except StepFailed as e:
            report.append(f"**posed reference at t = {t:g} s failed: {e}**\n")
    series = []
    summary = []
    runs = [(h, "per-update") for h in d["hysteresis"]]
    runs += [(d["hysteresis"][len(d["hysteresis"]) // 2], "per-sample")]
    for h, blend in runs:
        tag = f"h{h:g}_{blend}".replace(".", "p")
        name = f"h{h:g}/{blend}"
        out = runner.work / f"dyn_{tag}"
        extra = ["--blend", blend]
        try:
            t = render(runner, path, out, ["--width", W, "--height", H, "--frames", total, "--every",
                                           "--time", t0, "--fps", d["fps"], "--hysteresis", h,
                                           "--probe-samples", d["samples"], *extra],
                       f"dynamic {name}")
            exrs = sorted(out.glob("frame_*.exr"))
            if len(exrs) != total:
                raise StepFailed(f"dynamic h={h:g}: {len(exrs)} frames written, expected {total}")
            pairs = {f"f{k:04d}": (exrs[k], rest_ref) for k in range(stop, total)}
            # The lag on its own: every frame after the stop against the last frame of an
            # independent run (another seed) that saw only the rest pose for as many frames, so the
            # renderer's fixed bias against the path tracer drops out and what is left is the lag
            # plus the noise of two independent estimates.
            still = runner.work / f"dyn_{tag}_still"
            render(runner, path, still, ["--width", W, "--height", H, "--frames", total,
                                         "--time", t0 + total / d["fps"], "--fps", d["fps"],
                                         "--hysteresis", h, "--probe-samples", d["samples"],
                                         "--seed", 2, *extra], f"dynamic {name}, rest pose only")
            still_exr = only_exr(still)
            for k in range(stop, total):
                pairs[f"s{k:04d}"] = (exrs[k], still_exr)
            for tm, ref in motion_refs.items():
                k = round((tm - t0) * d["fps"])
                if 0 <= k < total:
                    pairs[f"m{k:04d}"] = (exrs[k], ref)
            figs = compare_many(runner, pairs, f"dyn_{tag}")
        except StepFailed as e:
            report.append(f"**Dynamic h = {h:g}: failed: {e}**\n")
            log(str(e))
            continue
        rmse = [figs[f"f{k:04d}"]["rmse"] for k in range(stop, total)]
        psnr = [figs[f"f{k:04d}"]["psnr"] for k in range(stop, total)]
        n = len(rmse)
        steady = median(rmse[n - max(1, n // 3):])
        steady_psnr = median(psnr[n - max(1, n // 3):])
        recovered = recovery(rmse, steady)
        lag = [figs[f"s{k:04d}"]["rmse"] for k in range(stop, total)]
        lag_steady = median(lag[len(lag) - max(1, len(lag) // 3):])
        lag_recovered = recovery(lag, lag_steady)
        frame_ms = median([f["total_ms"] - f["stages_ms"].get("output", 0.0) for f in t["frames"][1:]])
        for k in range(stop, total):
            series.append({"series": name, "hysteresis": h, "blend": blend, "frame": k, "frames_after_stop": k - stop,
                           "t": t0 + k / d["fps"], "rmse": figs[f"f{k:04d}"]["rmse"],
                           "rmse_vs_end": figs[f"s{k:04d}"]["rmse"] if f"s{k:04d}" in figs else None,
                           "psnr": figs[f"f{k:04d}"]["psnr"], "ssim": figs[f"f{k:04d}"]["ssim"]})
        motion = {}
        for tm in motion_refs:
            k = round((tm - t0) * d["fps"])
            if f"m{k:04d}" in figs:
                motion[tm] = figs[f"m{k:04d}"]
        summary.append({"series": name, "hysteresis": h, "blend": blend, "steady_rmse": steady, "steady_psnr": steady_psnr,
                        "first_rmse": rmse[0], "first_psnr": psnr[0],
                        "frames_to_recover": recovered, "frame_ms": frame_ms,
                        "rmse_vs_end_at_stop": lag[0], "rmse_vs_end_steady": lag_steady,
                        "frames_to_settle": lag_recovered,
                        **{f"psnr_moving_t{tm:g}": motion[tm]["psnr"] for tm in motion},
                        **{f"rmse_moving_t{tm:g}": motion[tm]["rmse"] for tm in motion}})
    if not summary:
        return None
    # Where the sample-count-aware run made the same images as the per-update run of its
    # hysteresis, say so: with every probe traced at full samples every frame the rules agree.
    same = []
    for s in summary:
        if s["blend"] != "per-sample":
            continue
        a = [r["rmse"] for r in series if r["series"] == s["series"]]
        b = [r["rmse"] for r in series if r["hysteresis"] == s["hysteresis"] and r["blend"] == "per-update"]
        if a and a == b:
            same.append(f"{s['hysteresis']:g}")
    csv_path = results_dir / "dynamic.csv"
    write_csv(csv_path, ["series", "hysteresis", "blend", "frame", "frames_after_stop", "t", "rmse",
                         "psnr", "ssim", "rmse_vs_end"], series)
    keys = list(summary[0].keys())
    write_csv(results_dir / "dynamic_summary.csv", keys, summary)
    mt = [k for k in keys if k.startswith("psnr_moving")]
    report.append("| hysteresis | blend | ms/frame | RMSE at stop | RMSE steady | PSNR steady dB | frames to recover (10 %) "
                  "| lag RMSE at stop | lag RMSE steady | frames to settle (10 %) |"
                  + "".join(f" PSNR moving t={k[13:]} s |" for k in mt))
    report.append("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |" + " ---: |" * len(mt))
    for s in summary:
        report.append(f"| {s['hysteresis']:g} | {s['blend']} | {fmt(s['frame_ms'])} | {fmt(s['first_rmse'], 4)} | "
                      f"{fmt(s['steady_rmse'], 4)} | {fmt(s['steady_psnr'], 2)} | "
                      f"{frames_text(s['frames_to_recover'], d['fps'], n)} | {fmt(s['rmse_vs_end_at_stop'], 4)} | "
                      f"{fmt(s['rmse_vs_end_steady'], 4)} | {frames_text(s['frames_to_settle'], d['fps'], n)} |"
                      + "".join(f" {fmt(s[k], 2)} |" for k in mt))
    report.append("\n*lag RMSE*: each frame against the last frame of an independent run (`--seed 2`, same "
                  f"settings) that rendered only the rest pose for {total} frames: the renderer's fixed bias "
                  "against the path tracer drops out, leaving the light's lag plus the noise of two "
                  "independent estimates; *frames to settle* is *frames to recover* on that measure (steady: "
                  "its median over the last third).")
    if mt:
        report.append("\n*PSNR moving*: the frame at that instant during the motion against a reference "
                      "of a static copy of the scene posed at the same t (the keyframes sampled by this "
                      "script).")
    report.append("\n*blend*: `--blend per-update` is the published running average (weight 1 − hysteresis "
                  "per update); `--blend per-sample` is the sample-count-aware rule."
                  + (f" At hysteresis {', '.join(same)} the two rules gave identical errors in every frame: "
                     "under `--schedule uniform` every probe receives the full samples every frame, where "
                     "the rules coincide; they differ only when the scheduler gives probes fewer samples."
                     if same else "") + "\n")
    report.append(f"CSV: [results/dynamic.csv](results/dynamic.csv), "
                  f"[results/dynamic_summary.csv](results/dynamic_summary.csv).\n")
    if plot(runner, "dynamic.gp", csv_path, results_dir / "dynamic.png",
            f"animated Cornell box, {W}x{H}, after the block stops",
            {"slist": " ".join(s["series"] for s in summary)}):
        report.append("![error after the block stops](results/dynamic.png)\n")
    return summary
