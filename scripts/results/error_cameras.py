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


def camera_rows(runner, cache, key, path, size, ref_spp, frames, defaults, camera):
    """One camera's paper-settings render, direct-only render and equal-time path tracing, with
    their error against the camera's reference: a row dict (figures None where a step failed)."""
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
    pt = runner.work / f"{tag}_pt"
    shutil.rmtree(pt, ignore_errors=True)
    runner.run([runner.exe("ddish"), "reference", path, "--width", W, "--height", H, "--camera", camera,
                "--seed", 7, "--out", pt, "--spp", 1 << 20, "--time-limit", f"{ms / 1000.0:.6f}"],
               f"error {key} camera {camera} path tracing equal time")
    pt_meta = json.loads((pt / "reference.json").read_text())
    figs = compare_many(runner, {"paper": (only_exr(runner.work / f"{tag}_paper"), ref_exr),
                                 "direct": (only_exr(runner.work / f"{tag}_direct"), ref_exr),
                                 "pt": (pt / "reference.exr", ref_exr)}, tag)
    return {"scene": key, "camera": camera, "ms_per_frame": ms,
            "psnr": figs["paper"]["psnr"], "ssim": figs["paper"]["ssim"], "rmse": figs["paper"]["rmse"],
            "pt_spp": pt_meta["spp"], "pt_ms": 1000.0 * pt_meta["seconds"],
            "pt_psnr": figs["pt"]["psnr"], "pt_ssim": figs["pt"]["ssim"],
            "direct_psnr": figs["direct"]["psnr"]}


def cameras_table(runner, cache, key, path, size, ref_spp, frames, defaults, report):
    """Appends the every-camera table of a scene with more than one camera; returns its rows."""
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
            rows.append(camera_rows(runner, cache, key, path, size, ref_spp, frames, defaults, camera))
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
    return rows
