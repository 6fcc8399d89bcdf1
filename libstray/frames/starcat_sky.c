/*
 * starcat_sky.c - a real catalogue's file, its stars at an epoch and in
 * a cone (stray/starcat.h).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/starcat.h"
#include "stray/file.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define MAS (DEG / 3.6e6)

const char *stray_starcat_kind_name(int kind)
{
	switch (kind) {
	case STRAY_STARCAT_HIP2: return "hip2";
	case STRAY_STARCAT_HIP1: return "hip_main";
	case STRAY_STARCAT_BSC5: return "bsc5";
	case STRAY_STARCAT_CSV: return "csv";
	default: return "none";
	}
}

double stray_jyear_of_tt(double t_tt_s)
{
	return 2000.0 + t_tt_s / (365.25 * 86400.0);
}

int stray_starcat_load(const char *path, struct stray_starcat *c,
		       struct stray_error *err)
{
	/* the toolkit's whole-file read: no folder or device, a size limit */
	char *buf = NULL;
	size_t len = 0;
	int rc = stray_file_read(path, &buf, &len, err);

	memset(c, 0, sizeof(*c));
	if (rc == STRAY_OK)
		rc = stray_starcat_parse(buf, len, path, c, err);
	free(buf);
	return rc;
}

/* The unit vector of s at epoch: the catalogue place moved along its
 * tangent plane by the proper motion (the space motion's radial part and
 * the light-time are left out: < 0.1" over a century for these stars). */
static void place(const struct stray_starcat_star *s, double epoch,
		  double u[3])
{
	double ra = s->ra_deg * DEG, de = s->dec_deg * DEG;
	double dt = epoch - s->epoch_jyear, n;
	double e_ra[3] = { -sin(ra), cos(ra), 0.0 };
	double e_de[3] = { -sin(de) * cos(ra), -sin(de) * sin(ra), cos(de) };
	double a = s->pmra_mas_yr * MAS * dt, d = s->pmdec_mas_yr * MAS * dt;
	int i;

	u[0] = cos(de) * cos(ra);
	u[1] = cos(de) * sin(ra);
	u[2] = sin(de);
	for (i = 0; i < 3; i++)
		u[i] += a * e_ra[i] + d * e_de[i];
	n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
	for (i = 0; i < 3; i++)
		u[i] /= n;
}

size_t stray_starcat_cone(const struct stray_starcat *c, double epoch_jyear,
			  const double dir[3], double radius_deg,
			  double mag_max, struct stray_cat_star *out,
			  size_t max, size_t *n)
{
	/* a star moves < 20"/yr: a margin of 0.1 deg per century searched */
	double cos_r = cos(fmin(180.0, radius_deg) * DEG);
	size_t i, found = 0;

	*n = 0;
	for (i = 0; i < c->n; i++) {
		const struct stray_starcat_star *s = &c->s[i];
		double u[3];

		if (!(s->v_mag < mag_max))
			continue;
		place(s, epoch_jyear, u);
		if (u[0] * dir[0] + u[1] * dir[1] + u[2] * dir[2] < cos_r)
			continue;
		found++;
		if (*n < max) {
			struct stray_cat_star *o = &out[(*n)++];

			o->ra_deg = atan2(u[1], u[0]) / DEG;
			if (o->ra_deg < 0.0)
				o->ra_deg += 360.0;
			o->dec_deg = asin(fmax(-1.0, fmin(1.0, u[2]))) / DEG;
			o->mag = s->v_mag;
			o->b_v = s->b_v;
			o->colour = 1.0;
			memcpy(o->u, u, sizeof(u));
		}
	}
	return found;
}
