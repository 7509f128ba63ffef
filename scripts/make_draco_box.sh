#!/usr/bin/env bash
# Writes scenes/draco_box_draco.gltf (+ .bin), the KHR_draco_mesh_compression twin of
# scenes/draco_box.gltf (scripts/feature_scenes.py), with Debian's Draco encoder (package
# `draco`, scripts/bootstrap.sh). Quantization at 20 bits keeps every position, normal and UV of
# the box within 1e-5 of the plain file (tests/scene/draco_test.cpp). Run after make_scenes.py.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
scenes="${1:-$here/../scenes}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
draco_transcoder -i "$scenes/draco_box.gltf" -o draco_box_draco.gltf -qp 20 -qt 20 -qn 20 >/dev/null
cp draco_box_draco.gltf draco_box_draco.bin "$scenes/"
echo "wrote $scenes/draco_box_draco.gltf"
