/*
 * frames_io.c - FITS frames out and focal-plane maps in (frames_io.h).
 */
#include <fitsio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "frames_io.h"
#include "stray/errfmt.h"

static int fits_fail(struct stray_error *err, int code, const char *path,
		     int status)
{
	char text[FLEN_STATUS];

	fits_get_errstatus(status, text);
	return stray_error_at(err, code, path, 0, 0, text);
}

static void write_keys(fitsfile *f, const struct frames_fits_meta *m,
		       int *st)
{
	double nd = 1.0, a = m->theta_deg, t = m->t_exp_s, al = m->alpha;
	double k = m->k_px, se = m->stray_e;
	int seq = m->seqnum, c0 = m->col0, r0 = m->row0, sat = m->sat_dn;
	long ns = (long)m->n_stars;
	char type[] = "FULL", src[] = "synthetic", norm[32];

	snprintf(norm, sizeof(norm), "%s", m->normalisation);
	fits_write_key(f, TSTRING, "FRAMETYP", type, "rendered: source on", st);
	fits_write_key(f, TDOUBLE, "ANGLE", &a, "[deg] source off boresight", st);
	fits_write_key(f, TDOUBLE, "EXPTIME", &t, "[s] exposure time", st);
	fits_write_key(f, TDOUBLE, "NDTRANS", &nd, "no ND filter", st);
	fits_write_key(f, TINT, "SEQNUM", &seq, "frame index", st);
	fits_write_key(f, TINT, "COL0", &c0, "detector column of pixel 1", st);
	fits_write_key(f, TINT, "ROW0", &r0, "detector row of pixel 1", st);
	fits_write_key(f, TINT, "SATLEVEL", &sat, "[DN] saturation", st);
	fits_write_key(f, TDOUBLE, "ALPHA", &al, "system attenuation", st);
	fits_write_key(f, TDOUBLE, "KPX", &k, "k_px = A_cs/(n_px A_px)", st);
	fits_write_key(f, TSTRING, "NORM", norm, "normalisation of eq. 2.3", st);
	fits_write_key(f, TDOUBLE, "STRAYE", &se, "[e-] mean stray per pixel", st);
	fits_write_key(f, TSTRING, "STARSRC", src, "star field: no catalogue", st);
	fits_write_key(f, TLONG, "NSTARS", &ns, "stars rendered", st);
}

int frames_fits_write(const char *path, const uint16_t *dn, int cols,
		      int rows, const struct frames_fits_meta *m,
		      struct stray_error *err)
{
	fitsfile *f;
	long naxes[2] = { cols, rows };
	char name[4096];
	int st = 0;

	snprintf(name, sizeof(name), "!%s", path);	/* '!': overwrite */
	fits_create_file(&f, name, &st);
	if (st)
		return fits_fail(err, STRAY_EIO, path, st);
	fits_create_img(f, USHORT_IMG, 2, naxes, &st);
	write_keys(f, m, &st);
	fits_write_img(f, TUSHORT, 1, (LONGLONG)cols * rows, (void *)dn, &st);
	{
		int st2 = 0;

		fits_close_file(f, &st2);
		if (!st)
			st = st2;
	}
	return st ? fits_fail(err, STRAY_EIO, path, st) : STRAY_OK;
}

static int read_image(const char *path, float **img, long *nx, long *ny,
		      struct stray_error *err)
{
	fitsfile *f;
	long ax[2] = { 0, 0 };
	int st = 0, naxis = 0, any = 0;

	fits_open_file(&f, path, READONLY, &st);
	if (st)
		return fits_fail(err, STRAY_ENOTFOUND, path, st);
	fits_get_img_dim(f, &naxis, &st);
	fits_get_img_size(f, 2, ax, &st);
	if (!st && (naxis != 2 || ax[0] < 1 || ax[1] < 1)) {
		fits_close_file(f, &st);
		return stray_error_at(err, STRAY_EPARSE, path, 0, "NAXIS",
				      "the map must be a 2-D image");
	}
	*img = st ? NULL : malloc((size_t)ax[0] * ax[1] * sizeof(float));
	if (!st && !*img) {
		fits_close_file(f, &st);
		return stray_error_at(err, STRAY_ENOMEM, path, 0, 0, "no memory");
	}
	if (!st)
		fits_read_img(f, TFLOAT, 1, (LONGLONG)ax[0] * ax[1], NULL, *img,
			      &any, &st);
	{
		int st2 = 0;

		fits_close_file(f, &st2);
	}
	if (st) {
		free(*img);
		return fits_fail(err, STRAY_EPARSE, path, st);
	}
	*nx = ax[0];
	*ny = ax[1];
	return STRAY_OK;
}

