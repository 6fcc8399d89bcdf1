/*
 * bench_alt.h - alternating runs for the C benches.  On a shared 2-core
 * machine a one-shot ratio moves by 1.5x; a ratio of two figures taken
 * side by side (A, B, A, B, ...) sees the same load on both, and the
 * median of >= 3 pairs with its min-max tells a 20 % change from noise.
 * BENCH_PAIRS (environment, default 3) sets the number of pairs.
 */
#ifndef BENCH_ALT_H
#define BENCH_ALT_H

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define BENCH_MAX_PAIRS 32

static inline double bench_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* BENCH_PAIRS, 1..BENCH_MAX_PAIRS (default 3); anything else ends the
 * bench with one line and status 2, as alt.sh does. */
static inline int bench_pairs(void)
{
	const char *s = getenv("BENCH_PAIRS");
	char *end = NULL;
	long n = s ? strtol(s, &end, 10) : 3;

	if (s && (end == s || *end || n < 1 || n > BENCH_MAX_PAIRS)) {
		fprintf(stderr, "BENCH_PAIRS: give a count from 1 to %d, not "
			"'%s'\n", BENCH_MAX_PAIRS, s);
		exit(2);
	}
	return (int)n;
}

static inline int bench_cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* Median, min and max of v[0..n-1] (n >= 1; v is sorted in place). */
static inline double bench_median(double *v, int n, double *lo, double *hi)
{
	qsort(v, (size_t)n, sizeof(*v), bench_cmp);
	*lo = v[0];
	*hi = v[n - 1];
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The ratios a[i] / b[i] of n pairs: prints label, the median in
 * width.prec, and "(lo-hi, n pairs)"; returns the median. */
static inline double bench_ratio(const char *label, const double *a,
				  const double *b, int n, int width, int prec)
{
	double r[BENCH_MAX_PAIRS], lo, hi, m;
	int i;

	for (i = 0; i < n; i++)
		r[i] = a[i] / b[i];
	m = bench_median(r, n, &lo, &hi);
	printf("%s%*.*f  (%.*f-%.*f, %d pairs)\n", label, width, prec, m,
	       prec, lo, prec, hi, n);
	return m;
}

#endif
