#!/usr/bin/env bash
# The README's first command, run small and read as a reader would: the
# demo with few rays, its report opened in headless Chromium, every figure
# loaded, no section empty.  `make demo-check`, and one job of the test
# pool in `make test` (tests/run-tests.sh).  Usage: scripts/demo-check.sh [BUILD_DIR]
set -euo pipefail
b=${1:-${STRAY_BUILD:-build}}
echo "== make demo (small), then its report in headless Chromium"
DEMO_RAYS=300000 DEMO_STEP_DEG=5 DEMO_FRAMES=256 scripts/demo.sh "$b" "$b/demo-check" \
	>"$b/demo-check.log" 2>&1 || { tail -n 30 "$b/demo-check.log"; exit 1; }
scripts/check-report.sh "$b/demo-check" --complete
