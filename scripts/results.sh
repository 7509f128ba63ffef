#!/usr/bin/env bash
# Regenerates the measured results report: docs/RESULTS.md, docs/results/*.csv and *.png.
#
#   bash scripts/results.sh [--quick] [--out DIR]
#
# --quick: tiny sizes, the Cornell box only (the test suite's smoke test; under a minute).
# --out DIR: write DIR/RESULTS.md and DIR/results/ instead of docs/ (the smoke test uses this).
# Environment: DDISH_BUILD_DIR (default build/) holds the built ddish and bench binaries; this
# script builds nothing. DDISH_SCENES (default ../shared/scenes beside the checkout) holds the
# Sponza and Breakfast-room scenes (skipped with a message when absent). DDISH_RESULTS_CACHE
# (default BUILD/results-cache) keeps the high-spp reference images between runs.
# Progress goes to stderr; the work is done by scripts/results/run.py (Python 3 standard library).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if ! command -v python3 >/dev/null 2>&1; then
  echo "results.sh: error: python3 is required (scripts/bootstrap.sh installs it)" >&2
  exit 2
fi
exec python3 "$here/results/run.py" "$@"
