/*
 * ghost.c - internal reflections (thesis fig. 3.8-3.9, reflections "A"
 * and "B"): secondary maxima of the row-collapsed J profile per angle and
 * their tracks across angles.
 */
#include <math.h>
#include <string.h>

#include "stray/reduce_ghost.h"

void stray_ghost_opts_default(struct stray_ghost_opts *o)
{
	o->window = 41;
	o->min_z = 6.0;
	o->min_rel = 0.005;
	o->gate_cols = 6.0;
	o->min_points = 3;
}

size_t stray_ghost_scratch(size_t n_cols, const struct stray_ghost_opts *o)
{
	return 5 * n_cols + o->window + 1;
}

/* [1 2 2 2 1]/8: zero response at periods 2 and 4 (Bayer, channels). */
static void smooth(const double *p, const double *vp, size_t n, double *s,
		   double *vs)
{
	static const double w[5] = { 1, 2, 2, 2, 1 };
	size_t c;
	int k;

	for (c = 0; c < n; c++) {
		double a = 0.0, v = 0.0, sw = 0.0;

		for (k = -2; k <= 2; k++) {
			long i = (long)c + k;

			if (i < 0 || i >= (long)n)
				continue;
			a += w[k + 2] * p[i];
			v += w[k + 2] * w[k + 2] * vp[i];
			sw += w[k + 2];
		}
		s[c] = a / sw;
		vs[c] = v / (sw * sw);
	}
}

/*
 * Median of s[lo..hi] where !skip (insertion sort into buf) and the median
 * of those columns; NaN if fewer than 3 are left.
 */
static double band_median(const double *s, const double *skip, size_t lo,
			  size_t hi, double *buf, double *at)
{
	size_t k, i, m = 0, j = 0;
	double pos = 0.0;

	for (k = lo; k <= hi; k++) {
		double x = s[k];

		if (skip[k] != 0.0)
			continue;
		for (i = m; i > 0 && buf[i - 1] > x; i--)
			buf[i] = buf[i - 1];
		buf[i] = x;
		m++;
	}
	if (m < 3)
		return NAN;
	for (k = lo; k <= hi; k++) {	/* the middle kept column(s) */
		if (skip[k] != 0.0)
			continue;
		j++;
		if (j == (m + 1) / 2 || j == m / 2 + 1)
			pos += (double)k;
	}
	*at = m % 2 ? pos : 0.5 * pos;
	return m % 2 ? buf[m / 2] : 0.5 * (buf[m / 2 - 1] + buf[m / 2]);
}

/*
 * Background under column c: the straight line through the medians of two
 * side bands, [c-h, c-g] and [c+g, c+h] cut at the ends of the profile
 * (each placed at the median of its columns).  A straight gradient is
 * reproduced exactly, near the edges too; a bump narrower than the gap g
 * is left out of both bands, and so are columns marked in skip (peaks
 * already found).  Where a band has fewer than 3 columns, the profile
 * itself (no peak can be seen there).
 */
static double background(const double *s, const double *skip, size_t n,
			 size_t c, size_t h, size_t g, double *buf)
{
	double a, b, xa = 0.0, xb = 0.0;

	if (c < g + 2 || c + g + 2 >= n)
		return s[c];
	a = band_median(s, skip, c > h ? c - h : 0, c - g, buf, &xa);
	b = band_median(s, skip, c + g, c + h < n ? c + h : n - 1, buf, &xb);
	if (isnan(a) || isnan(b) || !(xb > xa))
		return s[c];
	return a + (b - a) * ((double)c - xa) / (xb - xa);
}

static int is_local_max(const double *r, size_t n, size_t c)
{
	size_t k;

	for (k = 1; k <= 3; k++) {
		if (c >= k && r[c - k] > r[c])
			return 0;
		if (c + k < n && r[c + k] >= r[c])
			return 0;
	}
	return 1;
}

/* Centroid and summed excess over the positive run of r around c. */
static void measure(const double *r, size_t n, size_t c, size_t half,
		    struct stray_ghost_peak *pk)
{
	size_t lo = c, hi = c, i;
	double sw = 0.0, swc = 0.0;

	while (lo > 0 && c - lo < half && r[lo - 1] > 0.0)
		lo--;
	while (hi + 1 < n && hi - c < half && r[hi + 1] > 0.0)
		hi++;
	for (i = lo; i <= hi; i++) {
		sw += r[i];
		swc += r[i] * (double)i;
	}
	pk->column = swc / sw;
	pk->excess = sw;
}

static void insert_peak(struct stray_ghost_peak *peaks, size_t *n,
			size_t max, const struct stray_ghost_peak *pk)
{
	size_t i;

	if (*n == max && !(pk->z > peaks[max - 1].z))
		return;
	i = *n < max ? (*n)++ : max - 1;
	for (; i > 0 && peaks[i - 1].z < pk->z; i--)
		peaks[i] = peaks[i - 1];
	peaks[i] = *pk;
}

