/*
 * catalogue.c - the procedural synthetic catalogue and the ideal camera
 * (stray/catalogue.h).
 */
#include <math.h>

#include "stray/catalogue.h"
#include "rng.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define DEPTH 10.5		/* every cell is drawn to this magnitude */
#define BANDS 180		/* 1 deg in Dec */

static int band_cells(int b)
{
	double dc = (-90.0 + b + 0.5) * DEG;
	int n = (int)lround(360.0 * cos(dc));

	return n < 1 ? 1 : n;
}

static void unit(double ra, double dec, double u[3])
{
	u[0] = cos(dec) * cos(ra);
	u[1] = cos(dec) * sin(ra);
	u[2] = sin(dec);
}

/* The stars of cell (b, j), kept when within cos_r of dir. */
static size_t cell_stars(uint64_t seed, int b, int j, int nj,
			 const double dir[3], double cos_r, double mag_max,
			 struct stray_cat_star *out, size_t max, size_t *n)
{
	struct stray_frame_rng r;
	double s_lo = sin((-90.0 + b) * DEG), s_hi = sin((-89.0 + b) * DEG);
	double w = 2.0 * PI / nj, area_deg2, n_lo, n_hi, n_all, mean;
	size_t k, i, found = 0;

	area_deg2 = (s_hi - s_lo) * w / (DEG * DEG);
	n_lo = stray_star_counts_per_deg2(STRAY_CATALOGUE_MAG_MIN);
	/* The cell's full list is drawn to a fixed depth so that a
	 * fainter mag_max only adds stars, never moves the bright ones. */
	n_all = stray_star_counts_per_deg2(DEPTH);
	n_hi = stray_star_counts_per_deg2(mag_max < DEPTH ? mag_max : DEPTH);
	mean = (n_all - n_lo) * area_deg2;
	stray_frame_rng_init(&r, stray_frame_seed(seed, (uint64_t)b * 4096u +
						  (uint64_t)j));
	k = (size_t)stray_frame_rng_poisson(&r, mean);
	for (i = 0; i < k; i++) {
		double u1 = stray_frame_rng_uniform(&r);
		double u2 = stray_frame_rng_uniform(&r);
		double u3 = stray_frame_rng_uniform(&r);
		double nm = n_lo + u3 * (n_all - n_lo), ra, dec, v[3];

		if (nm > n_hi)
			continue;
		ra = (j + u1) * w;
		dec = asin(s_lo + u2 * (s_hi - s_lo));
		unit(ra, dec, v);
		if (v[0] * dir[0] + v[1] * dir[1] + v[2] * dir[2] < cos_r)
			continue;
		found++;
		if (*n < max) {
			struct stray_cat_star *s = &out[(*n)++];

			s->ra_deg = ra / DEG;
			s->dec_deg = dec / DEG;
			/* inverse of N(<m) = 0.121 10^(0.44 (m - 6)) */
			s->mag = 6.0 + log10(nm / 0.121) / 0.44;
			s->u[0] = v[0];
			s->u[1] = v[1];
			s->u[2] = v[2];
			s->b_v = 0.0;
			s->colour = 1.0;
		}
	}
	return found;
}

size_t stray_catalogue_cone(uint64_t seed, const double dir[3],
			    double radius_deg, double mag_max,
			    struct stray_cat_star *out, size_t max,
			    size_t *n)
{
	double dec0 = asin(fmax(-1.0, fmin(1.0, dir[2]))) / DEG;
	double ra0 = atan2(dir[1], dir[0]), cos_r = cos(radius_deg * DEG);
	size_t found = 0;
	int b;

	*n = 0;
	for (b = 0; b < BANDS; b++) {
		double lo = -90.0 + b, hi = lo + 1.0, dmax, half;
		int nj = band_cells(b), j, j0, j1;

		if (hi < dec0 - radius_deg - 1e-9 ||
		    lo > dec0 + radius_deg + 1e-9)
			continue;
		dmax = fmax(fabs(lo), fabs(hi));
		if (dmax + radius_deg >= 89.0 || fabs(dec0) + radius_deg >= 89.0) {
			j0 = 0;
			j1 = nj - 1;
		} else {
			/* RA half-width of the cone at the band's widest */
			half = asin(fmin(1.0, sin(radius_deg * DEG) /
					 cos(dmax * DEG)));
			j0 = (int)floor((ra0 - half) / (2.0 * PI / nj)) - 1;
			j1 = (int)floor((ra0 + half) / (2.0 * PI / nj)) + 1;
			if (j1 - j0 + 1 >= nj) {
				j0 = 0;
				j1 = nj - 1;
			}
		}
		for (j = j0; j <= j1; j++) {
			int jj = ((j % nj) + nj) % nj;

			found += cell_stars(seed, b, jj, nj, dir, cos_r, mag_max,
					    out, max, n);
		}
	}
	return found;
}

int stray_camera_project(const struct stray_camera *c, const double u[3],
			 double *x, double *y)
{
	double v[3];
	int i;

	for (i = 0; i < 3; i++)
		v[i] = c->m_ih[i][0] * u[0] + c->m_ih[i][1] * u[1] +
		       c->m_ih[i][2] * u[2];
	if (v[2] <= 1e-6)
		return 0;
	*x = c->cx + c->f_px * v[0] / v[2];
	*y = c->cy + c->f_px * v[1] / v[2];
	return 1;
}

size_t stray_camera_stars(const struct stray_camera *c,
			  const struct stray_cat_star *cat, size_t n_cat,
			  int cols, int rows, double margin, double f0_e,
			  struct stray_star *out, size_t max)
{
	size_t i, n = 0;

	for (i = 0; i < n_cat && n < max; i++) {
		double x, y;

		if (!stray_camera_project(c, cat[i].u, &x, &y))
			continue;
		if (x < -margin || y < -margin || x > cols + margin ||
		    y > rows + margin)
			continue;
		out[n].x = x;
		out[n].y = y;
		out[n].mag = cat[i].mag;
		out[n].photons_e = f0_e * pow(10.0, -0.4 * cat[i].mag) *
				   cat[i].colour;
		n++;
	}
	return n;
}
