/*
 * dark.c - the dark model D(t_exp) per Bayer read channel (thesis §3.2,
 * eq. 3.3: the dark depends on exposure time only) from a sigma-clipped
 * channel mean of each dark frame.
 */
#include <math.h>
#include <string.h>

#include "stray/reduce_dark.h"

void stray_dark_init(struct stray_dark_model *m,
		     const struct stray_bayer_map *map)
{
	memset(m, 0, sizeof(*m));
	m->map = *map;
}

static int same_t(double a, double b)
{
	return fabs(a - b) <= STRAY_DARK_T_REL_TOL * fmax(fabs(a), fabs(b));
}

int stray_dark_find(const struct stray_dark_model *m, double t_exp_s,
		    size_t *index, struct stray_error *err)
{
	size_t i;

	for (i = 0; i < m->n; i++)
		if (same_t(m->lvl[i].t_exp_s, t_exp_s)) {
			*index = i;
			return STRAY_OK;
		}
	return stray_error_set_value(err, STRAY_ENOTFOUND, "EXPTIME",
		"no dark frame at this exposure time", t_exp_s);
}

/* Smallest v with sum_{x<=v} h[x] >= k (k >= 1). */
static unsigned hist_rank(const uint32_t *h, double k)
{
	double cum = 0.0;
	unsigned v;

	for (v = 0; v < 65535u; v++) {
		cum += h[v];
		if (cum >= k)
			break;
	}
	return v;
}

/* Median absolute deviation about med, from the histogram. */
static unsigned hist_mad(const uint32_t *h, unsigned med, double n)
{
	double cum = h[med];
	unsigned d = 0;

	while (cum < 0.5 * n && d < 65535u) {
		d++;
		if (med >= d)
			cum += h[med - d];
		if (med + d < 65536u)
			cum += h[med + d];
	}
	return d;
}

/* Clipped mean and variance of one channel's histogram. */
static void clipped_stats(const uint32_t *h, double n, double *mean,
			  double *var, double *n_used)
{
	unsigned med = hist_rank(h, 0.5 * n);
	double width = STRAY_DARK_CLIP_SIGMA * 1.4826 * hist_mad(h, med, n);
	double lo, hi, s0 = 0.0, s1 = 0.0, s2 = 0.0;
	unsigned v, v_lo, v_hi;

	if (width < 1.0)
		width = 1.0;	/* integer counts: keep the median's bins */
	lo = med - width;
	hi = med + width;
	v_lo = lo < 0.0 ? 0u : (unsigned)ceil(lo);
	v_hi = hi > 65535.0 ? 65535u : (unsigned)floor(hi);
	for (v = v_lo; v <= v_hi; v++) {
		double c = h[v], x = (double)v - med;

		s0 += c;
		s1 += c * x;
		s2 += c * x * x;
	}
	*n_used = s0;
	*mean = med + s1 / s0;
	*var = s0 > 1.0 ? (s2 - s1 * s1 / s0) / (s0 - 1.0) : 0.0;
}

static int level_for(struct stray_dark_model *m, double t_exp_s, size_t *i,
		     struct stray_error *err)
{
	if (stray_dark_find(m, t_exp_s, i, NULL) == STRAY_OK)
		return STRAY_OK;
	if (m->n == STRAY_DARK_LEVELS_MAX)
		return stray_error_set_value(err, STRAY_ERANGE, "EXPTIME",
			"too many distinct dark exposure times", t_exp_s);
	*i = m->n++;
	memset(&m->lvl[*i], 0, sizeof(m->lvl[*i]));
	m->lvl[*i].t_exp_s = t_exp_s;
	return STRAY_OK;
}

int stray_dark_add(struct stray_dark_model *m, const struct stray_frame *f,
		   uint32_t *hist, struct stray_error *err)
{
	double n_ch[STRAY_BAYER_CHANNELS] = { 0 };
	struct stray_dark_level *l;
	size_t r, c, li;
	unsigned ch;
	int rc;

	if ((rc = stray_frame_check(f, err)) != STRAY_OK ||
	    (rc = level_for(m, f->t_exp_s, &li, err)) != STRAY_OK)
		return rc;
	memset(hist, 0, STRAY_DARK_HIST_LEN * sizeof(*hist));
	for (r = 0; r < f->n_rows; r++) {
		const uint16_t *row = f->pix + r * f->n_cols;
		uint32_t *h[4];
		unsigned ph[4], k;

		for (k = 0; k < 4; k++) {	/* the channel repeats every 4 */
			ph[k] = stray_bayer_channel(&m->map, f->det_row[r],
						    f->col0 + (long)k);
			h[k] = hist + ph[k] * 65536u;
			/* every column is one read of its channel */
			n_ch[ph[k]] += (double)((f->n_cols + 3 - k) / 4);
		}
		for (c = 0; c + 4 <= f->n_cols; c += 4) {
			h[0][row[c]]++;
			h[1][row[c + 1]]++;
			h[2][row[c + 2]]++;
			h[3][row[c + 3]]++;
		}
		for (; c < f->n_cols; c++)
			h[c & 3][row[c]]++;
	}
	l = &m->lvl[li];
	for (ch = 0; ch < STRAY_BAYER_CHANNELS; ch++) {
		double mean, var, used;

		if (n_ch[ch] == 0.0)
			continue;	/* a row-sampled frame may miss a channel */
		clipped_stats(hist + ch * 65536u, n_ch[ch], &mean, &var, &used);
		l->sum[ch] += mean;
		l->var_sum[ch] += var;
		l->n_pix[ch] += used;
	}
	l->n_frames++;
	return STRAY_OK;
}

void stray_dark_finish(struct stray_dark_model *m)
{
	size_t i;
	unsigned ch;

	for (i = 0; i < m->n; i++) {
		struct stray_dark_level *l = &m->lvl[i];

		for (ch = 0; ch < STRAY_BAYER_CHANNELS; ch++) {
			if (l->n_pix[ch] == 0.0)
				continue;
			l->mean[ch] = l->sum[ch] / (double)l->n_frames;
			l->var[ch] = l->var_sum[ch] / (double)l->n_frames;
			/* Conservative: the spatial pattern counts as noise. */
			l->var_mean[ch] = l->var[ch] / l->n_pix[ch];
		}
	}
}