/* Peaks of r above the thresholds, strongest first. */
static size_t scan(const double *r, const double *vs, const double *bg,
		   size_t n_cols, size_t g, const struct stray_ghost_opts *o,
		   struct stray_ghost_peak *peaks, size_t max_peaks)
{
	size_t c, n = 0;

	for (c = 2; c + 2 < n_cols; c++) {
		struct stray_ghost_peak pk;

		if (r[c] <= 0.0 || !is_local_max(r, n_cols, c))
			continue;
		pk.z = vs[c] > 0.0 ? r[c] / sqrt(vs[c]) : HUGE_VAL;
		if (pk.z < o->min_z || r[c] < o->min_rel * fabs(bg[c]))
			continue;
		measure(r, n_cols, c, g, &pk);
		insert_peak(peaks, &n, max_peaks, &pk);
	}
	return n;
}

size_t stray_ghost_find(const double *profile, const double *var_profile,
			size_t n_cols, const struct stray_ghost_opts *o,
			double *scratch, struct stray_ghost_peak *peaks,
			size_t max_peaks)
{
	double *s = scratch, *vs = s + n_cols, *bg = vs + n_cols;
	double *r = bg + n_cols, *skip = r + n_cols, *buf = skip + n_cols;
	size_t c, k, n, pass, h = o->window / 2, g = h / 3 > 2 ? h / 3 : 2;

	if (n_cols < 8 || max_peaks == 0)
		return 0;
	smooth(profile, var_profile, n_cols, s, vs);
	for (c = 0; c < n_cols; c++)
		skip[c] = 0.0;
	/* Twice: the second background leaves out the peaks found first,
	 * so a neighbouring ghost does not raise another's background. */
	for (pass = 0, n = 0; pass < 2; pass++) {
		for (c = 0; c < n_cols; c++) {
			bg[c] = background(s, skip, n_cols, c, h, g, buf);
			r[c] = s[c] - bg[c];
		}
		n = scan(r, vs, bg, n_cols, g, o, peaks, max_peaks);
		for (k = 0; k < n; k++)
			for (c = 0; c < n_cols; c++)
				if (fabs((double)c - peaks[k].column) < (double)g)
					skip[c] = 1.0;
	}
	return n;
}

void stray_ghost_tracker_init(struct stray_ghost_tracker *t,
			      const struct stray_ghost_opts *o,
			      struct stray_ghost_track *tracks,
			      size_t max_tracks)
{
	t->opts = *o;
	t->tracks = tracks;
	t->n_tracks = 0;
	t->max_tracks = max_tracks;
	t->step = 0;
	t->n_dropped = 0;
}

/* Column a track predicts at theta (its last motion continued). */
static double predict(const struct stray_ghost_track *k, double theta)
{
	const struct stray_ghost_point *a, *b;

	b = &k->pt[k->n - 1];
	if (k->n < 2)
		return b->column;
	a = &k->pt[k->n - 2];
	return b->column + (b->column - a->column) /
		(b->theta_deg - a->theta_deg) * (theta - b->theta_deg);
}

#define STRAY_GHOST_THETA_TOL 1e-6

static size_t best_track(const struct stray_ghost_tracker *t, double theta,
			 double column, const unsigned char *taken)
{
	size_t i, best = t->n_tracks;
	double best_d = t->opts.gate_cols;

	for (i = 0; i < t->n_tracks; i++) {
		const struct stray_ghost_track *k = &t->tracks[i];
		double d;

		/* Active: seen at the previous angle or the one before. */
		if (taken[i] || k->n == k->cap || t->step - k->last_step > 2)
			continue;
		d = fabs(column - predict(k, theta));
		if (d <= best_d) {
			best_d = d;
			best = i;
		}
	}
	return best;
}

void stray_ghost_tracker_add(struct stray_ghost_tracker *t, double theta_deg,
			     const struct stray_ghost_peak *peaks,
			     size_t n_peaks, double n_rows, double power)
{
	unsigned char taken[64] = { 0 };
	size_t i;

	t->step++;
	for (i = 0; i < n_peaks; i++) {	/* strongest first */
		size_t k = best_track(t, theta_deg, peaks[i].column, taken);
		struct stray_ghost_point pt;

		pt.theta_deg = theta_deg;
		pt.column = peaks[i].column;
		pt.excess = peaks[i].excess * n_rows;
		pt.power = power;
		if (k == t->n_tracks) {
			if (t->n_tracks == t->max_tracks || k >= 64) {
				t->n_dropped++;
				continue;
			}
			t->tracks[k].n = 0;
			t->n_tracks++;
		}
		taken[k] = 1;
		t->tracks[k].pt[t->tracks[k].n++] = pt;
		t->tracks[k].last_step = t->step;
	}
}

/* Max |residual| of the union of two tracks about its least-squares
 * line column = a + b theta, and whether their angles meet (overlap,
 * or a gap of at most two of their steps). */
