/*
 * frames_io.c - FITS frames out, and a focal map's weights as regions
 * (frames_io.h).
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
