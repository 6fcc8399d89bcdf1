/*
 * ccsds_gap.c - the gap rule of the OEM and AEM readers: interpolation
 * never crosses a gap in the records longer than its window, so a
 * message with a 13 h hole is not bridged by a polynomial or a SLERP.
 */
#include <stdlib.h>

#include "stray/ccsds.h"

static int by_value(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

double stray_ccsds_gap_s(const double *t, size_t n, size_t nodes)
{
	double *d, med;
	size_t i, span = nodes > 3 ? nodes - 1 : 2;

	if (n < 2)
		return 0.0;
	d = malloc((n - 1) * sizeof(*d));
	if (!d)
		return -1.0;
	for (i = 0; i + 1 < n; i++)
		d[i] = t[i + 1] - t[i];
	qsort(d, n - 1, sizeof(*d), by_value);
	med = d[(n - 1) / 2];
	free(d);
	/* the window's nominal span, and never below two steps (a record
	 * missing here and there is not a gap) */
	return (double)span * med;
}

size_t stray_ccsds_gaps(const double *t, size_t n, double gap_s)
{
	size_t i, k = 0;

	for (i = 0; i + 1 < n; i++)
		k += t[i + 1] - t[i] > gap_s;
	return k;
}

int stray_ccsds_piece(const double *t, size_t n, double gap_s, double at,
		      size_t reach, size_t *lo, size_t *hi)
{
	size_t a = 0, b = n - 1, a0, b0;

	if (n < 1 || !(at >= t[0] && at <= t[n - 1]))
		return -1;
	while (b - a > 1) {	/* t[a] <= at <= t[b] */
		size_t mid = a + (b - a) / 2;

		if (t[mid] <= at)
			a = mid;
		else
			b = mid;
	}
	if (n > 1 && t[b] - t[a] > gap_s) {	/* at in a gap, or on its ends */
		if (at == t[b])
			a = b;
		else if (at == t[a])
			b = a;
		else
			return -1;
	}
	/* widen while the steps are no gap, at most `reach` records */
	a0 = a;
	b0 = b;
	while (a > 0 && a0 - a < reach && t[a] - t[a - 1] <= gap_s)
		a--;
	while (b + 1 < n && b - b0 < reach && t[b + 1] - t[b] <= gap_s)
		b++;
	*lo = a;
	*hi = b;
	return 0;
}
