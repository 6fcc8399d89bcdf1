#!/usr/bin/env bash
# alt.sh - sourced by the shell benches: alternating runs and their
# spread.  On a shared 2-core machine one-shot ratios move by 1.5x; a
# ratio taken from runs made side by side (A, B, A, B, ...) sees the same
# load on both sides, and the median of >= 3 such pairs with its min-max
# tells a 20 % change from noise.  BENCH_PAIRS (default 3) sets the pairs.
pairs=${BENCH_PAIRS:-3}
{ [ "$pairs" -ge 1 ] && [ "$pairs" -le 32 ]; } 2>/dev/null ||
	{ echo "BENCH_PAIRS: give a count from 1 to 32, not '$pairs'" >&2; exit 2; }

# spread V...: "median min max" of the values (median of an even count:
# the mean of the middle two).
spread() {
	printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END {
		m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
		printf "%.4g %.4g %.4g\n", m, v[1], v[NR] }'
}

# ratios A_LIST B_LIST: the per-pair ratios a_i / b_i (space-separated
# lists of the same length, pair i run side by side).
ratios() {
	awk -v a="$1" -v b="$2" 'BEGIN { n = split(a, x, " "); split(b, y, " ");
		for (i = 1; i <= n; i++) printf "%.6g ", x[i] / y[i] }'
}

# show LABEL A_LIST B_LIST: one line, the median ratio a/b and its
# min-max over the pairs, e.g. "label  1.93 x  (1.71-2.05, 3 pairs)".
show() {
	local m lo hi
	# shellcheck disable=SC2046
	read -r m lo hi < <(spread $(ratios "$2" "$3"))
	printf '%-52s %7.3f  (%.3f-%.3f, %d pairs)\n' "$1" "$m" "$lo" "$hi" \
		"$(echo $2 | wc -w)"
}
