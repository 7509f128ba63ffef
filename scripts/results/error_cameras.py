"""Section 2, every camera: the paper settings, path tracing at equal time and direct light only
from each of a scene's cameras, each against its own high-spp reference (the full sweep runs
from the default camera only; this checks that its figures are not one lucky viewpoint)."""

import json
import shutil

from common import StepFailed, compare_many, finite, fmt, frame_stats, log, only_exr, reference, render


def scene_cameras(runner, path):
    """The camera names `ddish info --json` lists, the default first."""
    doc = json.loads(runner.run([runner.exe("ddish"), "info", path, "--json"], f"cameras of {path}"))
    names = [c["name"] for c in doc.get("cameras") or []]
    default = doc.get("default_camera")
    if default in names:
        names.remove(default)
        names.insert(0, default)
    return names


def camera_rows(runner, cache, key, path, size, ref_spp, frames, defaults, camera, variant=None):
    """One camera's paper-settings render, direct-only render and equal-time path tracing, with
    their error against the camera's reference: a row dict (figures None where a step failed).
    variant: {"label", "why", "args"}, the scene's probe settings that cost no more time than the
    paper's, rendered from the same camera (its figures go into the row as variant_*)."""
    W, H = size
    ref_exr, _ = reference(runner, cache, f"{key}_{camera}", path, size, ref_spp, ("--camera", camera))
    view = ["--width", W, "--height", H, "--frames", frames, "--camera", camera]
    tag = f"{key}_cam_{camera}"
    paper = render(runner, path, runner.work / f"{tag}_paper",
                   [*view, "--probe-samples", defaults["probe_samples"], "--sh-order", defaults["sh_order"],
                    "--hysteresis", defaults["hysteresis"], "--bounces", defaults["bounces"]],
                   f"error {key} camera {camera} paper")
    direct = render(runner, path, runner.work / f"{tag}_direct", [*view, "--no-indirect"],
                    f"error {key} camera {camera} direct only")
    ms = frame_stats(paper)["frame_ms"]
    pairs = {}
    if variant:
        var = render(runner, path, runner.work / f"{tag}_variant",
                     [*view, "--sh-order", defaults["sh_order"], "--hysteresis", defaults["hysteresis"],
                      "--bounces", defaults["bounces"], *variant["args"]],
                     f"error {key} camera {camera} {variant['label']}")
        var_stats = frame_stats(var)
        pairs["variant"] = (only_exr(runner.work / f"{tag}_variant"), ref_exr)
    pt = runner.work / f"{tag}_pt"
    shutil.rmtree(pt, ignore_errors=True)
    runner.run([runner.exe("ddish"), "reference", path, "--width", W, "--height", H, "--camera", camera,
                "--seed", 7, "--out", pt, "--spp", 1 << 20, "--time-limit", f"{ms / 1000.0:.6f}"],
               f"error {key} camera {camera} path tracing equal time")
    pt_meta = json.loads((pt / "reference.json").read_text())
    figs = compare_many(runner, {"paper": (only_exr(runner.work / f"{tag}_paper"), ref_exr),
                                 "direct": (only_exr(runner.work / f"{tag}_direct"), ref_exr),
                                 "pt": (pt / "reference.exr", ref_exr), **pairs}, tag)
    row = {"scene": key, "camera": camera, "ms_per_frame": ms,
           "psnr": figs["paper"]["psnr"], "ssim": figs["paper"]["ssim"], "rmse": figs["paper"]["rmse"],
           "pt_spp": pt_meta["spp"], "pt_ms": 1000.0 * pt_meta["seconds"],
           "pt_psnr": figs["pt"]["psnr"], "pt_ssim": figs["pt"]["ssim"],
           "direct_psnr": figs["direct"]["psnr"]}
    if variant:
        row.update(variant_ms_per_frame=var_stats["frame_ms"], variant_probe_ms=var_stats["probe_update_ms"],
                   paper_probe_ms=frame_stats(paper)["probe_update_ms"], variant_psnr=figs["variant"]["psnr"],
                   variant_ssim=figs["variant"]["ssim"])
    return row


def cameras_table(runner, cache, key, path, size, ref_spp, frames, defaults, report, variant=None):
    """Appends the every-camera table of a scene with more than one camera (and, with a variant,
    the table of that variant beside the paper settings); returns its rows."""
    try:
        cameras = scene_cameras(runner, path)
    except StepFailed as e:
        report.append(f"**cameras of {key}: failed: {e}**\n")
        return []
    if len(cameras) < 2:
        return []
    rows = []
    for camera in cameras:
        try:
            rows.append(camera_rows(runner, cache, key, path, size, ref_spp, frames, defaults, camera,
                                    variant))
        except StepFailed as e:
            report.append(f"**camera {camera}: failed: {e}**\n")
            log(str(e))
    report.append(f"Every camera of the scene ({len(cameras)}; the default first), paper settings, "
                  f"each against its own {ref_spp}-spp reference:\n")
    report.append("| camera | ms/frame | PSNR dB | SSIM | RMSE | path tracing at equal time | PSNR dB | SSIM "
                  "| direct only PSNR dB |")
    report.append("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        report.append(f"| {r['camera']} | {fmt(r['ms_per_frame'])} | {fmt(r['psnr'], 2)} | {fmt(r['ssim'], 3)} "
                      f"| {fmt(r['rmse'], 4)} | {r['pt_spp']} spp in {fmt(r['pt_ms'])} ms | "
                      f"{fmt(r['pt_psnr'], 2)} | {fmt(r['pt_ssim'], 3)} | {fmt(r['direct_psnr'], 2)} |")
    report.append("")
    if rows and all(finite(r["psnr"]) and finite(r["pt_psnr"]) for r in rows):
        wins = sum(1 for r in rows if r["psnr"] > r["pt_psnr"])
        report.append(f"The probes beat path tracing at equal time from {wins} of {len(rows)} cameras.\n")
    if variant and rows:
        variant_table(rows, variant, report)
    return rows


def variant_table(rows, variant, report):
    """The variant beside the paper settings, camera by camera. Its frame time is measured in the
    same run; path tracing at equal time is the paper settings' baseline (the variant is meant
    to cost no more, and the table shows both times)."""
    report.append(f"The same cameras with {variant['label']} ({variant['why']}), against the paper settings "
                  "of the table above:\n")
    report.append("| camera | paper ms/frame | probe update ms | variant ms/frame | probe update ms "
                  "| paper PSNR dB | variant PSNR dB | variant SSIM | path tracing at equal time PSNR dB "
                  "| direct only PSNR dB |")
    report.append("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        report.append(f"| {r['camera']} | {fmt(r['ms_per_frame'])} | {fmt(r.get('paper_probe_ms'))} "
                      f"| {fmt(r.get('variant_ms_per_frame'))} | {fmt(r.get('variant_probe_ms'))} "
                      f"| {fmt(r['psnr'], 2)} | {fmt(r.get('variant_psnr'), 2)} | {fmt(r.get('variant_ssim'), 3)} "
                      f"| {fmt(r['pt_psnr'], 2)} | {fmt(r['direct_psnr'], 2)} |")
    report.append("")
    ok = [r for r in rows if all(finite(r.get(k)) for k in ("variant_psnr", "pt_psnr", "direct_psnr"))]
    if len(ok) == len(rows):
        beat = sum(1 for r in ok if r["variant_psnr"] > r["pt_psnr"] and r["variant_psnr"] >= r["direct_psnr"] + 1.0)
        report.append(f"With the variant the probes beat path tracing at equal time and direct light by at least "
                      f"1 dB from {beat} of {len(rows)} cameras.\n")