static double union_residual(const struct stray_ghost_track *x,
			     const struct stray_ghost_track *y, int *meet)
{
	const struct stray_ghost_track *tr[2] = { x, y };
	double n = 0, st = 0, sc = 0, stt = 0, stc = 0, a, b, d, worst = 0;
	double step = HUGE_VAL, lo[2], hi[2];
	size_t k, i;

	for (k = 0; k < 2; k++) {
		lo[k] = tr[k]->pt[0].theta_deg;
		hi[k] = tr[k]->pt[tr[k]->n - 1].theta_deg;
		for (i = 0; i < tr[k]->n; i++) {
			double th = tr[k]->pt[i].theta_deg;
			double c = tr[k]->pt[i].column;

			n += 1;
			st += th;
			sc += c;
			stt += th * th;
			stc += th * c;
			if (i > 0 && th - tr[k]->pt[i - 1].theta_deg > 0)
				step = fmin(step, th -
					    tr[k]->pt[i - 1].theta_deg);
		}
	}
	if (!isfinite(step))
		step = 0;
	*meet = fmin(hi[0], hi[1]) >= fmax(lo[0], lo[1]) - 2.0 * step;
	d = n * stt - st * st;
	if (!(d > 0))
		return HUGE_VAL;
	b = (n * stc - st * sc) / d;
	a = (sc - b * st) / n;
	for (k = 0; k < 2; k++)
		for (i = 0; i < tr[k]->n; i++)
			worst = fmax(worst, fabs(tr[k]->pt[i].column - a -
						 b * tr[k]->pt[i].theta_deg));
	return worst;
}

/* y into x: points by increasing angle, the stronger kept where both
 * saw the ghost; 0 when x has no room. */
static int merge_into(struct stray_ghost_track *x,
		      const struct stray_ghost_track *y)
{
	struct stray_ghost_point tmp[256];
	size_t i = 0, j = 0, n = 0;

	while (i < x->n || j < y->n) {
		const struct stray_ghost_point *p;

		if (n == sizeof(tmp) / sizeof(tmp[0]))
			return 0;
		if (j >= y->n || (i < x->n && x->pt[i].theta_deg <
				  y->pt[j].theta_deg - STRAY_GHOST_THETA_TOL))
			p = &x->pt[i++];
		else if (i >= x->n || y->pt[j].theta_deg <
			 x->pt[i].theta_deg - STRAY_GHOST_THETA_TOL)
			p = &y->pt[j++];
		else	/* one angle: the stronger peak is the ghost */
			p = x->pt[i].excess >= y->pt[j].excess ? &x->pt[i++]
							       : &y->pt[j++];
		if (n > 0 && fabs(tmp[n - 1].theta_deg - p->theta_deg) <
		    STRAY_GHOST_THETA_TOL) {
			if (p->excess > tmp[n - 1].excess)
				tmp[n - 1] = *p;
			continue;
		}
		tmp[n++] = *p;
	}
	if (n > x->cap)
		return 0;
	memcpy(x->pt, tmp, n * sizeof(*tmp));
	x->n = n;
	if (y->last_step > x->last_step)
		x->last_step = y->last_step;
	return 1;
}

/*
 * One ghost, one track: a reflection whose profile peak splits in two at
 * some angles (6 px apart on the demo sweep) leaves tracks that hand
 * over or run side by side.  Two tracks whose angles meet and whose
 * points together lie within 1.5 gates of one straight line are one
 * ghost; two reflections crossing at different rates are not (their
 * union is far from any line).
 */
static void merge_tracks(struct stray_ghost_tracker *t)
{
	size_t i, j;
	int meet, again = 1;

	while (again) {
		again = 0;
		for (i = 0; i < t->n_tracks && !again; i++)
			for (j = i + 1; j < t->n_tracks && !again; j++) {
				struct stray_ghost_track tmp;

				if (union_residual(&t->tracks[i],
						   &t->tracks[j], &meet) >
				    1.5 * t->opts.gate_cols || !meet ||
				    !merge_into(&t->tracks[i], &t->tracks[j]))
					continue;
				/* j out, its array kept for the caller */
				tmp = t->tracks[j];
				t->tracks[j] = t->tracks[t->n_tracks - 1];
				t->tracks[t->n_tracks - 1] = tmp;
				t->tracks[t->n_tracks - 1].n = 0;
				t->n_tracks--;
				again = 1;
			}
	}
}

size_t stray_ghost_tracker_finish(struct stray_ghost_tracker *t)
{
	size_t i, kept = 0;

	merge_tracks(t);
	for (i = 0; i < t->n_tracks; i++) {
		if (t->tracks[i].n < t->opts.min_points)
			continue;
		if (kept != i) {	/* swap, so every array stays owned once */
			struct stray_ghost_track tmp = t->tracks[kept];

			t->tracks[kept] = t->tracks[i];
			t->tracks[i] = tmp;
		}
		kept++;
	}
	t->n_tracks = kept;
	return kept;
}
