"""Section 2: error against run time (probe settings swept, path tracing and direct light as
baselines in the same run)."""

import json
import shutil
import time
from pathlib import Path

from common import (SCENE_NAMES, StepFailed, compare_many, finite, fmt, frame_stats, log, median, only_exr,
                    plot, reference, render, write_csv)
from error_cameras import cameras_table
from settings import DEFAULTS, DEFAULTS_QUICK


def grid_counts(runner, path):
    out = runner.run([runner.exe("ddish"), "info", path, "--json"], f"info {Path(path).name}")
    doc = json.loads(out)
    counts = (doc.get("probe_grid") or {}).get("counts")
    if not counts:
        raise StepFailed(f"ddish info {path} gives no probe grid counts")
    return counts


def pareto(rows):
    pts = [r for r in rows if finite(r.get("ms_per_frame")) and finite(r.get("psnr"))]
    for r in rows:
        r["pareto"] = 0
    for r in pts:
        dominated = any(o is not r and o["ms_per_frame"] <= r["ms_per_frame"] and o["psnr"] >= r["psnr"]
                        and (o["ms_per_frame"] < r["ms_per_frame"] or o["psnr"] > r["psnr"]) for o in pts)
        r["pareto"] = 0 if dominated else 1


def section_error(runner, cfg, scenes, cache, results_dir, report):
    defaults = DEFAULTS if cfg["mode"] == "full" else DEFAULTS_QUICK
    frames = cfg["error_frames"]
    report.append("## 2. Error against run time\n")
    report.append(
        f"`ddish render` (one view, the scene's default camera, linear EXR of the last of {frames} frames) "
        "against a high-spp `ddish reference` of the same camera (16 bounces); PSNR and SSIM on display "
        "values, RMSE on linear values (`ddish compare --json`). *ms/frame* is the median frame time "
        "(pose + probe update + upload + raster, without file output) over the steady frames. "
        f"Sweeps change one setting at a time from the paper's settings: L{defaults['sh_order']} SH, "
        f"{defaults['probe_samples']} paths per probe per update, the scene's sidecar grid, hysteresis "
        f"{defaults['hysteresis']}, {defaults['bounces']} bounces per probe path (ddish's default: one fewer than the "
        "reference's 16, since the rasterized surface is the first scattering; *bounces_4* shows what shorter "
        "paths cost in accuracy). *grid half* halves the sidecar's probe counts on every axis (twice the spacing); *_fit* "
        "adds `--probe-placement fit` (the grid moved by a quarter cell where the surfaces the scene's cameras see "
        "then see more of their probes). "
        "Baselines in the same run: path tracing (`ddish reference --spp k`, seed 7 so its noise is "
        "independent of the reference's; its time is the reference renderer's own render seconds) at "
        "k spp and at equal time (`--time-limit` = the paper-settings frame time), and direct light only "
        "(`ddish render --no-indirect`).\n")
    left = [SCENE_NAMES[k] for k in ("cornell", "breakfast", "sponza") if k not in cfg["error_scenes"]]
    if left:
        report.append(f"Left out of this section to keep the {cfg['mode']} run within its time: "
                      f"{', '.join(left)}.\n")
    summary = {}
    camera_rows_all = []
    for key, sc in cfg["error_scenes"].items():
        path = scenes[key]
        if not path.is_file():
            report.append(f"**{SCENE_NAMES[key]}: skipped — {path} is absent.**\n")
            continue
        W, H = sc["size"]
        try:
            ref_exr, ref_meta = reference(runner, cache, key, path, (W, H), sc["ref_spp"])
            counts = grid_counts(runner, path)
        except StepFailed as e:
            report.append(f"**{SCENE_NAMES[key]}: reference failed: {e}**\n")
            log(str(e))
            continue
        half = ",".join(str(max(1, (c + 1) // 2)) for c in counts)
        configs = []
        def add(param, value, settings):
            name = f"{param}_{value}".replace(".", "p")
            if all(c["settings"] != settings for c in configs):
                configs.append({"name": name, "param": param, "value": value, "settings": settings})
        add("paper", "default", dict(defaults))
        for p, values in cfg["sweep"].items():
            for v in values:
                add(p, v, dict(defaults, **{p: v}))
        rows = []
        pairs = {}
        for c in configs:
            s = c["settings"]
            args = ["--width", W, "--height", H, "--frames", frames, "--probe-samples",
                    s["probe_samples"], "--sh-order", s["sh_order"], "--hysteresis", s["hysteresis"],
                    "--bounces", s["bounces"]]
            if s["grid"].startswith("half"):
                args += ["--grid", half]
            if s["grid"].endswith("_fit"):
                args += ["--probe-placement", "fit"]
            try:
                out = runner.work / f"err_{key}_{c['name']}"
                t = render(runner, path, out, args, f"error {key} {c['name']}")
                st = frame_stats(t)
                pairs[c["name"]] = (only_exr(out), ref_exr)
                rows.append({"scene": key, "method": "probes", "config": c["name"], "param": c["param"],
                             "value": c["value"], "samples": s["probe_samples"],
                             "grid": (",".join(map(str, counts)) if s["grid"].startswith("sidecar") else half)
                                     + (" fit" if s["grid"].endswith("_fit") else ""),
                             "sh_order": s["sh_order"], "hysteresis": s["hysteresis"],
                             "bounces": s["bounces"],
                             "ms_per_frame": st["frame_ms"], "probe_ms": st["probe_update_ms"],
                             "raster_ms": st["raster_ms"], "spp": None})
            except StepFailed as e:
                report.append(f"**{SCENE_NAMES[key]} {c['name']}: failed: {e}**\n")
                log(str(e))
        # Direct light only.
        try:
            out = runner.work / f"err_{key}_direct"
            t = render(runner, path, out, ["--width", W, "--height", H, "--frames", frames,
                                           "--no-indirect"], f"error {key} direct only")
            st = frame_stats(t)
            pairs["direct"] = (only_exr(out), ref_exr)
            rows.append({"scene": key, "method": "direct only", "config": "direct", "param": "no-indirect",
                         "value": "", "ms_per_frame": st["frame_ms"], "probe_ms": st["probe_update_ms"],
                         "raster_ms": st["raster_ms"], "spp": None})
        except StepFailed as e:
            report.append(f"**{SCENE_NAMES[key]} direct only: failed: {e}**\n")
        # Path tracing at k spp and at equal time.
        paper = next((r for r in rows if r["config"] == "paper_default"), None)
        pt_runs = [(f"pt_{k}spp", ["--spp", k], f"{k} spp") for k in cfg["pt_spp"]]
        if paper and finite(paper["ms_per_frame"]):
            limit = paper["ms_per_frame"] / 1000.0
            pt_runs.append(("pt_equal_time", ["--spp", 1 << 20, "--time-limit", f"{limit:.6f}"],
                            f"equal time ({paper['ms_per_frame']:.1f} ms)"))
        for name, args, label in pt_runs:
            out = runner.work / f"err_{key}_{name}"
            shutil.rmtree(out, ignore_errors=True)
            try:
                runner.run([runner.exe("ddish"), "reference", path, "--width", W, "--height", H,
                            "--seed", 7, "--out", out, *args], f"error {key} path tracing {label}")
                meta = json.loads((out / "reference.json").read_text())
                pairs[name] = (out / "reference.exr", ref_exr)
                rows.append({"scene": key, "method": "path tracing", "config": name, "param": "spp",
                             "value": label, "ms_per_frame": 1000.0 * meta["seconds"], "spp": meta["spp"]})
            except StepFailed as e:
                report.append(f"**{SCENE_NAMES[key]} path tracing {label}: failed: {e}**\n")
        try:
            figs = compare_many(runner, pairs, f"error_{key}")
        except StepFailed as e:
            report.append(f"**{SCENE_NAMES[key]}: compare failed: {e}**\n")
            continue
        for r in rows:
            f = figs.get(r["config"])
            if f:
                r.update(psnr=f["psnr"], ssim=f["ssim"], rmse=f["rmse"], relmse=f["relmse"])
        pareto(rows)
        header = ["scene", "method", "config", "param", "value", "samples", "grid", "sh_order",
                  "hysteresis", "bounces", "spp", "ms_per_frame", "probe_ms", "raster_ms", "psnr", "ssim", "rmse",
                  "relmse", "pareto"]
        csv_path = results_dir / f"error_{key}.csv"
        write_csv(csv_path, header, rows)
        report.append(f"### {SCENE_NAMES[key]} ({W}×{H}, reference {ref_meta.get('spp')} spp, "
                      f"{fmt(ref_meta.get('seconds'), 0)} s)\n")
        report.append("| method | setting | ms/frame | probe update ms | PSNR dB | SSIM | RMSE | Pareto |")
        report.append("| --- | --- | ---: | ---: | ---: | ---: | ---: | :---: |")
        for r in rows:
            setting = r["config"] if r["method"] != "path tracing" else f"{r['value']} → {r['spp']} spp"
            if r["config"] == "paper_default":
                setting = (f"paper: L{r['sh_order']}, {r['samples']} paths, grid {r['grid']}, "
                           f"h {r['hysteresis']}, {r['bounces']} bounces")
            report.append(f"| {r['method']} | {setting} | {fmt(r['ms_per_frame'])} | {fmt(r.get('probe_ms'))} | "
                          f"{fmt(r.get('psnr'), 2)} | {fmt(r.get('ssim'), 3)} | {fmt(r.get('rmse'), 4)} | "
                          f"{'●' if r.get('pareto') else ''} |")
        report.append(f"\nCSV: [results/error_{key}.csv](results/error_{key}.csv).\n")
        front = sorted((r for r in rows if r.get("pareto")), key=lambda r: r["ms_per_frame"])
        front_path = results_dir / f"pareto_front_{key}.csv"
        write_csv(front_path, header, front)
        if plot(runner, "pareto.gp", csv_path, results_dir / f"pareto_{key}.png",
                f"{SCENE_NAMES[key]}, {W}x{H}", {"frontfile": front_path}):
            report.append(f"![error against time, {SCENE_NAMES[key]}](results/pareto_{key}.png)\n")
        eq = next((r for r in rows if r["config"] == "pt_equal_time"), None)
        direct = next((r for r in rows if r["config"] == "direct"), None)
        if direct and finite(direct.get("probe_ms")) and direct["probe_ms"] > 0.1:
            report.append(f"Note: the `--no-indirect` run still spent {fmt(direct['probe_ms'])} ms per frame in "
                          "the probe update (measured in its timings), so its ms/frame is not the cost of "
                          "direct light alone; its raster time was "
                          f"{fmt(direct.get('raster_ms'))} ms.\n")
        if eq and paper and finite(eq["ms_per_frame"]) and eq["ms_per_frame"] > 1.5 * paper["ms_per_frame"]:
            report.append(f"Note: path tracing's first progressive pass ({eq['spp']} spp) took "
                          f"{fmt(eq['ms_per_frame'])} ms, more than the {fmt(paper['ms_per_frame'])} ms "
                          "frame time it was given, so the equal-time baseline had more time than the "
                          "probes.\n")
        summary[key] = {"paper": paper, "equal_time": eq,
                        "direct": next((r for r in rows if r["config"] == "direct"), None)}
        if cfg.get("error_all_cameras"):
            camera_rows_all += cameras_table(runner, cache, key, path, (W, H), sc["ref_spp"], frames,
                                             defaults, report, sc.get("camera_variant"))
    if camera_rows_all:
        header = list(dict.fromkeys(k for r in camera_rows_all for k in r))  # variant columns too
        write_csv(results_dir / "error_cameras.csv", header, camera_rows_all)
        report.append("Every-camera CSV: [results/error_cameras.csv](results/error_cameras.csv).\n")
    return summary
