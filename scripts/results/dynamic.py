"""Section 3: dynamic light. scenes/cornell_light.gltf's point light jumps, is switched off and
on again; per hysteresis and blend rule, the error of every frame after each event against a
converged reference of the new state, and the lag on its own (against an independent converged
run of the same state), with the frames until each is back to its steady value and the decay
rate compared with the running average's theory, log(0.1) / log(alpha) frames."""

import json
import math
import os
import shutil
import statistics
import struct
from pathlib import Path

from common import (ROOT, StepFailed, compare_many, fmt, frame_stats, log, only_exr, plot, reference, render,
                    write_csv)


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
            interpolation = sampler.get("interpolation", "LINEAR")
            if ch["target"]["path"] != "translation" or interpolation not in ("LINEAR", "STEP"):
                raise StepFailed("posed copy: only linear and step translation channels are supported")
            times = [x[0] for x in accessor(sampler["input"])]
            values = accessor(sampler["output"])
            if t <= times[0]:
                v = values[0]
            elif t >= times[-1]:
                v = values[-1]
            else:
                k = max(i for i in range(len(times)) if times[i] <= t)
                a = (t - times[k]) / (times[k + 1] - times[k])
                if interpolation == "STEP":  # the key's value holds until the next key
                    a = 0.0
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


SCENE = ROOT / "scenes" / "cornell_light.gltf"


def smooth(values):
    """Centred 5-frame moving average (fewer frames at the ends)."""
    return [statistics.fmean(values[max(0, i - 2):i + 3]) for i in range(len(values))]


def recovery(errors, steady):
    """Frames until the 5-frame moving average of errors is within 10 % of steady (None: never)."""
    sm = smooth(errors)
    return next((i for i in range(len(errors)) if sm[i] <= 1.1 * steady), None)


def _fit_at(y, r):
    """Least squares y_k = a + c r^(2k) with a, c >= 0 for one r: (residual, a, c)."""
    n = len(y)
    basis = [r ** (2 * k) for k in range(n)]
    sa, saa = sum(basis), sum(b * b for b in basis)
    sy, say = sum(y), sum(b * v for b, v in zip(basis, y))
    det = n * saa - sa * sa
    c = (n * say - sa * sy) / det if det > 1e-300 else 0.0
    a = (sy - c * sa) / n
    if c < 0.0:
        c, a = 0.0, sy / n
    if a < 0.0:
        a, c = 0.0, say / saa
    return sum((v - a - c * b) ** 2 for v, b in zip(y, basis)), a, c


def fit_decay(errors):
    """Fits the running average's transient on a noise floor, err(k)^2 = floor^2 + c^2 r^(2k)
    (independent parts add in quadrature): -> (floor, c, r). r on a grid in log(1 - r), coarse,
    then refined around the best; floor^2 and c^2 by linear least squares for each r."""
    y = [e * e for e in errors]
    if len(y) < 4:
        return (min(errors) if errors else float("nan")), float("nan"), float("nan")
    def grid(lo, hi, steps):
        return [lo + (hi - lo) * i / steps for i in range(steps + 1)]
    best = None
    for x in grid(0.3, 4.0, 150):
        f = _fit_at(y, 1.0 - 10.0 ** -x)
        if best is None or f[0] < best[0][0]:
            best = (f, x)
    step = 3.7 / 150
    for x in grid(best[1] - step, best[1] + step, 100):
        f = _fit_at(y, 1.0 - 10.0 ** -x)
        if f[0] < best[0][0]:
            best = (f, x)
    (_, a, c), x = best
    return math.sqrt(a), math.sqrt(c), 1.0 - 10.0 ** -x


def transient_frames(errors, floor):
    """Frames until the transient, sqrt(err^2 - floor^2) (5-frame moving average of err^2), is
    below 10 % of its value in the first frame after the event: what log(0.1) / log(alpha)
    predicts for a running average, whatever the size of the jump against the noise."""
    if not errors:
        return None
    t0 = math.sqrt(max(0.0, errors[0] ** 2 - floor ** 2))
    sm2 = smooth([e * e for e in errors])
    return next((k for k in range(len(errors)) if math.sqrt(max(0.0, sm2[k] - floor ** 2)) <= 0.1 * t0),
                None)


