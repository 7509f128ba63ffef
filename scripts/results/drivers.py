"""Section 1's driver row pair: the same bench/raster_views binary on Mesa 25 lavapipe (the system
driver, from bookworm-backports) and on bookworm's own Mesa 22.3 (unpacked beside the build by
scripts/fetch_mesa22.sh, selected with VK_DRIVER_FILES), one view at the scaling tile, full and
trivial shading. On a driver that runs the visibility pass (Mesa 25), full shading is measured
through both shading passes (`--shading-pass both`), so the table shows what that pass bought on
its own; Mesa 22 lacks non-uniform texture indexing and shades forward only."""

import csv
import re

from common import ROOT, SCENE_NAMES, StepFailed, fmt, log, write_csv


def driver_rows(runner, cfg, scenes, results_dir, report):
    W, H = cfg["scaling_tile"]
    msaa = cfg["scaling_msaa"]
    report.append("### Mesa 22 against Mesa 25\n")
    rv = runner.exe("raster_views")
    if rv is None:
        report.append("*Not measured: bench/raster_views is not built.*\n")
        return []
    try:
        icd = runner.run(["bash", str(ROOT / "scripts" / "fetch_mesa22.sh"), str(runner.build / "mesa22")],
                         "Mesa 22 lavapipe").strip().splitlines()[-1]
    except StepFailed as e:
        report.append(f"*Not measured: Mesa 22 could not be unpacked ({e}).*\n")
        return []
    mesa22_libs = str(runner.build / "mesa22" / "root" / "usr" / "lib" / "x86_64-linux-gnu")
    # (name, environment, shading passes to measure)
    drivers = [("Mesa 25 (system)", None, "both"),
               ("Mesa 22.3 (bookworm)", {"VK_DRIVER_FILES": icd, "LD_LIBRARY_PATH": mesa22_libs}, "auto")]
    # Which Mesa each run really got, as the driver reports it (ddish devices).
    names = []
    for name, env, _ in drivers:
        try:
            out = runner.run([runner.build / "ddish", "devices"], f"devices on {name}", env=env)
        except StepFailed as e:
            report.append(f"*Not measured: {name} does not start ({e}).*\n")
            return []
        found = re.search(r"\((\w+): (Mesa [^ )]+)", out)
        names.append(found.group(2) if found else name)
    if len(set(names)) != len(names):
        report.append(f"*Not measured: both runs report the same driver ({names[0]}).*\n")
        return []
    drivers = [(reported, env, passes) for reported, (_, env, passes) in zip(names, drivers)]
    rows = []
    for key in cfg["scaling_scenes"]:
        path = scenes[key]
        if not path.is_file():
            continue
        for name, env, passes in drivers:
            try:
                out = runner.run([rv, path, "--views", "1", "--size", f"{W}x{H}", "--frames",
                                  cfg["raster_floor_frames"], "--msaa", msaa, "--method", "per-view",
                                  "--cull", "on", "--shading", "both", "--shading-pass", passes],
                                 f"raster_views {key} on {name}", timeout=3600, env=env)
            except StepFailed as e:
                report.append(f"**{SCENE_NAMES[key]} on {name}: failed: {e}**\n")
                log(str(e))
                continue
            lines = [l for l in out.splitlines() if l and not l.startswith("#")]
            for r in csv.DictReader(lines):
                rows.append({"scene": key, "driver": name, "shading": r["shading"],
                             "shading_pass": r.get("shading_pass", "forward"),
                             "frame_ms": float(r["frame_ms"]), "forward_gpu_ms": float(r["forward_gpu_ms"])})
    if not rows:
        return rows
    write_csv(results_dir / "drivers.csv",
              ["scene", "driver", "shading", "shading_pass", "frame_ms", "forward_gpu_ms"], rows)
    report.append(f"The same `bench/raster_views` binary, one view of {W}×{H}, MSAA {msaa}, one pass per "
                  "view with cluster culling; frame = record + GPU + readback, median of "
                  f"{cfg['raster_floor_frames']} frames. CSV: [results/drivers.csv](results/drivers.csv).\n")
    report.append("The trivial shader is the forward pass's constant colour on either driver; *shading "
                  "pass* is the full shading's (`--shading-pass`: forward, or the visibility pass that "
                  "shades each pixel once).\n")
    report.append("| scene | driver | shading pass | full shading ms | trivial shading ms | full ÷ trivial |")
    report.append("| --- | --- | --- | ---: | ---: | ---: |")
    for key in dict.fromkeys(r["scene"] for r in rows):
        for name, _, _ in drivers:
            mine = [r for r in rows if r["scene"] == key and r["driver"] == name]
            trivial = [r["frame_ms"] for r in mine if r["shading"] == "trivial"]
            for r in mine:
                if r["shading"] == "full" and trivial:
                    report.append(f"| {SCENE_NAMES[key]} | {name} | {r['shading_pass']} | {fmt(r['frame_ms'])} | "
                                  f"{fmt(trivial[0])} | {fmt(r['frame_ms'] / trivial[0], 2)}× |")
    report.append("")
    return rows
