"""What every section of the results run shares: logging, running the binaries (and recording
the commands), the scenes, cached references, comparisons, plots and small number helpers."""

import csv
import hashlib
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path


ROOT = Path(__file__).resolve().parents[2]
START = time.monotonic()


def log(message):
    print(f"[results {time.monotonic() - START:7.1f} s] {message}", file=sys.stderr, flush=True)


class StepFailed(Exception):
    pass



# ---------------------------------------------------------------------------------------------
# Running the binaries.

def run_child(args, timeout, env):
    """Runs one command from the checkout's root. Returns (exit code, stdout, stderr, peak resident
    memory in KiB): the child's own ru_maxrss from wait4, which getrusage(RUSAGE_CHILDREN), a
    maximum over every child so far, cannot give (it includes the forked Python's pages before
    exec, about 20 MB, far below any render's). The exit code is None when it ran past `timeout`
    seconds (it is then killed)."""
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=ROOT, env=env)
    streams = {}
    readers = [threading.Thread(target=lambda n=n, f=f: streams.__setitem__(n, f.read()))
               for n, f in (("out", proc.stdout), ("err", proc.stderr))]
    for r in readers:
        r.start()
    expired = threading.Event()
    timer = threading.Timer(timeout, lambda: (expired.set(), proc.kill()))
    timer.start()
    try:
        _, status, usage = os.wait4(proc.pid, 0)
    finally:
        timer.cancel()
    for r in readers:
        r.join()
    proc.stdout.close()
    proc.stderr.close()
    proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
    return (None if expired.is_set() else proc.returncode, streams.get("out", ""), streams.get("err", ""),
            usage.ru_maxrss)


class Runner:
    def __init__(self, build, work, commands_file):
        self.build = build
        self.work = work
        self.commands = []
        self.commands_file = commands_file
        self.last_peak_kib = None  # peak resident memory of the last command run (KiB)

    def exe(self, name):
        for p in (self.build / name, self.build / "bench" / name):
            if p.is_file() and os.access(p, os.X_OK):
                return p
        return None

    def run(self, args, what, timeout=1800, env=None):
        args = [str(a) for a in args]
        shown = " ".join([f"{k}={self.show(str(v))}" for k, v in (env or {}).items()] +
                         [self.show(a) for a in args])
        self.commands.append(shown)
        t0 = time.monotonic()
        returncode, stdout, stderr, self.last_peak_kib = run_child(
            args, timeout, dict(os.environ, **{k: str(v) for k, v in env.items()}) if env else None)
        if returncode is None:
            raise StepFailed(f"{what}: timed out after {timeout} s: {shown}")
        if returncode != 0:
            tail = (stderr or stdout).strip().splitlines()[-3:]
            raise StepFailed(f"{what}: exit {returncode}: {shown}: {' | '.join(tail)}")
        log(f"{what} ({time.monotonic() - t0:.1f} s)")
        return stdout

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
    is left out. The file output is not part of the frame time and is reported on its own: the
    last frame's hand-over to the writer plus the wait for the writer after the loop
    ("output_drain"). Neither is the readback: `ddish render` reads back only the frames it writes
    (the last, or every one with --every), so a frame's time is that of a displayed frame, and
    the last frame's readback is reported on its own."""
    frames = timings["frames"]
    steady = frames[1:] or frames
    def stage(name, fr):
        return median([f["stages_ms"].get(name, 0.0) for f in fr])
    def off_frame(f):
        st = f["stages_ms"]
        return st.get("output", 0.0) + st.get("output_drain", 0.0) + st.get("readback", 0.0)
    raster_names = ["raster_record", "shadow_gpu", "forward_gpu", "tonemap_gpu", "raster_wait"]
    raster = median([sum(f["stages_ms"].get(n, 0.0) for n in raster_names) for f in steady])
    frame = median([f["total_ms"] - off_frame(f) for f in steady])
    last = frames[-1]["stages_ms"]
    return {
        "probe_update_ms": stage("probe_update", steady),
        "upload_ms": stage("upload", steady),
        "raster_ms": raster,
        "forward_gpu_ms": stage("forward_gpu", steady),
        "frame_ms": frame,
        "output_ms": (last["output"] + last.get("output_drain", 0.0)) if "output" in last else float("nan"),
        "readback_ms": last.get("readback", float("nan")),
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
    # Cold probes at frame 0, as the paper's curves start: the warm-up (on by default, bounded by
    # time, so machine-dependent) would hide the convergence the sections measure.
    if "--warmup-ms" not in [str(a) for a in args]:
        args = [*args, "--warmup-ms", "0"]
    runner.run([runner.exe("ddish"), "render", path, "--out", out, "--timings", tj, *args], what,
               timeout=timeout)
    return json.loads(tj.read_text())


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



def uniform_args():
    """The published behaviour, every active probe every frame, no budget: how the scaling,
    error and dynamic sections run."""
    return ["--schedule", "uniform", "--budget-ms", "0"]
