/*
 * focal.c - the focal-plane stray-light map: image points through an
 * ideal lens, and the map from the integrator's per-cell sums (focal.h).
 */
#include <stdlib.h>

#include "tracer/focal.h"

size_t tracer_focal_slots(const struct tracer_focal *fp)
{
	return (size_t)fp->nx * (size_t)fp->ny + 1;
}

int tracer_focal_check(const struct tracer_focal *fp,
		       struct stray_error *err)
{
	if (!(fp->f_mm > 0.0) || !isfinite(fp->f_mm))
		return stray_error_set_value(err, STRAY_EINVAL, "focal_mm",
					     "must be positive", fp->f_mm);
	if (!(fp->half_w_mm > 0.0 && fp->half_h_mm > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "focal.size_mm",
					     "must be positive", fp->half_w_mm);
	if (fp->nx < 1 || fp->ny < 1 || fp->nx > 4096 || fp->ny > 4096)
		return stray_error_set_value(err, STRAY_EINVAL, "focal.cells",
					     "must be 1 to 4096 a side",
					     fp->nx < 1 ? fp->nx : fp->ny);
	return STRAY_OK;
}

bool tracer_focal_point(const struct tracer_focal *fp, const struct frame *f,
			struct vec3 w, double *x_mm, double *y_mm)
{
	double wn = v3_dot(w, f->n);

	if (!(wn > 0.0))
		return false;
	/* ideal lens: x = f tan, un-inverted (tracer/README.md) */
	*x_mm = fp->f_mm * v3_dot(w, f->s) / wn;
	*y_mm = fp->f_mm * v3_dot(w, f->t) / wn;
	return true;
}

size_t tracer_focal_cell(const struct tracer_focal *fp, const struct frame *f,
			 struct vec3 w)
{
	size_t outside = (size_t)fp->nx * (size_t)fp->ny;
	double x, y, u, v;

	if (!tracer_focal_point(fp, f, w, &x, &y))
		return outside;
	u = (x / fp->half_w_mm + 1.0) * 0.5 * fp->nx;
	v = (y / fp->half_h_mm + 1.0) * 0.5 * fp->ny;
	if (!(u >= 0.0 && v >= 0.0 && u < fp->nx && v < fp->ny))
		return outside;
	return (size_t)v * (size_t)fp->nx + (size_t)u;
}

struct ranked {
	double d2;
	size_t cell;
};

static int cmp_ranked(const void *a, const void *b)
{
	const struct ranked *p = a, *q = b;

	if (p->d2 != q->d2)
		return p->d2 < q->d2 ? -1 : 1;
	return (p->cell > q->cell) - (p->cell < q->cell);
}

/* Level (over the mean) of quantile u of the region map, dark first. */
static double region_level(const struct tracer_focal_spread *sp, double u)
{
	double cum = 0.0;
	size_t r;

	for (r = 0; r + 1 < sp->n; r++) {
		cum += sp->fraction[r];
		if (u < cum)
			break;
	}
	return sp->rel_alpha[r];
}

/*
 * Per-cell weights of the outside slot, summing to 1: the region map's
 * levels by rank of distance to the source's image point (nearest
 * brightest), or 1 / n_cells each.
 */
static int spread_weights(const struct tracer_focal *fp,
			  const struct tracer_focal_spread *sp, double *w,
			  struct stray_error *err)
{
	size_t n = (size_t)fp->nx * fp->ny, k;
	struct ranked *rk;
	double sum = 0.0;

	if (!sp || sp->n == 0) {
		for (k = 0; k < n; k++)
			w[k] = 1.0 / (double)n;
		return STRAY_OK;
	}
	rk = malloc(n * sizeof(*rk));
	if (!rk)
		return stray_error_set(err, STRAY_ENOMEM, "focal map",
				       "out of memory");
	for (k = 0; k < n; k++) {
		double x = fp->half_w_mm * (2.0 * ((k % fp->nx) + 0.5) /
					    fp->nx - 1.0);
		double y = fp->half_h_mm * (2.0 * ((k / fp->nx) + 0.5) /
					    fp->ny - 1.0);

		rk[k].d2 = (x - sp->src_x_mm) * (x - sp->src_x_mm) +
			   (y - sp->src_y_mm) * (y - sp->src_y_mm);
		rk[k].cell = k;
	}
	qsort(rk, n, sizeof(*rk), cmp_ranked);
	for (k = 0; k < n; k++) {
		/* the nearest cell takes the top quantile */
		double u = 1.0 - ((double)k + 0.5) / (double)n;

		w[rk[k].cell] = region_level(sp, u);
		sum += w[rk[k].cell];
	}
	free(rk);
	if (!(sum > 0.0))
		return stray_error_set(err, STRAY_EINVAL, "lens map",
				       "levels sum to zero");
	for (k = 0; k < n; k++)
		w[k] /= sum;	/* the spread conserves the power exactly */
	return STRAY_OK;
}

int tracer_focal_finish(const struct tracer_focal *fp, const double *sums,
			double p0, double a_cs_mm2,
			const struct tracer_focal_spread *sp, double *map,
			double *in_field, struct stray_error *err)
{
	size_t n = (size_t)fp->nx * fp->ny, k;
	double a_cell = 4.0 * fp->half_w_mm * fp->half_h_mm / (double)n;
	double total = sums[n], scale;
	int rc;

	if (!(p0 > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "P(0)",
			"must be positive to normalise the focal map", p0);
	rc = spread_weights(fp, sp, map, err);
	if (rc)
		return rc;
	/* P_c / P(0) * A_cs / A_cell: per-pixel E_px / E_src with
	 * P(0) = E_src A_cs (issue 13: k_px = A_cs / (n_px A_px)) */
	scale = a_cs_mm2 / (p0 * a_cell);
	for (k = 0; k < n; k++) {
		double p = sums[k] + sums[n] * map[k];

		total += sums[k];
		map[k] = p * scale;
	}
	*in_field = total > 0.0 ? (total - sums[n]) / total : 0.0;
	return STRAY_OK;
}
