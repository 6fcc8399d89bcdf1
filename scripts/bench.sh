#!/usr/bin/env bash
# make bench: run every benchmark; each prints its figures as ratios
# against a baseline it measures in the same run (no wall-clock asserts),
# from alternating runs (baseline, figure, baseline, ...): the median of
# BENCH_PAIRS pairs (default 3) and its min-max, so a 20 % change can be
# told from the noise of a shared machine (bench/alt.sh, bench_alt.h).
# Usage: scripts/bench.sh BUILD_DIR BENCH...
set -eu
build=$1; shift
export STRAY_BUILD="$build" STRAY_BIN="$build/bin/stray"
export BENCH_PAIRS=${BENCH_PAIRS:-3}
start=$(date +%s)
for b in "$@"; do
	t0=$(date +%s)
	echo "== $b"
	"$b"
	echo "   ($(($(date +%s) - t0)) s)"
done
echo "== make bench: $(($(date +%s) - start)) s, $BENCH_PAIRS alternating pairs per figure"
