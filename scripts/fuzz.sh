#!/usr/bin/env bash
# A libFuzzer campaign on one fuzz target under ASan + UBSan:
#
#   bash scripts/fuzz.sh TARGET SECONDS [LIBFUZZER_FLAGS...]
#
# TARGET is NAME of tests/fuzz/fuzz_NAME.cpp (gltf, glb, sidecar, display_profile, calibration,
# volume_file, ...). Builds the libFuzzer binaries with clang 14 in build-fuzz/ (DDISH_FUZZ_BUILD;
# the first build compiles the non-Vulkan modules once more, minutes), then fuzzes for SECONDS
# at the lowest CPU priority, one process, starting from the seed corpus tests/fuzz/corpus/NAME/
# and the corpus earlier campaigns grew (build-fuzz/fuzz-corpus/NAME/). UBSan findings abort
# like ASan's; leaks are findings. A crashing input lands in build-fuzz/fuzz-artifacts/NAME/:
# fix the bug, then copy the input into tests/fuzz/corpus/NAME/ so that CTest replays it.
# Prints libFuzzer's final statistics (execs, corpus) and exits non-zero on a finding.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: bash scripts/fuzz.sh TARGET SECONDS [LIBFUZZER_FLAGS...]" >&2
  exit 2
fi
target=$1
seconds=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
build=${DDISH_FUZZ_BUILD:-$root/build-fuzz}
seeds=$root/tests/fuzz/corpus/$target
if [ ! -f "$root/tests/fuzz/fuzz_$target.cpp" ] || [ ! -d "$seeds" ]; then
  echo "fuzz.sh: no target '$target' (tests/fuzz/fuzz_$target.cpp and tests/fuzz/corpus/$target/)" >&2
  exit 2
fi
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER=clang++-14 -DDDISH_LIBFUZZER=ON -DDDISH_SANITIZE=ON \
    -DDDISH_BENCH=OFF -DDDISH_WERROR=OFF ${CCACHE_DIR:+-DCMAKE_CXX_COMPILER_LAUNCHER=ccache}
fi
nice -n 19 cmake --build "$build" --target "fuzz_$target" -j"${DDISH_FUZZ_JOBS:-2}"

work=$build/fuzz-corpus/$target
artifacts=$build/fuzz-artifacts/$target
mkdir -p "$work" "$artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:abort_on_error=1:print_stacktrace=1}
# 2 GB memory, 10 s per input: more is a finding (no few-KB input deserves either).
exec nice -n 19 "$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -rss_limit_mb=2048 \
  -malloc_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$artifacts/" \
  "$@" "$work" "$seeds"
