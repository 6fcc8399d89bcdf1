/*
 * curve.c - visits to the lens curve: alpha_lens = P(theta)/P(0)
 * (eq. 3.12), noise floor sigma(theta)/Pbar(0) (eq. 3.15), standard errors,
 * and a linear source drift fitted to the on-axis revisits.
 */
#include <math.h>
#include <string.h>

#include "stray/reduce_curve.h"

static int on_axis(const struct stray_visit *v)
{
	return fabs(v->theta_deg) <= STRAY_THETA_TOL_DEG;
}

/* P(0) as a line a + b (order - o_bar) by weighted least squares. */
struct p0_line {
	double a, b, o_bar, var_a, var_b;
};

static double weight(const struct stray_visit *v)
{
	return v->var_power > 0.0 ? 1.0 / v->var_power : 1.0;
}

/* The slope b and its variance (exact for any weights), given a, o_bar. */
static void fit_slope(const struct stray_visit *v, size_t n,
		      struct p0_line *f)
{
	double sxx = 0.0, sxp = 0.0;
	size_t i;

	for (i = 0; i < n; i++) {
		double x = v[i].order - f->o_bar;

		if (!on_axis(&v[i]))
			continue;
		sxx += weight(&v[i]) * x * x;
		sxp += weight(&v[i]) * x * v[i].power;
	}
	f->b = f->var_b = 0.0;
	if (!(sxx > 0.0))
		return;
	f->b = sxp / sxx;
	for (i = 0; i < n; i++) {
		double w = weight(&v[i]), x = v[i].order - f->o_bar;

		if (on_axis(&v[i]))
			f->var_b += w * w * x * x * v[i].var_power / (sxx * sxx);
	}
}

static int fit_p0(const struct stray_visit *v, size_t n, struct p0_line *f,
		  struct stray_drift *drift, struct stray_error *err)
{
	double sw = 0.0, swo = 0.0, swp = 0.0, swwv = 0.0;
	double o_min = HUGE_VAL, o_max = -HUGE_VAL;
	size_t i;

	memset(drift, 0, sizeof(*drift));
	for (i = 0; i < n; i++) {
		double w = weight(&v[i]);

		if (!on_axis(&v[i]))
			continue;
		/* The on-axis power must stand clear of its own noise: a
		 * sweep without source light (lamp off, beam blocked, a
		 * simulator's sky) otherwise normalises noise by noise and
		 * gives alpha > 1.  The value named is the power, not an
		 * angle. */
		if (!(v[i].power > 3.0 * sqrt(fmax(v[i].var_power, 0.0))))
			return stray_error_set_value(err, STRAY_EINVAL,
				"P(0)", "the on-axis visit's power (eq. 3.9, lit "
				"minus ambient frames) is not above 3 times its "
				"noise: no source light reached the camera at "
				"0 deg", v[i].power);
		sw += w;
		swo += w * v[i].order;
		swp += w * v[i].power;
		swwv += w * w * v[i].var_power;
		o_min = fmin(o_min, v[i].order);
		o_max = fmax(o_max, v[i].order);
		drift->n_ref++;
	}
	if (drift->n_ref == 0)
		return stray_error_set(err, STRAY_ENOTFOUND, "ANGLE",
				       "no on-axis (0 deg) visit to normalise by; "
				       "reduce the folder together with one that "
				       "has it (stray reduce A B)");
	f->o_bar = swo / sw;
	f->a = swp / sw;
	f->var_a = swwv / (sw * sw);	/* exact for any weights */
	drift->p0_rel_sigma = sqrt(f->var_a) / f->a;
	drift->p0 = f->a;
	f->b = f->var_b = 0.0;
	if (drift->n_ref < 2 || o_max == o_min)
		return STRAY_OK;	/* no span to see a drift over */
	fit_slope(v, n, f);
	drift->fitted = 1;
	drift->z = f->var_b > 0.0 ? f->b / sqrt(f->var_b) :
		   (f->b != 0.0 ? copysign(HUGE_VAL, f->b) : 0.0);
	drift->detected = fabs(drift->z) > STRAY_DRIFT_Z;
	drift->p0 = f->a + f->b * (o_min - f->o_bar);
	drift->rel_change = f->b * (o_max - o_min) / drift->p0;
	return STRAY_OK;
}

/*
 * eq. 3.12 with the drift line: alpha = P(theta) / P0(order).  By eq. 3.11,
 * P = F_src A_px abar_px n_ppi, so the ratio is the mean per-pixel
 * attenuation abar_px(theta) / abar_px(0) of eq. 3.10 (F_src, A_px and
 * n_ppi cancel), and eq. 3.7's J(theta) / J(0) summed over the image.
 */
static void visit_alpha(const struct stray_visit *v, const struct p0_line *f,
			double pbar0, double *alpha, double *var, double *nf)
{
	double x = v->order - f->o_bar;
	double p0 = f->a + f->b * x;
	double var_p0 = f->var_a + x * x * f->var_b;

	*alpha = v->power / p0;
	*var = (*alpha) * (*alpha) *
	       (v->var_power / (v->power * v->power + 1e-300) +
		var_p0 / (p0 * p0));
	if (on_axis(v))
		*var = 0.0;	/* alpha(0) = 1 by definition */
	*nf = v->sigma / pbar0;	/* eq. 3.15 (per-pixel scale, Pbar(0)) */
}

/* Index of the smallest theta above lo (or the smallest when !have_lo). */
static size_t next_angle(const struct stray_visit *v, size_t n, int have_lo,
			 double lo)
{
	size_t i, best = n;

	for (i = 0; i < n; i++) {
		if (have_lo && !(v[i].theta_deg > lo + STRAY_THETA_TOL_DEG))
			continue;
		if (best == n || v[i].theta_deg < v[best].theta_deg)
			best = i;
	}
	return best;
}

int stray_reduce_curve(const struct stray_visit *v, size_t n,
		       struct stray_curve_point *out, size_t *n_out,
		       struct stray_drift *drift, struct stray_error *err)
{
	struct p0_line f = { 0, 0, 0, 0, 0 };
	double pbar0;
	size_t k = 0, b;
	int rc;

	*n_out = 0;
	if ((rc = fit_p0(v, n, &f, drift, err)) != STRAY_OK)
		return rc;
	pbar0 = drift->p0 / (double)v[0].n_pix;	/* eq. 3.13 at theta = 0 */
	for (b = next_angle(v, n, 0, 0.0); b < n;
	     b = next_angle(v, n, 1, out[k - 1].theta_deg)) {
		struct stray_curve_point *p = &out[k++];
		double sw = 0.0, swa = 0.0, snf = 0.0;
		size_t i;

		p->theta_deg = v[b].theta_deg;
		p->n_visits = 0;
		for (i = 0; i < n; i++) {
			double a, var, nf, w;

			if (fabs(v[i].theta_deg - p->theta_deg) >
			    STRAY_THETA_TOL_DEG)
				continue;
			visit_alpha(&v[i], &f, pbar0, &a, &var, &nf);
			w = var > 0.0 ? 1.0 / var : 1.0;
			sw += w;
			swa += w * a;
			snf += nf;
			p->n_visits++;
		}
		/* alpha(0) = 1 by definition; revisits differ only by noise. */
		p->alpha = on_axis(&v[b]) ? 1.0 : swa / sw;
		p->sigma = on_axis(&v[b]) ? 0.0 : sqrt(1.0 / sw);
		p->noise_floor = snf / (double)p->n_visits;
	}
	*n_out = k;
	return STRAY_OK;
}
