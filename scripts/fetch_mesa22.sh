#!/usr/bin/env bash
# Unpacks bookworm's own Mesa 22.3 lavapipe beside the build, for the report's Mesa 22 vs Mesa 25
# row pair (scripts/results/drivers.py): the same binaries run on either driver through
# VK_DRIVER_FILES, while the system keeps Mesa 25 from bookworm-backports (scripts/bootstrap.sh).
# Downloads the .deb files from Debian's archive with `apt-get download` (no root needed, nothing
# installed) and writes DIR/lvp22.json, an ICD manifest naming the unpacked driver.
#
#   bash scripts/fetch_mesa22.sh [DIR]      (default build/mesa22; prints the manifest's path)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(realpath -m "${1:-build/mesa22}")
icd="$dir/lvp22.json"
if [ -f "$icd" ]; then echo "$icd"; exit 0; fi
# bookworm's version, not the backport's: the candidate of the archive's main suite.
version=$(apt-cache madison mesa-vulkan-drivers | awk -F'|' '$3 ~ /bookworm\/main|bookworm-updates\/main|bookworm-security/ && $3 !~ /backports/ {gsub(/ /, "", $2); print $2; exit}')
if [ -z "$version" ]; then
  echo "fetch_mesa22: error: no bookworm (non-backports) mesa-vulkan-drivers in apt's lists (run apt-get update)" >&2
  exit 2
fi
mkdir -p "$dir/debs" "$dir/root"
# apt warns when it downloads as root outside its sandbox user; the log keeps it for a failure.
(cd "$dir/debs" && apt-get download -q "mesa-vulkan-drivers=$version" >"$dir/download.log" 2>&1) ||
  { cat "$dir/download.log" >&2; exit 2; }
# lavapipe 22.3 links LLVM 15; Mesa 25 does not, so a machine that never had Mesa 22 lacks it.
if ! ldconfig -p | grep -q 'libLLVM-15.so.1'; then
  (cd "$dir/debs" && apt-get download -q libllvm15 >>"$dir/download.log" 2>&1) ||
    { cat "$dir/download.log" >&2; exit 2; }
fi
for deb in "$dir"/debs/*.deb; do dpkg-deb -x "$deb" "$dir/root"; done
lib="$dir/root/usr/lib/x86_64-linux-gnu/libvulkan_lvp.so"
[ -f "$lib" ] || { echo "fetch_mesa22: error: $lib is not in the package" >&2; exit 2; }
cat >"$icd" <<JSON
{
    "file_format_version": "1.0.0",
    "ICD": { "library_path": "$lib", "api_version": "1.3.230" }
}
JSON
echo "$icd"
