/*
 * avail_demo.c - the mission of `stray availability --write-oem
 * --write-aem`: a circular orbit (any altitude; sun-synchronous with an
 * LTAN, or any inclination) and an attitude (nadir pointing with yaw
 * steering, inertial, or Sun-pointing), written as OEM and AEM and kept
 * in memory for the same run.  The defaults are the demo's mission:
 * 550 km, sun-synchronous, LTAN 22:30, nadir with yaw steering.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mission/avail_mission.h"
#include "fdrfw/ephem.h"
#include "mission/orbit.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "vec3d.h"

#define OMEGA_EARTH 7.2921159e-5	/* rad/s, IERS */

/*
 * Nadir pointing with yaw steering: body +z to nadir, +x along the ground
 * track (the orbital velocity less the Earth's rotation under it), the
 * yaw angle psi = atan2(w_E sin i cos u, n - w_E cos i).
 */
static void nadir_yaw_m(const struct orbit *o, double ts, const double r[3],
			const double v[3], double m[3][3])
{
	double x0[3], y0[3], h[3], u = o->n_rad_s * ts, psi;
	int k;

	psi = atan2(OMEGA_EARTH * sin(o->incl_rad) * cos(u),
		    o->n_rad_s - OMEGA_EARTH * cos(o->incl_rad));
	cross(r, v, h);
	for (k = 0; k < 3; k++) {
		m[2][k] = -r[k];
		y0[k] = -h[k];
	}
	unit(m[2]);
	unit(y0);
	cross(y0, m[2], x0);
	for (k = 0; k < 3; k++) {
		m[0][k] = cos(psi) * x0[k] + sin(psi) * y0[k];
		m[1][k] = -sin(psi) * x0[k] + cos(psi) * y0[k];
	}
}

/* Sun-pointing: body +z to the Sun, +x in the equatorial plane (north x
 * Sun; the vernal equinox when the Sun is at a pole of the sky). */
static void sun_pointing_m(const float sun[3], double m[3][3])
{
	static const double north[3] = { 0, 0, 1 };
	int k;

	for (k = 0; k < 3; k++)
		m[2][k] = sun[k];
	unit(m[2]);
	cross(north, m[2], m[0]);
	if (m[0][0] * m[0][0] + m[0][1] * m[0][1] + m[0][2] * m[0][2] < 1e-12)
		m[0][0] = 1, m[0][1] = m[0][2] = 0;
	unit(m[0]);
	cross(m[2], m[0], m[1]);
}

/* Text made in memory by write(f), then kept there for the run that
 * flies it and written to path (atomically, with the command's other
 * outputs): what is flown is what was written, in one run. */
static int make_text(const char *path, char **text, size_t *len,
		     int (*write)(FILE *f, const void *ctx), const void *ctx,
		     struct stray_error *err)
{
	struct stray_file_out fo;
	FILE *mem = open_memstream(text, len);
	int rc;

	if (!mem)
		return stray_error_set(err, STRAY_ENOMEM, "mission text", NULL);
	rc = write(mem, ctx);
	if (fclose(mem) != 0 && rc == STRAY_OK)
		rc = stray_error_set(err, STRAY_ENOMEM, "mission text", NULL);
	if (rc != STRAY_OK)
		return rc == STRAY_ENOMEM ? rc :
		       stray_error_at(err, rc, path, 0, 0, "could not be made");
	if ((rc = stray_file_open_atomic(&fo, path, err)) != STRAY_OK)
		return rc;
	if (fwrite(*text, 1, *len, fo.f) != *len) {
		int e = errno;

		stray_file_abort(&fo);
		return stray_error_at(err, STRAY_EIO, path, 0, 0,
				      e ? strerror(e) : "write failed");
	}
	return stray_file_commit(&fo, err);
}

struct demo {
	double *t, (*r)[3], (*v)[3], (*q)[4];
	size_t n;
};

static int write_oem(FILE *f, const void *ctx)
{
	const struct demo *d = ctx;

	return stray_oem_write(f, "STRAY-DEMO", STRAY_TS_UTC, d->t,
			       (const double (*)[3])d->r,
			       (const double (*)[3])d->v, d->n,
			       STRAY_INTERP_HERMITE, 7);
}

static int write_aem(FILE *f, const void *ctx)
{
	const struct demo *d = ctx;

	return stray_aem_write(f, "STRAY-DEMO", STRAY_TS_UTC, d->t,
			       (const double (*)[4])d->q, d->n);
}

int mission_write_demo(const struct mission_args *a, struct mission *m,
		       struct stray_error *err)
{
	struct orbit orb;
	struct demo d;
	char date[40];
	double t0, m0[3][3], mm[3][3];
	float sun[3];
	size_t i;
	int rc;

	d.n = (size_t)(a->hours * 3600.0 / a->gen_step_s) + 1;
	snprintf(date, sizeof(date), "%04d-%02d-%02dT00:00:00", a->year,
		 a->month, a->day);
	if (stray_ccsds_epoch(date, STRAY_TS_UTC, &t0) != 0)
		return stray_error_at(err, STRAY_EINVAL, NULL, 0, "epoch",
				      "not a calendar date");
	d.t = malloc(d.n * sizeof(*d.t));
	d.r = malloc(d.n * sizeof(*d.r));
	d.v = malloc(d.n * sizeof(*d.v));
	d.q = malloc(d.n * sizeof(*d.q));
	if (!d.t || !d.r || !d.v || !d.q) {
		free(d.t), free(d.r), free(d.v), free(d.q);
		return stray_error_set(err, STRAY_ENOMEM, "records", NULL);
	}
	fdrfw_sun_dir((int32_t)lround(t0), sun);
	if (a->incl_deg < 0.0)
		orbit_sso(&orb, a->altitude_km, a->ltan_h, atan2(sun[1], sun[0]));
	else
		orbit_inclined(&orb, a->altitude_km, a->incl_deg, a->ltan_h,
			       atan2(sun[1], sun[0]));
	for (i = 0; i < d.n; i++) {
		double ts = (double)i * a->gen_step_s;

		d.t[i] = t0 + ts;
		orbit_state(&orb, ts, d.r[i], d.v[i]);
		if (a->attitude == MISSION_SUN) {
			fdrfw_sun_dir((int32_t)lround(d.t[i]), sun);
			sun_pointing_m(sun, mm);
		} else {
			nadir_yaw_m(&orb, ts, d.r[i], d.v[i], mm);
			/* inertial: the epoch's nadir attitude, held */
			if (i == 0)
				memcpy(m0, mm, sizeof(m0));
			if (a->attitude == MISSION_INERTIAL)
				memcpy(mm, m0, sizeof(m0));
		}
		stray_dcm_q(mm, d.q[i]);
	}
	rc = make_text(a->write_oem, &m->oem_text, &m->oem_len, write_oem, &d,
		       err);
	if (rc == STRAY_OK)
		rc = make_text(a->write_aem, &m->aem_text, &m->aem_len,
			       write_aem, &d, err);
	free(d.t), free(d.r), free(d.v), free(d.q);
	return rc;
}
