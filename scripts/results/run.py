#!/usr/bin/env python3
"""Measures and writes the results report (docs/RESULTS.md, docs/results/*.csv, *.png).

Run through scripts/results.sh (see there for the options and environment). Everything in the
report comes from the built binaries run here: ddish render (--timings), ddish reference,
ddish compare --json, bench/trace_floor and bench/raster_views. A step that fails is reported as
failed in the report; nothing is filled in. Python 3 standard library only.
"""

import argparse
import datetime
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from settings import FULL, QUICK
from common import (ROOT, Runner, SCENE_NAMES, START, finite, fmt, log, reference, render, scene_paths, uniform_args)
from scaling import section_scaling
from error_time import section_error
from dynamic import section_dynamic
from schedule import section_schedule
from service import section_service
from soak import section_soak


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
    ap = argparse.ArgumentParser(description="regenerate the results report")
    ap.add_argument("--quick", action="store_true", help="tiny sizes, Cornell box only (smoke test)")
    ap.add_argument("--out", default=str(ROOT / "docs"), help="write OUT/RESULTS.md and OUT/results/")
    ap.add_argument("--sections", default="scaling,error,dynamic,schedule,service,soak",
                    help="comma-separated subset of scaling,error,dynamic,schedule,service,soak (default: all)")
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
    cache.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="ddish-results-"))
    runner = Runner(build, work, results_dir / "commands.txt")
    scenes = scene_paths(scenes_dir)
    log(f"{cfg['mode']} run: build {build}, scenes {scenes_dir}, cache {cache}, output {out_dir}")

    started = datetime.datetime.now(datetime.timezone.utc)
    # The machine and commit first: removing the old outputs below would mark the tree dirty.
    info, _ = machine(runner)
    for old in list(results_dir.glob("*.csv")) + list(results_dir.glob("*.png")):
        old.unlink()

    body = []
    failures = []
    sections = [
        ("viewport scaling", "scaling", lambda: section_scaling(runner, cfg, scenes, results_dir, body)),
        ("error against run time", "error",
         lambda: section_error(runner, cfg, scenes, cache, results_dir, body)),
        ("dynamic light", "dynamic", lambda: section_dynamic(runner, cfg, scenes, cache, results_dir, body)),
        ("scheduling", "schedule", lambda: section_schedule(runner, cfg, scenes, cache, results_dir, body)),
        ("probe service", "service", lambda: section_service(runner, cfg, results_dir, body)),
        ("soak", "soak", lambda: section_soak(runner, cfg, results_dir, body)),
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
            "Every `ddish render` runs with `--warmup-ms 0`: the probes start cold at frame 0, so the "
            "curves show the convergence the warm-up (on by default) would otherwise hide.\n",
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
        rows, _trace, overhead, mem = scaling
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
        if overhead:
            lines.append(f"- Output: writing every frame of a {overhead['frames']}-frame {overhead['views']}-view "
                         f"{SCENE_NAMES[overhead['scene']]} run adds {fmt(100 * overhead['overhead'], 1)} % to its "
                         f"wall time ({fmt(overhead['last_s'], 1)} s → {fmt(overhead['every_s'], 1)} s).")
        if mem:
            one, hi = mem["views"][0], mem["views"][-1]
            line = (f"- Memory: each view beyond a full batch adds {fmt(mem['bytes_per_pixel'])} bytes per quilt "
                    f"pixel to the peak resident memory ({SCENE_NAMES[mem['scene']]}: {fmt(mem['peak_mb'][one])} MB "
                    f"at {one} view, {fmt(mem['peak_mb'][hi])} MB at {hi})")
            if mem.get("large"):
                L = mem["large"]
                line += (f"; the {L['display']} quilt ({L['views']} views of {L['tile'][0]}x{L['tile'][1]}) "
                         f"peaks at {fmt(L['peak_mb'])} MB, {fmt(L['bytes_per_pixel'])} bytes per extra pixel")
            lines.append(line + ".")
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
    svc = outcome.get("probe service")
    if svc:
        # serve's default streams 8x8 moment maps; the rows without maps (--probe-visibility 0)
        # are the figure to compare with reports from before protocol version 2.
        enc = {(r["encoding"] + (" + zstd" if r["zstd"] == "yes" else ""), r.get("moment_maps", "none")): r
               for r in svc["service_encodings.csv"]}
        with_maps, without = enc.get(("compact", "8x8")), enc.get(("compact", "none"))
        if with_maps:
            lines.append(f"- Probe stream (`serve` defaults, 8×8 moment maps): {with_maps['bytes_per_probe']} B "
                         f"per L2 probe in the first update (compact encoding), PSNR "
                         f"{with_maps['psnr_vs_in_process_db']} dB against the in-process render of the same "
                         "probes" + (f"; without moment maps {without['bytes_per_probe']} B, "
                                     f"{without['psnr_vs_in_process_db']} dB." if without else "."))
        elif without:
            lines.append(f"- Probe stream: {without['bytes_per_probe']} B per L2 probe (compact "
                         f"encoding), PSNR {without['psnr_vs_in_process_db']} dB against the "
                         "in-process render of the same probes.")
        rec = svc["service_reconnect.csv"]
        if rec:
            worst = max(float(r["max_s"]) for r in rec)
            lines.append(f"- Probe service faults: {len(rec)} clients × {rec[0]['reconnections']} server "
                         f"restarts, every client reconnected within {worst:.2f} s of the server's return.")
    soak = outcome.get("soak")
    if soak:
        growth = ", ".join(f"{r['resource']} {r['growth_pct']:+.2f} %" for r in soak["rows"])
        lines.append(f"- Soak, {soak['frames']} frames: after the warm-up {growth} "
                     f"({'flat' if soak['flat'] else 'NOT flat'}); frame time "
                     f"{soak['frame_ms_slope_per_1000']:+.3f} ms per 1000 frames "
                     f"({'no upward trend' if soak['trend_ok'] else 'UPWARD TREND'}).")
    if len(lines) == 1:
        lines.append("- none: no section produced figures.")
    lines.append("")
    return lines


if __name__ == "__main__":
    sys.exit(main())