/* A detector pixel's position in map cells, measured between cell
 * centres (a map samples a smooth distribution: bilinear, not steps),
 * extrapolated linearly past the outer centres (half a cell). */
static double cell_coord(int px, int det, long n)
{
	return (px + 0.5) * (double)n / det - 0.5;
}

/* The cell left of (below) f, so that f lies in [i, i + 1] inside. */
static long cell_base(double f, long n)
{
	long i = (long)floor(f);

	return n < 2 ? 0 : i < 0 ? 0 : i > n - 2 ? n - 2 : i;
}

int frames_map_read(const char *path, int det_x, int det_y, int col0,
		    int row0, int cols, int rows, float *weight,
		    struct stray_error *err)
{
	float *img = NULL;
	long nx = 0, ny = 0, i;
	double sum = 0.0, mean;
	int rc = read_image(path, &img, &nx, &ny, err), x, y;

	if (rc != STRAY_OK)
		return rc;
	for (i = 0; i < nx * ny; i++) {
		if (!(isfinite(img[i]) && img[i] >= 0.0f)) {
			free(img);
			return stray_error_at(err, STRAY_EINVAL, path, 0, "pixel",
					      "map values must be finite and >= 0");
		}
		sum += img[i];
	}
	mean = sum / ((double)nx * ny);
	if (!(mean > 0.0)) {
		free(img);
		return stray_error_at(err, STRAY_EINVAL, path, 0, "MEAN",
				      "the map carries no light");
	}
	for (y = 0; y < rows; y++) {
		double fy = cell_coord(row0 + y, det_y, ny);
		long y0 = cell_base(fy, ny), y1 = ny > 1 ? y0 + 1 : y0;

		fy -= (double)y0;
		for (x = 0; x < cols; x++) {
			double fx = cell_coord(col0 + x, det_x, nx), top, bot, v;
			long x0 = cell_base(fx, nx), x1 = nx > 1 ? x0 + 1 : x0;

			fx -= (double)x0;
			top = img[y0 * nx + x0] + fx * (img[y0 * nx + x1] - img[y0 * nx + x0]);
			bot = img[y1 * nx + x0] + fx * (img[y1 * nx + x1] - img[y1 * nx + x0]);
			v = (top + fy * (bot - top)) / mean;
			weight[(size_t)y * cols + x] = (float)(v > 0.0 ? v : 0.0);
		}
	}
	free(img);
	return STRAY_OK;
}

void frames_map_regions(const float *weight, size_t n,
			struct stray_region_map *map)
{
	enum { NB = STRAY_MAP_REGIONS_MAX };
	double lo = INFINITY, hi = -INFINITY, cnt[NB], sum[NB];
	size_t i;
	int b, k = 0;

	memset(cnt, 0, sizeof(cnt));
	memset(sum, 0, sizeof(sum));
	for (i = 0; i < n; i++) {
		lo = fmin(lo, weight[i]);
		hi = fmax(hi, weight[i]);
	}
	for (i = 0; i < n; i++) {
		b = hi > lo ? (int)((weight[i] - lo) / (hi - lo) * NB) : 0;
		b = b >= NB ? NB - 1 : b;
		cnt[b] += 1.0;
		sum[b] += weight[i];
	}
	for (b = 0; b < NB; b++)
		if (cnt[b] > 0.0) {
			map->fraction[k] = cnt[b] / (double)n;
			map->rel_alpha[k] = sum[b] / cnt[b];
			k++;
		}
	map->n = (unsigned)k;
}
