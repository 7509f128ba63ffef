#!/usr/bin/env bash
# The soak run (issue 15), outside the report: a long `ddish render` of the animated Cornell box
# with the budget scheduler on and an image every 100th frame; checks that resident memory, open
# file descriptors and Vulkan allocations stay flat after the warm-up and that the frame time has
# no upward trend (scripts/results/soak.py says how). The report's section 6 runs the same.
#
#   bash bench/soak.sh [--frames N] [--size WxH] [--budget-ms MS] [--every N] [--build DIR] [--out DIR]
#
# Defaults: 10000 frames, 128x128, 30 ms, every 100th frame, build/. Exit 0: flat and no trend;
# 1: something grew or trends upward; 2: the run failed.
set -euo pipefail
exec python3 "$(cd "$(dirname "$0")/.." && pwd)/scripts/results/soak.py" "$@"
