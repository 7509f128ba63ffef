#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/NAME/) from the project's own files.

  gltf/          every scenes/*.gltf with its buffers embedded as data URIs (self-contained:
                 the fuzz target loads one file from an empty folder)
  glb/           the same scenes as binary glTF (JSON chunk + BIN chunk)
  sidecar/       scenes/*.ddish.json, the shared scenes' sidecars, one with probe bounds
  display_profile/  displays/*.json
  calibration/   a Looking Glass visual.json ({"value": x} fields) and one with bare numbers
  volume_file/   DDPV volumes written by `ddish probes` (L1..L4, fp16 and shared exponent)

Usage: python3 scripts/make_fuzz_corpus.py [BUILD_DIR]  (BUILD_DIR/ddish writes the volumes;
default build/). The corpora are committed; rerun this when the formats change.
"""
import base64
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(ROOT, "tests", "fuzz", "corpus")


def fresh(name):
    d = os.path.join(CORPUS, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    return d


def scenes():
    d = os.path.join(ROOT, "scenes")
    return sorted(f for f in os.listdir(d) if f.endswith(".gltf"))


def compact(doc):
    return json.dumps(doc, separators=(",", ":"))


def gltf_and_glb():
    gltf_dir, glb_dir = fresh("gltf"), fresh("glb")
    for name in scenes():
        path = os.path.join(ROOT, "scenes", name)
        with open(path) as f:
            doc = json.load(f)
        blobs = []
        for b in doc.get("buffers", []):
            with open(os.path.join(os.path.dirname(path), b["uri"]), "rb") as f:
                blobs.append(f.read())
        stem = name[: -len(".gltf")]
        embedded = json.loads(json.dumps(doc))
        for b, blob in zip(embedded["buffers"], blobs):
            b["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
        with open(os.path.join(gltf_dir, stem + ".gltf"), "w") as f:
            f.write(compact(embedded))
        if len(blobs) != 1:
            continue  # GLB holds one buffer
        binary = json.loads(json.dumps(doc))
        del binary["buffers"][0]["uri"]
        js = compact(binary).encode()
        js += b" " * (-len(js) % 4)
        bin_ = blobs[0] + b"\0" * (-len(blobs[0]) % 4)
        total = 12 + 8 + len(js) + 8 + len(bin_)
        with open(os.path.join(glb_dir, stem + ".glb"), "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, total))
            f.write(struct.pack("<I4s", len(js), b"JSON") + js)
            f.write(struct.pack("<I4s", len(bin_), b"BIN\0") + bin_)


def sidecars():
    d = fresh("sidecar")
    for name in sorted(os.listdir(os.path.join(ROOT, "scenes"))):
        if name.endswith(".ddish.json"):
            with open(os.path.join(ROOT, "scenes", name)) as f:
                doc = json.load(f)
            with open(os.path.join(d, name), "w") as f:
                f.write(compact(doc))
    shared = os.path.join(ROOT, "..", "shared", "scenes")
    for sub in ("sponza", "breakfast_room"):
        sub_dir = os.path.join(shared, sub)
        if os.path.isdir(sub_dir):
            for name in os.listdir(sub_dir):
                if name.endswith(".ddish.json"):
                    shutil.copy(os.path.join(sub_dir, name), os.path.join(d, name))
    with open(os.path.join(d, "every_member.ddish.json"), "w") as f:
        f.write(compact({"light_units": "radiometric",
                         "environment": {"radiance": [0.5, 0.25, 1e-3]},
                         "probe_grid": {"counts": [3, 2, 1],
                                        "bounds": {"min": [-1.5, 0, -2], "max": [1, 2.5, 0.5]}},
                         "camera": "CameraMain"}))


def profiles():
    d = fresh("display_profile")
    for name in sorted(os.listdir(os.path.join(ROOT, "displays"))):
        if name.endswith(".json"):
            shutil.copy(os.path.join(ROOT, "displays", name), os.path.join(d, name))


def calibrations():
    d = fresh("calibration")
    fields = {"pitch": 52.58737671470091, "slope": -7.196136200157333,
              "center": 0.4321881363063158, "viewCone": 40.0, "invView": 1,
              "verticalAngle": 0.0, "DPI": 63.28125, "screenW": 300.0, "screenH": 400.0,
              "flipImageX": 0.0, "flipImageY": 0.0, "flipSubp": 0.0}
    wrapped = {"configVersion": "1.0", "serial": "LKG-P-FUZZ"}
    wrapped.update({k: {"value": v} for k, v in fields.items()})
    with open(os.path.join(d, "visual.json"), "w") as f:
        f.write(compact(wrapped))
    bare = dict(fields, invView=0, flipSubp=1, flipImageX=1)
    with open(os.path.join(d, "bare_numbers.json"), "w") as f:
        f.write(compact(bare))


def volumes(build):
    d = fresh("volume_file")
    exe = os.path.join(build, "ddish")
    with tempfile.TemporaryDirectory() as tmp:
        runs = [("cornell_l1", "cornell_box", ["--sh-order", "1"]),
                ("cornell_l2", "cornell_box", ["--sh-order", "2"]),
                ("cornell_l3", "cornell_spot", ["--sh-order", "3", "--grid", "2,2,1"]),
                ("cornell_l4", "two_rooms", ["--sh-order", "4", "--grid", "1,1,1"]),
                ("bright", "cornell_light", ["--grid", "2,1,1"])]
        for stem, scene, extra in runs:
            out = os.path.join(tmp, stem + ".ddpv")
            args = [exe, "probes", os.path.join(ROOT, "scenes", scene + ".gltf"),
                    "--probe-samples", "16", "--out", out]
            if "--grid" not in extra:
                args += ["--grid", "2,2,2"]
            subprocess.run(args + extra, check=True, stdout=subprocess.DEVNULL)
            shutil.copy(out, os.path.join(d, stem + ".ddpv"))


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    gltf_and_glb()
    sidecars()
    profiles()
    calibrations()
    volumes(build)
    for name in sorted(os.listdir(CORPUS)):
        files = os.listdir(os.path.join(CORPUS, name))
        print(f"{name}: {len(files)} files")


if __name__ == "__main__":
    main()