def frames_text(frames, fps, n):
    if frames is None:
        return f"not within {n} frames"
    return f"{frames} ({frames / fps:.2f} s)"


def theory_frames(alpha):
    return math.log(0.1) / math.log(alpha)


def theory_recover(alpha, first, floor):
    """Frames until floor^2 + T^2 alpha^(2k) <= (1.1 floor)^2 for a transient T at the event (the
    first frame's error above the floor): when the RMSE is back within 10 % of its steady value."""
    t0 = math.sqrt(max(0.0, first ** 2 - floor ** 2))
    if not (floor > 0.0 and t0 > 0.0):
        return None
    return max(0.0, math.log(math.sqrt(1.21 - 1.0) * floor / t0) / math.log(alpha))


def section_dynamic(runner, cfg, scenes, cache, results_dir, report):
    d = cfg["dynamic"]
    path = SCENE
    W, H = d["size"]
    seg_s = d["segment_s"]
    events = [{"t": float(t), "id": eid, "what": what, "state": state}
              for t, eid, what, state in d["events"]]

    def timeline(fps):
        """Frame of each event at fps (frame k shows t = k / fps; the events fall on whole frames)
        and the frames of the run: to the last event + segment_s."""
        frames = [round(e["t"] * fps) for e in events]
        return frames, frames[-1] + round(seg_s * fps)

    fps_text = ", ".join(f"{d['fps'][h]:g} fps at α = {h:g} ({timeline(d['fps'][h])[1]} frames)"
                         for h in d["hysteresis"])
    report.append("## 3. Dynamic light: a point light that jumps and switches\n")
    report.append(
        "`scenes/cornell_light.gltf` (scenes/README.md): the Cornell box with its emissive ceiling quad "
        "as a fill light and a 6 W/sr point light on STEP keys, at A (near the red wall, front) from "
        "t = 0; " + "; ".join(f"at t = {e['t']:g} s {e['what']}" for e in events) + ". "
        "glTF cannot animate intensity, so *off* is a move into a closed housing behind the back wall: "
        "the path tracer and the cube shadow map both see every ray of the light blocked. "
        f"Each run renders t = 0–{events[-1]['t'] + seg_s:g} s (`--every`), {fps_text}: one probe "
        f"update per frame, so the frame rate sets how many updates fall between events; {W}×{H}, "
        f"{d['samples']} paths per probe, `--schedule uniform`. Every frame from an event to the next "
        f"({seg_s:g} s) is compared with a {d['ref_spp']}-spp path-traced reference of the new state "
        "(a static copy of the scene posed at the event) and, for the lag on its own, with the last "
        f"frame of an independent converged run of the new state (`--seed 2`, {d['still_frames']} "
        f"updates at hysteresis {d['still_hysteresis']:g}, i.e. a running mean): there the renderer's "
        "fixed bias against the path tracer drops out and what is left is the probes' lag plus the "
        "noise of two estimates.\n")
    report.append(
        "The RMSE after an event is fitted as RMSE(k)² = floor² + c²·r^(2k), the running average's "
        "transient over a noise floor: *steady* is the fitted floor (the asymptote; the last frames "
        "of a segment are not yet settled at hysteresis 0.99), *r* the measured decay per frame. "
        "*Frames to recover* counts frames after the event until the 5-frame moving average of the "
        "RMSE is within 10 % of steady (it depends on how large the jump is against the floor); "
        "*transient to 10 %* counts frames until sqrt(RMSE² − floor²) is below 10 % of its value "
        "in the first frame after the event, the figure the theory predicts: a running average "
        "keeps a fraction α^k of the old state after k more updates, so log(0.1) / log(α) frames "
        f"(α = 0.9: {theory_frames(0.9):.1f}, 0.95: {theory_frames(0.95):.1f}, 0.99: "
        f"{theory_frames(0.99):.1f}). The scene runs in for {events[0]['t']:g} s "
        f"({', '.join(str(timeline(d['fps'][h])[0][0]) for h in d['hysteresis'])} frames) before the "
        "first event; "
        + ("more than the 1 / (1 − α) updates of the warm-up in which a probe's weight is 1 / updates, "
           "so each event starts from a running average at full hysteresis.\n"
           if all(timeline(d["fps"][h])[0][0] >= 1.0 / (1.0 - h) for h in d["hysteresis"]) else
           "in this variant fewer than the 1 / (1 − α) updates of the warm-up in which a probe's "
           "weight is 1 / updates, and too few frames per event for the theory's figures.\n"))
    states = {}
    for e in events:
        if e["state"] in states:
            continue
        try:
            posed = posed_copy(path, e["t"], runner.work / "posed")
            ref = reference(runner, cache, f"light_{e['state']}", posed, (W, H), d["ref_spp"])[0]
            still = runner.work / f"dyn_still_{e['state']}"
            render(runner, path, still, ["--width", W, "--height", H, "--frames", d["still_frames"],
                                         "--time", e["t"], "--fps", 1000, "--hysteresis",
                                         d["still_hysteresis"], "--blend", "per-update",
                                         "--probe-samples", d["samples"], "--seed", 2],
                   f"dynamic: converged run of state {e['state']}")
            states[e["state"]] = (ref, only_exr(still))
        except StepFailed as err:
            report.append(f"**Dynamic light: state {e['state']}: {err}**\n")
            log(str(err))
            return None
    series = []
    summary = []
    # (hysteresis, blend, budget ms or None): the uniform runs, then the budgeted ones (visibility
    # schedule), where probes get fewer samples or wait, and the two blend rules differ.
    runs = [(h, blend, None, None) for blend in d["blends"] for h in d["hysteresis"]]
    runs += [(b["hysteresis"], blend, b["budget_ms"], b.get("fps")) for b in d.get("budget_runs", [])
             for blend in d["blends"]]
    n_seg = {}
    for h, blend, budget, *run_fps in runs:
        tag = f"h{h:g}_{blend}".replace(".", "p") + (f"_budget{budget:g}" if budget else "")
        name = f"h{h:g}/{blend}" + (f"/budget{budget:g}ms" if budget else "")
        schedule = ["--schedule", "visibility", "--budget-ms", budget] if budget else []
        fps = run_fps[0] or d["fps"][h]
        frames, total = timeline(fps)
        for e, k in zip(events, frames):
            e["frame"] = k
        n_seg[name] = {e["id"]: (events[i + 1]["frame"] if i + 1 < len(events) else total) - e["frame"]
                    for i, e in enumerate(events)}
        out = runner.work / f"dyn_{tag}"
        try:
            t = render(runner, path, out, ["--width", W, "--height", H, "--frames", total, "--every",
                                           "--time", 0, "--fps", fps, "--hysteresis", h,
                                           "--probe-samples", d["samples"], "--blend", blend, *schedule],
                       f"dynamic {name}")
            exrs = sorted(out.glob("frame_*.exr"))
            if len(exrs) != total:
                raise StepFailed(f"dynamic {name}: {len(exrs)} frames written, expected {total}")
            pairs = {}
            for i, e in enumerate(events):
                end = events[i + 1]["frame"] if i + 1 < len(events) else total
                ref, still = states[e["state"]]
                for k in range(e["frame"], end):
                    pairs[f"r{k:05d}"] = (exrs[k], ref)
                    pairs[f"s{k:05d}"] = (exrs[k], still)
            figs = compare_many(runner, pairs, f"dyn_{tag}")
        except StepFailed as err:
            report.append(f"**Dynamic {name}: {err}**\n")
            log(str(err))
            continue
        frame_ms = frame_stats(t)["frame_ms"]
        # The share of the full-rate paths (every active probe, full samples) traced per frame.
        shares = []
        for f in t["frames"][1:]:
            pr = (f.get("scheduler") or {}).get("probes") or {}
            if pr.get("active"):
                shares.append(pr.get("traced", 0) * pr.get("samples_per_probe", 0) / (pr["active"] * d["samples"]))
        path_share = statistics.fmean(shares) if shares else float("nan")
        for i, e in enumerate(events):
            end = events[i + 1]["frame"] if i + 1 < len(events) else total
            ks = range(e["frame"], end)
            rmse = [figs[f"r{k:05d}"]["rmse"] for k in ks]
            lag = [figs[f"s{k:05d}"]["rmse"] for k in ks]
            floor, _, r = fit_decay(rmse)
            lag_floor, _, lag_r = fit_decay(lag)
            for k in ks:
                series.append({"series": name, "hysteresis": h, "blend": blend, "budget_ms": budget or 0,
                           "event": e["id"],
                               "frame": k, "frames_after_event": k - e["frame"], "t": k / fps,
                               "rmse": figs[f"r{k:05d}"]["rmse"], "psnr": figs[f"r{k:05d}"]["psnr"],
                               "ssim": figs[f"r{k:05d}"]["ssim"], "lag_rmse": figs[f"s{k:05d}"]["rmse"]})
            n = len(rmse)
            summary.append({
                "series": name, "hysteresis": h, "blend": blend, "budget_ms": budget or 0, "event": e["id"],
                "fps": fps, "path_share": path_share,
                "event_frame": e["frame"],
                "frame_ms": frame_ms, "first_rmse": rmse[0], "steady_rmse": floor,
                "median_last_third_rmse": statistics.median(rmse[n - max(1, n // 3):]),
                "decay_r": r, "frames_to_recover": recovery(rmse, floor),
                "transient_frames": transient_frames(rmse, floor),
                "first_lag_rmse": lag[0], "steady_lag_rmse": lag_floor, "lag_decay_r": lag_r,
                "lag_frames_to_recover": recovery(lag, lag_floor),
                "lag_transient_frames": transient_frames(lag, lag_floor),
                "theory_frames": theory_frames(h),
                "lag_recover_theory": theory_recover(h, lag[0], lag_floor), "theory_frames_measured_r": theory_frames(lag_r)
                if 0.0 < lag_r < 1.0 else None})
    if not summary:
        return None
    # Where the sample-count-aware rule made the same errors as the per-update rule, say so: under
    # --schedule uniform every probe gets the full samples every frame, where the rules coincide.
    same = []
    for h in d["hysteresis"]:
        a = [x["rmse"] for x in series if x["hysteresis"] == h and x["blend"] == "per-update" and not x["budget_ms"]]
        b = [x["rmse"] for x in series if x["hysteresis"] == h and x["blend"] == "per-sample" and not x["budget_ms"]]
        if a and b and len(a) == len(b) and max(abs(u - v) for u, v in zip(a, b)) <= 1e-4 * max(a):
            same.append(f"{h:g}")
    csv_path = results_dir / "dynamic.csv"
    write_csv(csv_path, ["series", "hysteresis", "blend", "budget_ms", "event", "frame", "frames_after_event", "t",
                         "rmse", "psnr", "ssim", "lag_rmse"], series)
    keys = list(summary[0].keys())
    write_csv(results_dir / "dynamic_summary.csv", keys, summary)
    report.append("| event | hysteresis | blend | ms/frame | RMSE at event | RMSE steady | frames to recover "
                  "(10 %) | lag RMSE at event | lag RMSE steady | lag: frames to recover (10 %) | theory | lag: "
                  "transient to 10 % | theory log(0.1)/log(α) | lag: decay r |")
    report.append("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for s in summary:
        report.append(
            f"| {s['event']} | {s['hysteresis']:g} | {s['blend']}"
            + (f", budget {s['budget_ms']:g} ms ({100 * s['path_share']:.0f} % of the paths)" if s["budget_ms"] else "")
            + f" | {fmt(s['frame_ms'])} | "
            f"{fmt(s['first_rmse'], 4)} | {fmt(s['steady_rmse'], 4)} | "
            f"{frames_text(s['frames_to_recover'], s['fps'], n_seg[s['series']][s['event']])} | "
            f"{fmt(s['first_lag_rmse'], 4)} | {fmt(s['steady_lag_rmse'], 4)} | "
            f"{frames_text(s['lag_frames_to_recover'], s['fps'], n_seg[s['series']][s['event']])} | "
            f"{fmt(s['lag_recover_theory'])} | "
            f"{frames_text(s['lag_transient_frames'], s['fps'], n_seg[s['series']][s['event']])} | "
            f"{theory_frames(s['hysteresis']):.1f} | {fmt(s['lag_decay_r'], 4)} |")
    # The measurement against the theory, per hysteresis: the lag transient's frames to 10 % and
    # the fitted decay, over every event and blend.
    lines = []
    for h in d["hysteresis"]:
        rows = [s for s in summary if s["hysteresis"] == h and not s["budget_ms"]]
        got = [s["lag_transient_frames"] for s in rows if s["lag_transient_frames"] is not None]
        rs = [s["lag_decay_r"] for s in rows if math.isfinite(s["lag_decay_r"])]
        if not got:
            lines.append(f"α = {h:g}: the lag transient did not fall to 10 % within the segment")
            continue
        lines.append(f"α = {h:g}: transient to 10 % in {min(got)}–{max(got)} frames against "
                     f"{theory_frames(h):.1f} in theory ({statistics.fmean(got) / theory_frames(h):.2f}× on "
                     f"average); fitted decay r = {min(rs):.4f}–{max(rs):.4f} per frame against α = {h:g}")
    report.append("\n**Against the theory.** " + "; ".join(lines) + ". *Frames to recover* (back "
                  "within 10 % of the steady RMSE) is a different count: with a transient T at the event "
                  "over a floor F it is log(sqrt(0.21)·F / T) / log(α) (the *theory* column beside it, "
                  "from the measured F and T), longer than the transient's 10 % where the jump is large "
                  "against the noise, as for the lag (the floor is only the noise of two estimates), "
                  "and shorter on the reference RMSE, whose floor is the renderer's fixed bias.")
    budgeted = [s for s in summary if s["budget_ms"]]
    if budgeted:
        parts = []
        for b in d.get("budget_runs", []):
            for blend in d["blends"]:
                rows = [s for s in budgeted if s["hysteresis"] == b["hysteresis"] and s["blend"] == blend
                        and s["budget_ms"] == b["budget_ms"]]
                got = [s["lag_transient_frames"] for s in rows if s["lag_transient_frames"] is not None]
                if not rows:
                    continue
                share = rows[0]["path_share"]
                parts.append(
                    f"{blend} at α = {b['hysteresis']:g}, budget {b['budget_ms']:g} ms, {rows[0]['fps']:g} fps: "
                    f"{100 * share:.0f} % of the full-rate paths traced per frame, transient to 10 % in "
                    + (f"{min(got)}–{max(got)} frames" if got else "more frames than the segment holds")
                    + (f" (if every probe kept its whole history in samples, as the per-sample rule "
                       f"aims to, {theory_frames(b['hysteresis']) / share:.0f})" if share > 0 else ""))
        report.append("\n**Under a budget** (`--schedule visibility`: probes ranked by the views, "
                      "fewer samples or skipped to fit the frame's time; the per-update rule then uses "
                      "the sample-equivalent hysteresis, the per-sample rule also shrinks the history "
                      "of a probe that waited): " + "; ".join(parts) + ". The budget is time, so these "
                      "runs depend on the machine's load; the uniform runs above do not.")
    report.append("\n*blend*: `--blend per-update` is the published running average (weight "
                  "max(1/updates, 1 − α) per update); `--blend per-sample` is the sample-count-aware rule "
                  "(weight n / (n + min(history, N_α)), N_α = S·α/(1 − α) samples)."
                  + (f" At hysteresis {', '.join(same)} the two rules gave the same errors in every frame "
                     "(to 1e-4 relative): under `--schedule uniform` every probe receives the full samples "
                     "every frame, where the rules coincide; they differ only when the scheduler gives "
                     "probes fewer samples or skips them." if same else "") + "\n")
    report.append("CSV: [results/dynamic.csv](results/dynamic.csv), "
                  "[results/dynamic_summary.csv](results/dynamic_summary.csv).\n")
    if plot(runner, "dynamic.gp", csv_path, results_dir / "dynamic.png",
            f"cornell_light, {W}x{H}: lag RMSE after each event",
            {"slist": " ".join(dict.fromkeys(s["series"] for s in summary)),
             "elist": " ".join(e["id"] for e in events)}):
        report.append("![lag after the light jumps, switches off and on](results/dynamic.png)\n")
    return summary
