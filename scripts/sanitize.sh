#!/usr/bin/env bash
# The whole suite built with AddressSanitizer and UBSan in a second build folder (build-asan),
# GPU tests on lavapipe included. Leak reports inside the Mesa/LLVM and Vulkan loader libraries
# are suppressed (.ci/sanitizers/lsan.supp names the frames each line covers); everything in
# ddish's own code, and every ASan error (not only leaks) and every UBSan report, fails its test.
# The `window` suite (tests/window: SDL2 windows on a private Xvfb, screenshots with xwd, keys
# with xdotool, ddish run as a child process) runs too; SDL's D-Bus helper's one leak is
# suppressed by name like the others.
# Usage: bash scripts/sanitize.sh [ctest arguments, e.g. -L "gpu|raster"]
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
# Warnings are not fatal here: the normal build (.ci/run's first part) already fails on any
# warning, and GCC 12's instrumented -O3 build raises false positives of its own (seen in <regex>).
cmake -S . -B build-asan -G Ninja -DDDISH_SANITIZE=ON -DDDISH_BENCH=OFF -DDDISH_WERROR=OFF
cmake --build build-asan -j2
t1=$(date +%s)
sup=$PWD/.ci/sanitizers
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=0 \
LSAN_OPTIONS=suppressions=$sup/lsan.supp:print_suppressions=0 \
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build-asan -j2 --output-on-failure "$@"
t2=$(date +%s)
echo "sanitize: build $((t1 - t0)) s, suite $((t2 - t1)) s"
