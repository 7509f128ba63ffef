#!/usr/bin/env python3
"""Measures and writes the results report (docs/RESULTS.md, docs/results/*.csv, *.png).

Run through scripts/results.sh (see there for the options and environment). Everything in the
report comes from the built binaries run here: ddish render (--timings), ddish reference,
ddish compare --json, bench/trace_floor and bench/raster_views. A step that fails is reported as
failed in the report; nothing is filled in. Python 3 standard library only.
"""

import argparse
import csv
import datetime
import hashlib
import json
import math
import os
import platform
import re
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
START = time.monotonic()


def log(message):
    print(f"[results {time.monotonic() - START:7.1f} s] {message}", file=sys.stderr, flush=True)


class StepFailed(Exception):
    pass


# ---------------------------------------------------------------------------------------------
# Settings: the full run (about 25 minutes on the 2-core development machine) and --quick.

FULL = {
    "mode": "full",
    "scaling_scenes": ["sponza", "breakfast"],
    "scaling_views": [1, 2, 4, 8, 16, 32, 48],
    "scaling_tile": (210, 280),
    "scaling_msaa": 1,
    "scaling_frames": 3,
    "raster_floor_frames": 2,
    "trace_floor": {"samples": 256, "updates": 3, "repeat": 3},
    "error_scenes": {
        "cornell": {"size": (160, 160), "ref_spp": 1024},
        "breakfast": {"size": (160, 120), "ref_spp": 512},
        "sponza": {"size": (160, 120), "ref_spp": 512},
    },
    "error_frames": 24,
    "sweep": {
        "probe_samples": [16, 64, 256],
        "grid": ["sidecar", "half"],
        "sh_order": [1, 2, 3, 4],
        "hysteresis": [0.9, 0.95, 0.99],
    },
    "pt_spp": [1, 2, 4, 8, 16],
    "dynamic": {
        "size": (96, 96), "ref_spp": 1024, "samples": 64, "hysteresis": [0.9, 0.95, 0.99],
        "start_time": 2.0, "fps": 30.0, "moving_frames": 60, "static_frames": 180,
        "motion_times": [2.5, 3.0, 3.5],
    },
    "schedule": {
        "sponza_camera": "CameraAlcove", "size": (160, 120), "ref_spp": 256, "frames": 16,
        "path_frames": 300, "path_size": (96, 96), "path_ref_spp": 1024,
    },
}

QUICK = {
    "mode": "quick",
    "scaling_scenes": ["cornell"],
    "scaling_views": [1, 4],
    "scaling_tile": (48, 64),
    "scaling_msaa": 1,
    "scaling_frames": 3,
    "raster_floor_frames": 1,
    "trace_floor": {"samples": 16, "updates": 2, "repeat": 1},
    "error_scenes": {"cornell": {"size": (48, 48), "ref_spp": 32}},
    "error_frames": 4,
    "sweep": {
        "probe_samples": [16, 64],
        "grid": ["sidecar", "half"],
        "sh_order": [1, 2],
        "hysteresis": [0.95],
    },
    "pt_spp": [1, 4],
    "dynamic": {
        "size": (32, 32), "ref_spp": 32, "samples": 16, "hysteresis": [0.9],
        "start_time": 3.8, "fps": 30.0, "moving_frames": 6, "static_frames": 12,
        "motion_times": [],
    },
    "schedule": None,
}

# The paper's settings (DDISH-GI): L2 probes, 256 paths per probe per update, the grid of the
# scene's sidecar (../shared/scenes/README.md), hysteresis 0.95 (ddish's default).
DEFAULTS = {"probe_samples": 256, "grid": "sidecar", "sh_order": 2, "hysteresis": 0.95}
DEFAULTS_QUICK = {"probe_samples": 64, "grid": "sidecar", "sh_order": 2, "hysteresis": 0.95}


# ---------------------------------------------------------------------------------------------
# Running the binaries.

class Runner:
    def __init__(self, build, work, commands_file):
        self.build = build
        self.work = work
        self.commands = []
        self.commands_file = commands_file

    def exe(self, name):
        for p in (self.build / name, self.build / "bench" / name):
            if p.is_file() and os.access(p, os.X_OK):
                return p
        return None

    def run(self, args, what, timeout=1800):
        args = [str(a) for a in args]
        shown = " ".join(self.show(a) for a in args)
        self.commands.append(shown)
        t0 = time.monotonic()
        try:
            proc = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                  timeout=timeout, cwd=ROOT)
        except subprocess.TimeoutExpired:
            raise StepFailed(f"{what}: timed out after {timeout} s: {shown}")
        if proc.returncode != 0:
            tail = (proc.stderr or proc.stdout).strip().splitlines()[-3:]
            raise StepFailed(f"{what}: exit {proc.returncode}: {shown}: {' | '.join(tail)}")
        log(f"{what} ({time.monotonic() - t0:.1f} s)")
        return proc.stdout

    def show(self, a):
        for base, name in ((self.work, "$WORK"), (self.build, "$BUILD"), (ROOT, ".")):
            s = str(base)
            if a.startswith(s + "/"):
                return name + a[len(s):]
        return a

    def save_commands(self):
        self.commands_file.write_text("\n".join(self.commands) + "\n")


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def median(values):
    values = [v for v in values if finite(v)]
    return statistics.median(values) if values else float("nan")


