"""Section 1: viewport scaling (N views from one probe update against the naive way and the
machine's floors)."""

import csv
import shutil
import time

from common import SCENE_NAMES, StepFailed, fmt, frame_stats, log, plot, render, write_csv
from memory import memory
from output_overhead import output_overhead
from drivers import driver_rows


def section_scaling(runner, cfg, scenes, results_dir, report):
    W, H = cfg["scaling_tile"]
    msaa = cfg["scaling_msaa"]
    # The Looking Glass Portrait profile's tile, drawn with the renderer's default MSAA (4 on
    # lavapipe); a smaller tile or 1 sample is a reduction that the text must own up to.
    msaa_note = ("" if msaa == 4 else
                 f"; {msaa} sample per pixel instead of the renderer's default 4, so that the full run "
                 "fits its time on a 2-core lavapipe machine")
    rows_all = []
    report.append("## 1. Viewport scaling\n")
    report.append(
        f"N views of a Looking Glass Portrait light-field rig (`--display looking-glass-portrait "
        f"--views N --width {W} --height {H} --msaa {msaa}`: tile {W}×{H}"
        f"{', the profile tile' if (W, H) == (420, 560) else ', reduced from the profile tile 420×560 so that the full run fits its time on a 2-core lavapipe machine (the tables show what a view costs at this size)'}"
        f"{msaa_note}; texture anisotropic filtering automatic, i.e. off on lavapipe, see `--anisotropy`"
        f"), {cfg['scaling_frames']} frames per run; figures are medians over the steady frames (frame 0, "
        "which builds pipelines and uploads every probe, is left out; *output* is the last frame's "
        "file writing: its hand-over to the writer thread plus the wait for the writer to finish). "
        "Probe settings are the scene's defaults (sidecar grid, L2, 256 paths per probe, 15 bounces). "
        "*frame* = pose + probe update + upload + raster: a displayed frame, without output and "
        "without readback (`ddish render` reads back only the frames it writes; *readback* is the "
        "last frame's, which is written).\n")
    report.append(
        "*Naive* is computed, not run: N × (probe update + upload + 1-view raster), i.e. one probe "
        "update per view, with the probe update and upload measured in the same run as the N views "
        "(so that load drifting between runs does not favour either side) and the 1-view raster from "
        "the N = 1 run. *Trivial-shader floor* is "
        f"`bench/raster_views --method per-view --cull on --shading trivial` at the same N, tile size "
        f"and MSAA ({msaa}): the recording `ddish render` uses (one pass per view, cluster culling), "
        "the same triangles, vertex shader, depth test, passes and target, with a fragment shader "
        "that writes a constant colour; its frame (record + GPU, shadow maps kept, the bench's readback "
        "taken out as it is from *raster*) is the "
        "machine's vertex + raster + fill floor for N views, so *raster ÷ floor* is what shading "
        "multiplies it by. *Tracing floor* is `bench/trace_floor`: the rays of a real probe update, "
        "recorded as it casts them (probe and bounce rays as closest-hit queries, shadow rays as "
        "occlusion queries), replayed with plain `rtcIntersect1` / `rtcOccluded1` on one flat Embree "
        "scene over the same threads, no shading, against the full probe update casting the same "
        "rays; *share of the floor* is the update's Mrays/s over the floor's.\n")
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
        elif b"--shading" not in rv.read_bytes():
            floor_note = "missing: this build's bench/raster_views has no --shading trivial"
        else:
            try:
                out = runner.run([rv, path, "--views", ",".join(str(r["views"]) for r in rows) or "1",
                                  "--size", f"{W}x{H}", "--frames", cfg["raster_floor_frames"],
                                  "--msaa", msaa, "--method", "per-view", "--cull", "on",
                                  "--shading", "trivial"],
                                 f"raster_views {key}", timeout=3600)
                lines = [l for l in out.splitlines() if l and not l.startswith("#")]
                reader = list(csv.DictReader(lines))
                for r in reader:
                    r2 = dict(r, scene=key)
                    floor_rows.append(r2)
                trivial = [r for r in reader if r.get("shading") == "trivial"]
                for r in trivial:
                    n = int(r["views"])
                    ms = float(r["frame_ms"]) - float(r.get("readback_ms") or 0.0)
                    floor[n] = min(floor.get(n, ms), ms)
                floor_note = ("trivial-shader rows of bench/raster_views" if trivial else
                              "missing: bench/raster_views printed no trivial-shader rows")
            except (StepFailed, KeyError, ValueError) as e:
                floor_note = f"failed: {e}"
                log(floor_note)
        for r in rows:
            r["trivial_floor_ms"] = floor.get(r["views"])
            r["trivial_floor_per_view_ms"] = (r["trivial_floor_ms"] / r["views"]
                                              if r["trivial_floor_ms"] is not None else None)
            r["raster_over_floor"] = (r["raster_ms"] / r["trivial_floor_ms"]
                                      if r["trivial_floor_ms"] else None)
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
                  "raster_per_view_ms", "forward_gpu_ms", "frame_ms", "output_ms", "readback_ms", "naive_ms",
                  "speedup_vs_naive", "trivial_floor_ms", "trivial_floor_per_view_ms",
                  "raster_over_floor", "probe_rays", "probe_updates", "frames_used"]
        csv_path = results_dir / f"scaling_{key}.csv"
        write_csv(csv_path, header, rows)
        report.append(f"### {SCENE_NAMES[key]}\n")
        report += failed
        if rows:
            report.append("| N | probe update | upload | raster | raster / view | frame | output | readback | naive (N updates) | speed-up | trivial-shader floor | floor / view | raster ÷ floor |")
            report.append("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
            for r in rows:
                report.append(
                    f"| {r['views']} | {fmt(r['probe_update_ms'])} | {fmt(r['upload_ms'], 2)} | "
                    f"{fmt(r['raster_ms'])} | {fmt(r['raster_per_view_ms'])} | {fmt(r['frame_ms'])} | "
                    f"{fmt(r['output_ms'])} | {fmt(r.get('readback_ms'))} | {fmt(r.get('naive_ms'))} | {fmt(r.get('speedup_vs_naive'), 2)}× | "
                    f"{fmt(r.get('trivial_floor_ms'))} | {fmt(r.get('trivial_floor_per_view_ms'))} | "
                    f"{fmt(r.get('raster_over_floor'), 2)}{'×' if r.get('raster_over_floor') else ''} |")
            report.append(f"\nAll times in ms per frame. Trivial-shader floor: {floor_note}. "
                          f"CSV: [results/scaling_{key}.csv](results/scaling_{key}.csv).\n")
            if plot(runner, "scaling.gp", csv_path, results_dir / f"scaling_{key}.png",
                    f"{SCENE_NAMES[key]}, {W}x{H} per view"):
                report.append(f"![viewport scaling, {SCENE_NAMES[key]}](results/scaling_{key}.png)\n")
        if trace:
            report.append(
                f"Tracing floor ({trace_note}): grid {trace['grid']}, {trace['active']} active of "
                f"{trace['probes']} probes × {trace['samples']} paths, {trace['threads']} threads. The update's own "
                f"{trace['floor_rays']} rays ({fmt(float(trace['update_rays']) / max(1.0, float(trace['update_paths'])), 2)} per path; "
                f"{trace['floor_shadow_rays']} of them shadow rays) with plain Embree queries: "
                f"{fmt(float(trace['floor_ms']))} ms ({fmt(float(trace['floor_mrays_s']), 2)} Mrays/s, "
                f"{fmt(float(trace['floor_mrays_s_per_thread']), 2)} per thread, {fmt(100 * float(trace['floor_hit_fraction']))} % hit); "
                f"through the tracer's own Embree scene ({trace['tracer_scene']}, alpha filters): {fmt(float(trace['scene_floor_ms']))} ms "
                f"({fmt(float(trace['scene_floor_mrays_s']), 2)} Mrays/s). Full probe update casting the same rays: "
                f"{fmt(float(trace['update_ms']))} ms, {fmt(float(trace['update_mrays_s']), 2)} Mrays/s "
                f"({fmt(float(trace['update_mrays_s_per_thread']), 2)} per thread); share of the floor "
                f"{fmt(100 * float(trace['update_share_of_floor']))} % (the update takes "
                f"{fmt(float(trace['update_over_floor']), 2)}× the floor's time; on process CPU time, steadier "
                f"on a loaded machine: {fmt(float(trace['update_cpu_ms']))} ms against {fmt(float(trace['floor_cpu_ms']))} ms, "
                f"{fmt(100 * float(trace['update_share_of_floor_cpu']))} %).\n")
        else:
            report.append(f"Tracing floor: {trace_note}.\n")
    overhead = output_overhead(runner, cfg, scenes, report)
    mem = memory(runner, cfg, scenes, report, overhead)
    if floor_rows:
        keys = list(floor_rows[0].keys())
        write_csv(results_dir / "raster_views.csv", keys, floor_rows)
        report.append("Raw `bench/raster_views` output (the trivial-shader floor rows): "
                      "[results/raster_views.csv](results/raster_views.csv).\n")
    if trace_rows:
        write_csv(results_dir / "trace_floor.csv", list(trace_rows[0].keys()), trace_rows)
        report.append("Tracing floor per scene: [results/trace_floor.csv](results/trace_floor.csv).\n")
    if cfg["mode"] == "full":
        driver_rows(runner, cfg, scenes, results_dir, report)
    return rows_all, trace_rows, overhead, mem
