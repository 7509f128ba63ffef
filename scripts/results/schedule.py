"""Section 4: probe scheduling (rays to reach the uniform run's error; a budgeted camera path)."""

import statistics

from common import (StepFailed, compare_many, fmt, frame_stats, log, median, only_exr, plot, reference, render, write_csv)


def section_schedule(runner, cfg, scenes, cache, results_dir, report):
    report.append("## 4. Probe scheduling (issue 7)\n")
    sch = cfg["schedule"]
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
        headroom = [f["scheduler"].get("headroom_ms") for f in frames[1:] if f.get("scheduler")]
        headroom = [h for h in headroom if h is not None]
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
            f"{fmt(sorted(ms[1:])[int(0.95 * (len(ms) - 2))] if len(ms) > 2 else float('nan'))} ms; "
            f"the controller's jitter headroom (it aims at the budget less 1.3 sigmas of its recent "
            f"prediction misses, src/probes/budget.h) had a median of {fmt(median(headroom) if headroom else float('nan'))} ms. "
            f"End error against a {meta.get('spp')}-spp reference of the rest pose: PSNR "
            f"{fmt(fig['psnr'], 2)} dB, SSIM {fmt(fig['ssim'], 3)}, RMSE {fmt(fig['rmse'], 4)}. "
            "CSV: [results/schedule_path.csv](results/schedule_path.csv).\n")
        result.update(within=frac, end_psnr=fig["psnr"], budget=budget)
    except StepFailed as e:
        report.append(f"**Budgeted path: failed: {e}**\n")
        log(str(e))
    return result