def fmt(x, digits=1):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–" if x is None else str(x)
    if isinstance(x, int):
        return str(x)
    return f"{x:.{digits}f}"


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([("" if r.get(h) is None else
                         (f"{r[h]:.6g}" if isinstance(r[h], float) else r[h])) for h in header])


def frame_stats(timings):
    """Median stage times over the steady frames: frame 0 (pipelines, first upload of every probe)
    is left out; the file output (the last frame's, or every frame's with --every) is not part of
    the frame time and is reported on its own."""
    frames = timings["frames"]
    steady = frames[1:] or frames
    def stage(name, fr):
        return median([f["stages_ms"].get(name, 0.0) for f in fr])
    raster_names = ["raster_record", "shadow_gpu", "forward_gpu", "tonemap_gpu", "raster_wait",
                    "readback"]
    raster = median([sum(f["stages_ms"].get(n, 0.0) for n in raster_names) for f in steady])
    frame = median([f["total_ms"] - f["stages_ms"].get("output", 0.0) for f in steady])
    return {
        "probe_update_ms": stage("probe_update", steady),
        "upload_ms": stage("upload", steady),
        "raster_ms": raster,
        "forward_gpu_ms": stage("forward_gpu", steady),
        "frame_ms": frame,
        "output_ms": frames[-1]["stages_ms"].get("output", float("nan")),
        "probe_rays": median([f.get("probe_rays", float("nan")) for f in steady]),
        "probe_updates": median([f.get("probe_updates", float("nan")) for f in steady]),
        "views": frames[-1].get("views", 1),
        "frames_used": len(steady),
    }


# ---------------------------------------------------------------------------------------------
# Scenes and references.

def scene_paths(scenes_dir):
    return {
        "cornell": ROOT / "scenes" / "cornell_box.gltf",
        "animated": ROOT / "scenes" / "cornell_animated.gltf",
        "sponza": scenes_dir / "sponza" / "Sponza.gltf",
        "breakfast": scenes_dir / "breakfast_room" / "BreakfastRoom.gltf",
    }


SCENE_NAMES = {"cornell": "Cornell box", "animated": "animated Cornell box", "sponza": "Sponza",
               "breakfast": "Breakfast room"}


def scene_key_hash(path, extra):
    h = hashlib.sha1()
    for p in sorted(Path(path).parent.glob(Path(path).stem + "*")):
        if p.is_file():
            st = p.stat()
            h.update(f"{p.name}:{st.st_size}:{int(st.st_mtime)}".encode())
    h.update(extra.encode())
    return h.hexdigest()[:10]


def reference(runner, cache, key, path, size, spp, extra_args=()):
    """A high-spp reference, cached by scene files, size, spp and arguments."""
    tag = f"{key}_{size[0]}x{size[1]}_{spp}spp_" + scene_key_hash(path, " ".join(map(str, extra_args)))
    out = cache / f"ref_{tag}"
    exr = out / "reference.exr"
    if exr.is_file() and (out / "reference.json").is_file():
        log(f"reference {tag}: cached")
    else:
        runner.run([runner.exe("ddish"), "reference", path, "--width", size[0], "--height", size[1],
                    "--spp", spp, "--out", out, *extra_args], f"reference {tag}", timeout=3600)
    meta = json.loads((out / "reference.json").read_text())
    return exr, meta


def compare_many(runner, pairs, tag):
    """pairs: {name: (image.exr, reference.exr)} -> {name: {psnr, ssim, rmse, relmse}} with one
    `ddish compare` of two folders of links."""
    base = runner.work / f"cmp_{tag}"
    shutil.rmtree(base, ignore_errors=True)
    (base / "img").mkdir(parents=True)
    (base / "ref").mkdir()
    for name, (img, ref) in pairs.items():
        os.symlink(Path(img).resolve(), base / "img" / f"{name}.exr")
        os.symlink(Path(ref).resolve(), base / "ref" / f"{name}.exr")
    out = runner.run([runner.exe("ddish"), "compare", base / "img", base / "ref", "--json"],
                     f"compare {tag} ({len(pairs)} images)")
    doc = json.loads(out)
    views = doc.get("views")
    if views is None:  # a single pair compares as one image
        views = [dict(doc, name=f"{next(iter(pairs))}.exr")]
    result = {}
    for v in views:
        result[v["name"][:-4] if v["name"].endswith(".exr") else v["name"]] = v
    missing = set(pairs) - set(result)
    if missing:
        raise StepFailed(f"compare {tag}: no figures for {sorted(missing)}")
    return result


def only_exr(folder):
    exrs = sorted(Path(folder).glob("*.exr"))
    if len(exrs) != 1:
        raise StepFailed(f"expected one .exr in {folder}, found {len(exrs)}")
    return exrs[0]


def render(runner, path, out, args, what, timeout=1800):
    tj = Path(str(out) + ".timings.json")
    shutil.rmtree(out, ignore_errors=True)
    if "--schedule" not in [str(a) for a in args]:
        args = [*args, *uniform_args()]
    runner.run([runner.exe("ddish"), "render", path, "--out", out, "--timings", tj, *args], what,
               timeout=timeout)
    return json.loads(tj.read_text())


# ---------------------------------------------------------------------------------------------
# 1. Viewport scaling.

