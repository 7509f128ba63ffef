#!/usr/bin/env python3
"""Runs every malformed input and option of the bad-input catalogue and prints its markdown
table (docs/extreme-cases.md, "Bad-input catalogue"): the command, what is wrong, and the one
line ddish answers with. tests/app/bad_input_catalogue_test.cpp walks the same table and checks
each line and exit code 2, so regenerate the table with this script when a message changes:

  python3 scripts/bad_input_catalogue.py [BUILD_DIR] > /tmp/table.md

Placeholders in the table: {scene} the bundled Cornell box, {bad} tests/app/bad_inputs/,
{tmp} a scratch folder of the run (holding a file `a_file`), {src} the source tree.
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (arguments after `ddish`, what is wrong[, where the line's machine- or branch-dependent rest
# starts: the table keeps what comes before it and ends with "…", which the test matches as a
# prefix])
CASES = [
    ("nosuch", "an unknown command", "(commands: "),
    ("nosuch --help", "an unknown command, with --help", "(commands: "),
    ("", "no command"),
    ("render", "no scene"),
    ("render {tmp}/nowhere.gltf", "a scene file that does not exist"),
    ("render {scene} --frames 0", "no frames"),
    ("render {scene} --frames abc", "a number that is not one"),
    ("render {scene} --fps 0", "a frame rate of 0"),
    ("render {scene} --msaa 3", "an MSAA count no device has"),
    ("render {scene} --anisotropy 99", "anisotropy beyond 16"),
    ("render {scene} --tonemap sepia", "an unknown tone curve"),
    ("render {scene} --grid 1,2", "a grid of two counts"),
    ("render {scene} --grid 0,1,1", "a grid count of 0"),
    ("render {scene} --grid 2,2,2 --probe-spacing 0.5", "both --grid and --probe-spacing"),
    ("render {scene} --probe-spacing -1", "a negative probe spacing"),
    ("render {scene} --probe-samples 0", "no paths per probe"),
    ("render {scene} --bounces -1", "negative bounces"),
    ("render {scene} --hysteresis 1", "hysteresis 1 (the average would never move)"),
    ("render {scene} --sh-order 5", "SH order 5"),
    ("render {scene} --schedule random", "an unknown schedule"),
    ("render {scene} --budget-ms -1", "a negative budget"),
    ("render {scene} --blend sometimes", "an unknown blend rule"),
    ("render {scene} --camera 1,2,3", "a camera of three numbers"),
    ("render {scene} --camera NoSuchNode", "a camera node the scene lacks"),
    ("render {scene} --display nosuch", "an unknown display profile", "available: "),
    ("render {scene} --display {bad}/profile_zero_views.json", "a profile with 0 views"),
    ("render {scene} --display {bad}/profile_no_tile.json", "a profile without a tile size"),
    ("render {scene} --display {bad}/profile_not_json.json", "a profile that is not JSON"),
    ("render {scene} --display {bad}/profile_views_do_not_fit.json", "more views than quilt cells"),
    ("render {scene} --display looking-glass-portrait --views 0", "0 views"),
    ("render {scene} --display stereo --views 3", "3 views of a stereo display"),
    ("render {scene} --calibration {bad}/calibration_good.json", "a calibration for a single view"),
    ("render {scene} --display looking-glass-portrait --calibration {bad}/calibration_no_slope.json",
     "a calibration without slope"),
    ("render {scene} --display looking-glass-portrait --calibration {bad}/calibration_negative_pitch.json",
     "a negative lenticular pitch"),
    ("render {scene} --display looking-glass-portrait --calibration {bad}/calibration_not_json.json",
     "a calibration that is not JSON"),
    ("render {scene} --out {tmp}/a_file/out", "an output folder under a file"),
    ("render {scene} --timings {tmp}/a_file/t.json", "a timings file under a file"),
    ("render {scene} --every=0", "writing every 0th frame"),
    ("render {scene} --width 2048 --height 2048 --warmup-ms 0 --max-gpu-memory 64",
     "a view larger than --max-gpu-memory allows"),
    ("render {bad}/truncated.gltf", "a glTF cut off in the middle"),
    ("render {bad}/empty.gltf", "an empty file"),
    ("info {bad}/version_1.gltf", "glTF 1.0"),
    ("info {bad}/accessor_past_buffer.gltf", "an accessor that reaches past its buffer"),
    ("info {bad}/index_out_of_range.gltf", "a triangle index past the vertices"),
    ("info {bad}/unsupported_extension.gltf", "a required extension ddish lacks"),
    ("info {bad}/node_cycle.gltf", "a node that is its own child"),
    ("info {bad}/missing_mesh.gltf", "a node naming a mesh that does not exist"),
    ("info {bad}/missing_buffer_file.gltf", "a buffer file that is not there"),
    ("info {bad}/scale_not_finite.gltf", "a node scale beyond float range"),
    ("info {bad}/skin_joint_out_of_range.gltf", "a skinned vertex using a joint its skin lacks"),
    ("info {bad}/skin_no_joints.gltf", "a skin without joints"),
    ("render {bad}/points_only.gltf", "a scene of points only (nothing ddish draws)"),
    ("render {bad}/huge_textures.gltf", "textures that decode to more than the memory free",
     "more than the"),
    ("info {bad}/truncated.glb", "a GLB cut off in its header"),
    ("info {src}/tests/fuzz/corpus/glb/glb_draco_orientation_count.glb",
     "a Draco stream that would keep libdraco busy for seconds (a fuzz finding)"),
    ("info {bad}/sidecar_counts.gltf", "a sidecar whose grid counts are a word"),
    ("info {bad}/sidecar_negative_sky.gltf", "a sidecar with negative sky radiance"),
    ("info {bad}/sidecar_not_json.gltf", "a sidecar that is not JSON"),
    ("info {bad}/sidecar_zero_counts.gltf", "a sidecar grid count of 0"),
    ("info {tmp}", "a folder for a scene"),
    ("probes {scene} --updates 0", "no probe updates"),
    ("probes {scene} --out {tmp}", "a probe volume path that is a folder"),
    ("reference {scene} --out {tmp}/r --spp 0", "0 samples per pixel"),
    ("reference {scene} --out {tmp}/r --time-limit -1", "a negative time limit"),
    ("reference {scene} --out {tmp}/r --display looking-glass-portrait --convergence {tmp}/c.csv",
     "a convergence curve of 48 views"),
    ("reference {scene} --out {tmp}/a_file/r", "a reference folder under a file"),
    ("compare {bad}/not_an_image.png", "no reference"),
    ("compare {bad}/not_an_image.png {bad}/not_an_image.png", "a file that is not an image"),
    ("compare {bad}/not_an_image.png {tmp}/nowhere.png", "a reference that does not exist"),
    ("compare {tmp} {tmp} --quilt 3", "a quilt layout without rows"),
]


def expand(text, tmp):
    return (text.replace("{scene}", os.path.join(ROOT, "scenes", "cornell_box.gltf"))
            .replace("{bad}", os.path.join(ROOT, "tests", "app", "bad_inputs"))
            .replace("{tmp}", tmp).replace("{src}", ROOT))


def collapse(text, tmp):
    return (text.replace(os.path.join(ROOT, "scenes", "cornell_box.gltf"), "{scene}")
            .replace(os.path.join(ROOT, "tests", "app", "bad_inputs"), "{bad}")
            .replace(tmp, "{tmp}").replace(ROOT, "{src}"))


def cell(text):
    return text.replace("|", "\\|")


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    exe = os.path.join(build, "ddish")
    print("| # | command | what is wrong | the one line (exit code 2) |")
    print("| --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory(prefix="ddish_catalogue_") as tmp:
        with open(os.path.join(tmp, "a_file"), "w") as f:
            f.write("x")
        for n, (args, what, *cut) in enumerate(CASES, 1):
            r = subprocess.run([exe] + expand(args, tmp).split(), capture_output=True, text=True,
                               timeout=120)
            lines = r.stderr.splitlines()
            last = lines[-1] if lines else ""
            errors = [l for l in lines if l.startswith("ddish: error: ")]
            if r.returncode != 2 or len(errors) != 1 or last != errors[0]:
                print(f"catalogue: case {n} ({args}): exit {r.returncode}, stderr: {r.stderr!r}",
                      file=sys.stderr)
            line = collapse(last, tmp)
            if cut and cut[0] in line:
                line = line[: line.index(cut[0]) + len(cut[0])] + "…"
            print(f"| {n} | `ddish {cell(args)}` | {cell(what)} | `{cell(line)}` |")


if __name__ == "__main__":
    main()
