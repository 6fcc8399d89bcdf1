#!/usr/bin/env bash
# make bench: run every benchmark binary; each prints its figures as ratios
# against a baseline it measures in the same run (no wall-clock asserts).
# Usage: scripts/bench.sh BUILD_DIR BENCH...
set -eu
build=$1; shift
export STRAY_BUILD="$build" STRAY_BIN="$build/bin/stray"
for b in "$@"; do
	echo "== $b"
	"$b"
done