def section_scaling(runner, cfg, scenes, results_dir, report):
    W, H = cfg["scaling_tile"]
    rows_all = []
    report.append("## 1. Viewport scaling\n")
    report.append(
        f"N views of a Looking Glass Portrait light-field rig (`--display looking-glass-portrait "
        f"--views N --width {W} --height {H} --msaa {cfg['scaling_msaa']}`: tile {W}×{H}"
        f"{', the profile tile' if (W, H) == (420, 560) else ', reduced from the profile tile 420×560 so that the full run fits its time on a 2-core lavapipe machine (the tables show what a view costs at this size)'}"
        f"), {cfg['scaling_frames']} frames per run; figures are medians over the steady frames (frame 0, "
        "which builds pipelines and uploads every probe, is left out; *output* is the last frame's "
        "file writing, not part of *frame*). Probe settings are the scene's "
        "defaults (sidecar grid, L2, 256 paths per probe, 4 bounces). *frame* = pose + probe update + "
        "upload + raster, without output.\n")
    report.append(
        "*Naive* is computed, not run: N × (probe update + upload + 1-view raster), i.e. one probe "
        "update per view, with the probe update and upload measured in the same run as the N views "
        "(so that load drifting between runs does not favour either side) and the 1-view raster from "
        "the N = 1 run. *Trivial-shader floor* is "
        "`bench/raster_views` with its trivial-shader rows at the same N and tile size (when it has "
        "them). *Tracing floor* is `bench/trace_floor`: the probe update's own primary rays (rotated "
        "Fibonacci directions from every active probe) traced with plain `rtcIntersect1` closest-hit "
        "queries on one flat Embree scene, no shading, against the full probe update.\n")
    floor_rows = []
    trace_rows = []
    for key in cfg["scaling_scenes"]:
        path = scenes[key]
        if not path.is_file():
            report.append(f"**{SCENE_NAMES[key]}: skipped — {path} is absent.**\n")
            log(f"scaling: {key} skipped, {path} absent")
            continue
        rows = []
        failed = []
        for n in cfg["scaling_views"]:
            try:
                t = render(runner, path, runner.work / f"scale_{key}_{n}",
                           ["--display", "looking-glass-portrait", "--views", n, "--width", W,
                            "--height", H, "--msaa", cfg["scaling_msaa"],
                            "--frames", cfg["scaling_frames"]],
                           f"scaling {key} N={n}")
                s = frame_stats(t)
                if s["views"] != n:
                    raise StepFailed(f"scaling {key}: asked for {n} views, the timings say {s['views']}")
                s.update(scene=key, views=n, tile=f"{W}x{H}", raster_per_view_ms=s["raster_ms"] / n)
                rows.append(s)
            except StepFailed as e:
                failed.append(f"**{SCENE_NAMES[key]}, N = {n}: failed: {e}**\n")
                log(str(e))
            shutil.rmtree(runner.work / f"scale_{key}_{n}", ignore_errors=True)
        if rows and rows[0]["views"] == 1:
            # A probe update per view: N × (probe update + upload + the 1-view raster), the probe
            # update and upload taken from the same run as the N views (the machine's load drifts
            # between runs; the update does not depend on N), the raster from the N = 1 run.
            one = rows[0]
            for r in rows:
                r["naive_ms"] = r["views"] * (r["probe_update_ms"] + r["upload_ms"] + one["raster_ms"])
                r["speedup_vs_naive"] = r["naive_ms"] / r["frame_ms"] if r["frame_ms"] > 0 else float("nan")
        # The trivial-shader floor.
        floor = {}
        rv = runner.exe("raster_views")
        if rv is None:
            floor_note = "missing: bench/raster_views is not built"
        elif b"trivial" not in rv.read_bytes():
            floor_note = "missing: this build's bench/raster_views has no trivial-shader method"
        else:
            try:
                out = runner.run([rv, path, "--views", ",".join(str(r["views"]) for r in rows) or "1",
                                  "--size", f"{W}x{H}", "--frames", cfg["raster_floor_frames"],
                                  "--msaa", cfg["scaling_msaa"]],
                                 f"raster_views {key}", timeout=3600)
                lines = [l for l in out.splitlines() if l and not l.startswith("#")]
                reader = list(csv.DictReader(lines))
                for r in reader:
                    r2 = dict(r, scene=key)
                    floor_rows.append(r2)
                trivial = [r for r in reader if "trivial" in " ".join(str(v) for v in r.values()).lower()]
                for r in trivial:
                    n = int(r["views"])
                    ms = float(r["frame_ms"])
                    floor[n] = min(floor.get(n, ms), ms)
                floor_note = ("trivial-shader rows of bench/raster_views" if trivial else
                              "missing: bench/raster_views printed no trivial-shader rows")
            except (StepFailed, KeyError, ValueError) as e:
                floor_note = f"failed: {e}"
                log(floor_note)
        for r in rows:
            r["trivial_floor_ms"] = floor.get(r["views"])
        # The tracing floor.
        tf = runner.exe("trace_floor")
        trace = None
        if tf is None:
            trace_note = "missing: bench/trace_floor is not built"
        else:
            try:
                o = cfg["trace_floor"]
                out = runner.run([tf, path, "--samples", o["samples"], "--updates", o["updates"],
                                  "--repeat", o["repeat"]], f"trace_floor {key}")
                lines = [l for l in out.splitlines() if l and not l.startswith("#")]
                trace = next(csv.DictReader(lines))
                trace["scene"] = key
                trace_rows.append(trace)
                trace_note = "bench/trace_floor"
            except (StepFailed, StopIteration) as e:
                trace_note = f"failed: {e}"
                log(trace_note)
        rows_all += rows
        header = ["scene", "views", "tile", "probe_update_ms", "upload_ms", "raster_ms",
                  "raster_per_view_ms", "forward_gpu_ms", "frame_ms", "output_ms", "naive_ms",
                  "speedup_vs_naive", "trivial_floor_ms", "probe_rays", "probe_updates", "frames_used"]
        csv_path = results_dir / f"scaling_{key}.csv"
        write_csv(csv_path, header, rows)
        report.append(f"### {SCENE_NAMES[key]}\n")
        report += failed
        if rows:
            report.append("| N | probe update | upload | raster | raster / view | frame | output | naive (N updates) | speed-up | trivial-shader floor |")
            report.append("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
            for r in rows:
                report.append(
                    f"| {r['views']} | {fmt(r['probe_update_ms'])} | {fmt(r['upload_ms'], 2)} | "
                    f"{fmt(r['raster_ms'])} | {fmt(r['raster_per_view_ms'])} | {fmt(r['frame_ms'])} | "
                    f"{fmt(r['output_ms'])} | {fmt(r.get('naive_ms'))} | {fmt(r.get('speedup_vs_naive'), 2)}× | "
                    f"{fmt(r.get('trivial_floor_ms'))} |")
            report.append(f"\nAll times in ms per frame. Trivial-shader floor: {floor_note}. "
                          f"CSV: [results/scaling_{key}.csv](results/scaling_{key}.csv).\n")
            if plot(runner, "scaling.gp", csv_path, results_dir / f"scaling_{key}.png",
                    f"{SCENE_NAMES[key]}, {W}x{H} per view"):
                report.append(f"![viewport scaling, {SCENE_NAMES[key]}](results/scaling_{key}.png)\n")
        if trace:
            report.append(
                f"Tracing floor ({trace_note}): grid {trace['grid']}, {trace['active']} active of "
                f"{trace['probes']} probes × {trace['samples']} paths = {trace['floor_rays']} primary rays "
                f"per update, {trace['threads']} threads. Plain closest hit: {fmt(float(trace['floor_ms']))} ms "
                f"({fmt(float(trace['floor_mrays_s']), 2)} Mrays/s, {fmt(100 * float(trace['floor_hit_fraction']))} % hit). "
                f"Full probe update of the same probes: {fmt(float(trace['update_ms']))} ms, "
                f"{trace['update_rays']} rays ({fmt(float(trace['update_rays']) / max(1.0, float(trace['update_paths'])), 2)} per path: "
                f"bounces and shadow rays), {fmt(float(trace['update_mrays_s']), 2)} Mrays/s; the update takes "
                f"{fmt(float(trace['update_over_floor']), 1)}× the floor's time.\n")
        else:
            report.append(f"Tracing floor: {trace_note}.\n")
    if floor_rows:
        keys = list(floor_rows[0].keys())
        write_csv(results_dir / "raster_views.csv", keys, floor_rows)
        report.append("Raw `bench/raster_views` output (every method, culling on and off): "
                      "[results/raster_views.csv](results/raster_views.csv).\n")
    if trace_rows:
        write_csv(results_dir / "trace_floor.csv", list(trace_rows[0].keys()), trace_rows)
        report.append("Tracing floor per scene: [results/trace_floor.csv](results/trace_floor.csv).\n")
    return rows_all, trace_rows


# ---------------------------------------------------------------------------------------------
# Plots.

def plot(runner, script, data, png, title, extra=None):
    gp = ROOT / "bench" / "plots" / script
    if shutil.which("gnuplot") is None:
        log("gnuplot is not installed: no plots")
        return False
    defs = f"datafile='{data}'; outfile='{png}'; plottitle='{title}'"
    for k, v in (extra or {}).items():
        defs += f"; {k}='{v}'"
    try:
        runner.run(["gnuplot", "-e", defs, gp], f"plot {Path(png).name}")
        return Path(png).is_file()
    except StepFailed as e:
        log(str(e))
        return False


# ---------------------------------------------------------------------------------------------
# 2. Error against run time.

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
        f"{defaults['hysteresis']}. *grid half* halves the sidecar's probe counts on every axis (twice the spacing). "
        "Baselines in the same run: path tracing (`ddish reference --spp k`, seed 7 so its noise is "
        "independent of the reference's; its time is the reference renderer's own render seconds) at "
        "k spp and at equal time (`--time-limit` = the paper-settings frame time), and direct light only "
        "(`ddish render --no-indirect`).\n")
    left = [SCENE_NAMES[k] for k in ("cornell", "breakfast", "sponza") if k not in cfg["error_scenes"]]
    if left:
        report.append(f"Left out of this section to keep the {cfg['mode']} run within its time: "
                      f"{', '.join(left)}.\n")
    summary = {}
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
                    s["probe_samples"], "--sh-order", s["sh_order"], "--hysteresis", s["hysteresis"]]
            if s["grid"] == "half":
                args += ["--grid", half]
            try:
                out = runner.work / f"err_{key}_{c['name']}"
                t = render(runner, path, out, args, f"error {key} {c['name']}")
                st = frame_stats(t)
                pairs[c["name"]] = (only_exr(out), ref_exr)
                rows.append({"scene": key, "method": "probes", "config": c["name"], "param": c["param"],
                             "value": c["value"], "samples": s["probe_samples"],
                             "grid": ",".join(map(str, counts)) if s["grid"] == "sidecar" else half,
                             "sh_order": s["sh_order"], "hysteresis": s["hysteresis"],
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
                  "hysteresis", "spp", "ms_per_frame", "probe_ms", "raster_ms", "psnr", "ssim", "rmse",
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
                           f"h {r['hysteresis']}")
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
    return summary


# ---------------------------------------------------------------------------------------------
# Dynamic light: the animated Cornell box.

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
    if "--blend" in RENDER_HELP:
        runs += [(d["hysteresis"][len(d["hysteresis"]) // 2], "per-sample")]
    for h, blend in runs:
        tag = f"h{h:g}_{blend}".replace(".", "p")
        name = f"h{h:g}/{blend}"
        out = runner.work / f"dyn_{tag}"
        extra = ["--blend", blend] if "--blend" in RENDER_HELP else []
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
    report.append("\nSample-count-aware blend: not measured — `ddish render` has no option to select it.\n"
                  if "--blend" not in RENDER_HELP else
                  "\n*blend*: `--blend per-update` is the published running average (weight 1 − hysteresis "
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


# ---------------------------------------------------------------------------------------------
# Issue 7: the scheduler's two measurements.

RENDER_HELP = ""


def uniform_args():
    """The published behaviour, every active probe every frame, no budget: how the scaling,
    error and dynamic sections run, where the build has a scheduler (issue 7) at all."""
    args = []
    if "--schedule" in RENDER_HELP:
        args += ["--schedule", "uniform"]
    if "--budget-ms" in RENDER_HELP:
        args += ["--budget-ms", "0"]
    return args


def section_schedule(runner, cfg, scenes, cache, results_dir, report):
    report.append("## 4. Probe scheduling (issue 7)\n")
    sch = cfg["schedule"]
    if "--schedule" not in RENDER_HELP or "--budget-ms" not in RENDER_HELP:
        report.append("Not measured: scheduler not wired (`ddish render --help` has no `--schedule` / "
                      "`--budget-ms`).\n")
        return None
    if sch is None:
        report.append("Not measured in --quick.\n")
        return None
    result = {}
    # (a) A camera that sees part of Sponza: error against rays spent, scheduled and uniform.
    path = scenes["sponza"]
    W, H = sch["size"]
    cam = sch["sponza_camera"]
    F = sch["frames"]
    if not path.is_file():
        report.append(f"**Sponza: skipped — {path} is absent.**\n")
    else:
        try:
            ref, meta = reference(runner, cache, f"sponza_{cam}", path, (W, H), sch["ref_spp"],
                                  ["--camera", cam])
            common = ["--camera", cam, "--width", W, "--height", H, "--every"]
            curves, timings = {}, {}
            timings["uniform"] = render(runner, path, runner.work / "sched_uniform",
                                        [*common, "--frames", F, "--schedule", "uniform", "--budget-ms", 0],
                                        "schedule uniform")
            u = frame_stats(timings["uniform"])
            # The scheduled run's budget: the uniform frame with a quarter of its probe update,
            # from the uniform run just measured; it gets 3x the frames to show where it gets to.
            budget = u["frame_ms"] - 0.75 * u["probe_update_ms"]
            timings["visibility"] = render(runner, path, runner.work / "sched_visibility",
                                           [*common, "--frames", 3 * F, "--schedule", "visibility",
                                            "--budget-ms", f"{budget:.1f}"],
                                           f"schedule visibility, budget {budget:.0f} ms")
            # The probes' own convergence: an independent uniform run (--seed 2, hysteresis 0.99,
            # twice the frames) as the converged image of this renderer, so the renderer's fixed
            # bias against the path tracer (the same for both schedules) drops out.
            conv_dir = runner.work / "sched_converged"
            render(runner, path, conv_dir, ["--camera", cam, "--width", W, "--height", H, "--frames", 2 * F,
                                            "--schedule", "uniform", "--budget-ms", 0, "--seed", 2,
                                            "--hysteresis", 0.99], "schedule: converged uniform run")
            conv = only_exr(conv_dir)
            for mode, t in timings.items():
                out = runner.work / f"sched_{mode}"
                exrs = sorted(out.glob("frame_*.exr"))
                if len(exrs) != len(t["frames"]):
                    raise StepFailed(f"schedule {mode}: {len(exrs)} images for {len(t['frames'])} frames")
                pairs = {f"f{k:04d}": (e, ref) for k, e in enumerate(exrs)}
                pairs.update({f"c{k:04d}": (e, conv) for k, e in enumerate(exrs)})
                figs = compare_many(runner, pairs, f"sched_{mode}")
                rays = 0
                pts = []
                for k, f in enumerate(t["frames"]):
                    rays += f.get("probe_rays", 0)
                    fig = figs[f"f{k:04d}"]
                    pts.append({"mode": mode, "frame": k, "rays": rays, "rmse": fig["rmse"],
                                "rmse_vs_converged": figs[f"c{k:04d}"]["rmse"],
                                "psnr": fig["psnr"], "probes_traced": f.get("probes_traced"),
                                "frame_ms": f["total_ms"] - f["stages_ms"].get("output", 0.0)})
                curves[mode] = pts
            write_csv(results_dir / "schedule_rays.csv",
                      ["mode", "frame", "rays", "probes_traced", "rmse", "psnr", "rmse_vs_converged", "frame_ms"],
                      curves["uniform"] + curves["visibility"])
            # Error against rays on the convergence measure, each curve smoothed over 3 frames; the
            # target is the uniform run's smoothed error at its last frame.
            for pts in curves.values():
                for i, p in enumerate(pts):
                    p["smooth"] = statistics.fmean(q["rmse_vs_converged"] for q in pts[max(0, i - 2):i + 1])
            target = curves["uniform"][-1]
            reach = next((p for p in curves["visibility"] if p["smooth"] <= target["smooth"]), None)
            report.append(f"### Sponza, camera {cam}, {W}×{H} (reference {meta.get('spp')} spp)\n")
            report.append(
                f"`--schedule uniform --budget-ms 0` for {F} frames against `--schedule visibility "
                f"--budget-ms {budget:.1f}` for {3 * F} frames (the budget is the uniform run's median frame, "
                f"{fmt(u['frame_ms'])} ms, less three quarters of its probe update, {fmt(u['probe_update_ms'])} ms). "
                "Rays are the timings' `probe_rays` summed over the frames; every frame's image is compared "
                "with the path-traced reference (*RMSE*, PSNR) and with the last frame of an independent "
                f"uniform run of {2 * F} frames (`--seed 2 --hysteresis 0.99`), the renderer's converged image "
                "(*convergence RMSE*: the renderer's fixed bias against the path tracer, the same for both "
                "schedules, drops out). The ray ratio uses the convergence RMSE, smoothed over 3 frames.\n")
            report.append("| schedule | frames | rays | median probes traced per frame | final RMSE | final PSNR dB | final convergence RMSE |")
            report.append("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
            for mode, pts in curves.items():
                report.append(f"| {mode} | {len(pts)} | {pts[-1]['rays']} | "
                              f"{fmt(median([p['probes_traced'] for p in pts[1:]]), 0)} | "
                              f"{fmt(pts[-1]['rmse'], 4)} | {fmt(pts[-1]['psnr'], 2)} | "
                              f"{fmt(pts[-1]['rmse_vs_converged'], 4)} |")
            if reach:
                ratio = reach["rays"] / target["rays"] if target["rays"] else float("nan")
                report.append(f"\nThe visibility schedule first reaches the uniform run's final convergence RMSE "
                              f"({fmt(target['smooth'], 4)}) at frame {reach['frame']} with {reach['rays']} rays: "
                              f"**{fmt(ratio, 3)} ×** the uniform run's {target['rays']} rays.\n")
                result["ray_ratio"] = ratio
            else:
                report.append(f"\nThe visibility schedule does not reach the uniform run's final convergence RMSE "
                              f"({fmt(target['smooth'], 4)}) within its {3 * F} frames "
                              f"({curves['visibility'][-1]['rays']} rays).\n")
                result["ray_ratio_note"] = "not reached"
            report.append("CSV: [results/schedule_rays.csv](results/schedule_rays.csv).\n")
            if plot(runner, "schedule.gp", results_dir / "schedule_rays.csv",
                    results_dir / "schedule_rays.png", f"Sponza {cam}, {W}x{H}"):
                report.append("![error against rays](results/schedule_rays.png)\n")
        except StepFailed as e:
            report.append(f"**Sponza scheduling: failed: {e}**\n")
            log(str(e))
    # (b) A path of frames at a fixed budget: the animated Cornell box (the block moves, the camera
    # stays), which ends at the rest pose so the end error has a reference.
    path = scenes["animated"]
    W, H = sch["path_size"]
    n = sch["path_frames"]
    try:
        ref, meta = reference(runner, cache, "animated_rest", path, (W, H), sch["path_ref_spp"])
        probe = render(runner, path, runner.work / "sched_path_uniform",
                       ["--width", W, "--height", H, "--frames", 6, "--schedule", "uniform",
                        "--budget-ms", 0], "schedule path: uniform cost")
        pu = frame_stats(probe)
        budget = 0.5 * pu["frame_ms"]
        out = runner.work / "sched_path"
        t = render(runner, path, out, ["--width", W, "--height", H, "--frames", n,
                                       "--schedule", "visibility", "--budget-ms", f"{budget:.1f}"],
                   f"schedule path {n} frames, budget {budget:.0f} ms", timeout=3600)
        frames = t["frames"]
        ms = [f["total_ms"] - f["stages_ms"].get("output", 0.0) for f in frames]
        within = sum(1 for m in ms if m <= budget)
        within_steady = sum(1 for m in ms[1:] if m <= budget)
        fig = compare_many(runner, {"end": (only_exr(out), ref)}, "sched_path")["end"]
        frac = within / len(frames)
        write_csv(results_dir / "schedule_path.csv", ["frame", "frame_ms", "budget_ms", "probe_rays",
                                                      "probes_traced"],
                  [{"frame": f["frame"], "frame_ms": m, "budget_ms": budget, "probe_rays": f.get("probe_rays"),
                    "probes_traced": f.get("probes_traced")} for f, m in zip(frames, ms)])
        report.append(f"### Budget: animated Cornell box, {n} frames at 30 fps "
                      f"(t = 0–{n / 30:.1f} s; the block moves for the first 4 s), {W}×{H}\n")
        report.append(
            f"`--schedule visibility --budget-ms {budget:.1f}`: half the median frame of a 6-frame uniform run "
            f"of the same scene and size ({fmt(pu['frame_ms'])} ms, measured just before). Frames within the "
            f"budget (frame time without file output): {within} of {len(frames)} ({fmt(100 * frac)} %; "
            f"{within_steady} of {len(frames) - 1} without the first frame, which builds the pipelines); "
            f"median frame {fmt(median(ms[1:]))} ms, 95th percentile "
            f"{fmt(sorted(ms[1:])[int(0.95 * (len(ms) - 2))] if len(ms) > 2 else float('nan'))} ms. "
            f"End error against a {meta.get('spp')}-spp reference of the rest pose: PSNR "
            f"{fmt(fig['psnr'], 2)} dB, SSIM {fmt(fig['ssim'], 3)}, RMSE {fmt(fig['rmse'], 4)}. "
            "CSV: [results/schedule_path.csv](results/schedule_path.csv).\n")
        result.update(within=frac, end_psnr=fig["psnr"], budget=budget)
    except StepFailed as e:
        report.append(f"**Budgeted path: failed: {e}**\n")
        log(str(e))
    return result


# ---------------------------------------------------------------------------------------------
# Machine description.

def machine(runner):
    info = {}
    wanted = ("Model name", "CPU(s)", "Core(s) per socket", "Thread(s) per core")
    try:
        lscpu = subprocess.run(["lscpu"], stdout=subprocess.PIPE, text=True).stdout
        found = {}
        for line in lscpu.splitlines():
            k, _, v = line.partition(":")
            if k.strip() in wanted and k.strip() not in found:
                found[k.strip()] = v.strip()
        info.update((k, found[k]) for k in wanted if k in found)
    except OSError:
        info["Model name"] = "unknown (no lscpu)"
    try:
        mem = Path("/proc/meminfo").read_text().splitlines()[0].split()
        info["Memory"] = f"{int(mem[1]) / 1024 / 1024:.1f} GiB"
    except (OSError, IndexError, ValueError):
        info["Memory"] = "unknown"
    devices = runner.run([runner.exe("ddish"), "devices"], "devices")
    m = re.search(r"device \d+: (.*?)\s+\[default\]", devices)
    info["Vulkan device"] = m.group(1) if m else "unknown"
    m = re.search(r"Mesa ([0-9.]+)", devices)
    info["Mesa"] = m.group(1) if m else "none (no Mesa driver)"
    m = re.search(r"Vulkan loader ([0-9.]+)", devices)
    info["Vulkan loader"] = m.group(1) if m else "unknown"
    info["OS"] = platform.platform()
    try:
        info["Commit"] = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"],
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                        text=True).stdout.strip() or "unknown"
    except OSError:
        info["Commit"] = "unknown"
    load = os.getloadavg()
    info["Load average at start"] = f"{load[0]:.2f} {load[1]:.2f} {load[2]:.2f}"
    return info, devices


def main():
    global RENDER_HELP
    ap = argparse.ArgumentParser(description="regenerate the results report")
    ap.add_argument("--quick", action="store_true", help="tiny sizes, Cornell box only (smoke test)")
    ap.add_argument("--out", default=str(ROOT / "docs"), help="write OUT/RESULTS.md and OUT/results/")
    ap.add_argument("--sections", default="scaling,error,dynamic,schedule",
                    help="comma-separated subset of scaling,error,dynamic,schedule (default: all)")
    a = ap.parse_args()
    cfg = QUICK if a.quick else FULL

    build = Path(os.environ.get("DDISH_BUILD_DIR", "build"))
    build = build if build.is_absolute() else (ROOT / build)
    scenes_dir = Path(os.environ.get("DDISH_SCENES", str(ROOT.parent / "shared" / "scenes")))
    cache = Path(os.environ.get("DDISH_RESULTS_CACHE", str(build / "results-cache")))
    out_dir = Path(a.out).resolve()
    results_dir = out_dir / "results"
    if not (build / "ddish").is_file():
        print(f"results: error: {build / 'ddish'} is not built (set DDISH_BUILD_DIR or build first)",
              file=sys.stderr)
        return 2
    results_dir.mkdir(parents=True, exist_ok=True)
    for old in list(results_dir.glob("*.csv")) + list(results_dir.glob("*.png")):
        old.unlink()
    cache.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="ddish-results-"))
    runner = Runner(build, work, results_dir / "commands.txt")
    scenes = scene_paths(scenes_dir)
    log(f"{cfg['mode']} run: build {build}, scenes {scenes_dir}, cache {cache}, output {out_dir}")

    started = datetime.datetime.now(datetime.timezone.utc)
    info, _ = machine(runner)
    RENDER_HELP = runner.run([build / "ddish", "render", "--help"], "render --help")

    body = []
    failures = []
    sections = [
        ("viewport scaling", "scaling", lambda: section_scaling(runner, cfg, scenes, results_dir, body)),
        ("error against run time", "error",
         lambda: section_error(runner, cfg, scenes, cache, results_dir, body)),
        ("dynamic light", "dynamic", lambda: section_dynamic(runner, cfg, scenes, cache, results_dir, body)),
        ("scheduling", "schedule", lambda: section_schedule(runner, cfg, scenes, cache, results_dir, body)),
    ]
    chosen = set(a.sections.split(","))
    unknown = chosen - {key for _, key, _ in sections}
    if unknown:
        print(f"results: error: unknown section(s) {', '.join(sorted(unknown))}", file=sys.stderr)
        return 2
    outcome = {}
    for name, key, fn in sections:
        if key not in chosen:
            body.append(f"*Section {name}: not run in this invocation (--sections).*\n")
            continue
        log(f"section: {name}")
        try:
            outcome[name] = fn()
        except Exception as e:  # a broken section is reported, the others still run
            failures.append(f"{name}: {type(e).__name__}: {e}")
            body.append(f"**Section {name} failed: {type(e).__name__}: {e}**\n")
            log(f"section {name} failed: {e}")
    runner.save_commands()
    elapsed = time.monotonic() - START

    head = ["# Results\n",
            f"Generated by `bash scripts/results.sh{' --quick' if a.quick else ''}` "
            f"({cfg['mode']} variant) on {started:%Y-%m-%d %H:%M} UTC in {elapsed / 60:.1f} min. "
            "Every figure below was measured in that run (reference images may come from the cache "
            "of an earlier run of the same scene, size and spp); nothing is typed in by hand. "
            "The commands run are listed in [results/commands.txt](results/commands.txt) "
            "(`$BUILD` = the build directory, `$WORK` = a scratch directory).\n",
            ("Every `ddish render` outside section 4 runs with `" + " ".join(uniform_args()) +
             "`: the published behaviour, every active probe at full samples every frame.\n"
             if uniform_args() else ""),
            "## Machine\n", "| | |", "| --- | --- |"]
    for k, v in info.items():
        head.append(f"| {k} | {v} |")
    head.append("")
    head += headline(outcome)
    if failures:
        head.append("**Failed sections:** " + "; ".join(failures) + "\n")
    text = "\n".join(head + body) + "\n"
    (out_dir / "RESULTS.md").write_text(text)
    shutil.rmtree(work, ignore_errors=True)
    log(f"wrote {out_dir / 'RESULTS.md'} and {results_dir} in {elapsed:.0f} s")
    return 0


def headline(outcome):
    lines = ["## Headline figures\n"]
    scaling = outcome.get("viewport scaling")
    if scaling:
        rows, _trace = scaling
        for key in dict.fromkeys(r["scene"] for r in rows):
            rs = {r["views"]: r for r in rows if r["scene"] == key}
            lo, hi = min(rs), max(rs)
            lines.append(f"- {SCENE_NAMES[key]}: {fmt(rs[lo]['frame_ms'])} ms per frame for {lo} view, "
                         f"{fmt(rs[hi]['frame_ms'])} ms for {hi} views "
                         f"({fmt(rs[hi]['raster_per_view_ms'])} ms raster per view); "
                         f"speed-up over a probe update per view (naive, {fmt(rs[hi].get('naive_ms'))} ms): "
                         f"{fmt(rs[hi].get('speedup_vs_naive'), 2)}× at {hi} views"
                         + (f", {fmt(rs[32].get('speedup_vs_naive'), 2)}× at 32" if 32 in rs and hi != 32 else "")
                         + ".")
    err = outcome.get("error against run time")
    if err:
        for key, s in err.items():
            p, e, d = s["paper"], s["equal_time"], s["direct"]
            if p and finite(p.get("psnr")):
                line = (f"- {SCENE_NAMES[key]}, paper settings: PSNR {fmt(p['psnr'], 2)} dB, SSIM "
                        f"{fmt(p['ssim'], 3)} at {fmt(p['ms_per_frame'])} ms per frame")
                if e and finite(e.get("psnr")):
                    line += (f"; path tracing at equal time ({e['spp']} spp, {fmt(e['ms_per_frame'])} ms): "
                             f"PSNR {fmt(e['psnr'], 2)} dB, SSIM {fmt(e['ssim'], 3)}")
                if d and finite(d.get("psnr")):
                    line += f"; direct light only: PSNR {fmt(d['psnr'], 2)} dB"
                lines.append(line + ".")
    sch = outcome.get("scheduling")
    if sch:
        if "ray_ratio" in sch:
            lines.append(f"- Scheduling: the visibility schedule reaches the uniform run's error with "
                         f"{fmt(sch['ray_ratio'], 3)} × its rays.")
        if "within" in sch:
            lines.append(f"- Budgeted path ({fmt(sch['budget'])} ms): {fmt(100 * sch['within'])} % of frames "
                         f"within budget, end PSNR {fmt(sch['end_psnr'], 2)} dB.")
        if sch.get("ray_ratio_note"):
            lines.append("- Scheduling: the visibility schedule did not reach the uniform run's error "
                         "within its frames.")
    if len(lines) == 1:
        lines.append("- none: no section produced figures.")
    lines.append("")
    return lines


if __name__ == "__main__":
    sys.exit(main())
