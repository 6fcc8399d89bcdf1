/*
 * orbit_fly.c - `stray orbit`'s work (orbit_fly.h): the flight module
 * flown frame by frame along a circular sun-synchronous orbit (orbit.c),
 * the tracker's boresight at the zenith, with the module's own Sun and
 * Moon ephemeris, as on board.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdrfw/ephem.h"
#include "mission/orbit.h"
#include "mission/orbit_fly.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"

static int run_alloc(struct orbit_run *r, size_t n)
{
	int b;

	memset(r, 0, sizeof(*r));
	r->n = n;
	r->t_h = calloc(n, sizeof(double));
	r->stars = calloc(n, sizeof(double));
	r->flags = calloc(n, sizeof(uint32_t));
	for (b = 0; b < FDRFW_BODIES; b++)
		r->theta[b] = calloc(n, sizeof(double));
	return r->t_h && r->stars && r->flags && r->theta[0] && r->theta[1] &&
	       r->theta[2];
}

void orbit_run_free(struct orbit_run *r)
{
	int b;

	free(r->t_h);
	free(r->stars);
	free(r->flags);
	for (b = 0; b < FDRFW_BODIES; b++)
		free(r->theta[b]);
}

/* Fly the orbit: one fdrfw_frame call per step, as on board. */
static void fly(const struct orbit_fly_opts *a, const struct fdrfw_table *t,
		struct orbit_run *run)
{
	struct fdrfw_ctx ctx;
	struct orbit orb;
	float sun[3];
	long day0 = stray_ccsds_days_from_2000(a->year, a->month, a->day);
	int32_t t0 = (int32_t)(day0 * 86400L - 43200L);
	size_t i;

	fdrfw_init(&ctx, t);
	fdrfw_sun_dir(t0, sun);
	orbit_sso(&orb, a->altitude_km, a->ltan_h, atan2(sun[1], sun[0]));
	for (i = 0; i < run->n; i++) {
		struct fdrfw_input in = { .t_exp_s = t->t_exp_nominal_s };
		struct fdrfw_output out;
		double ts = i * a->step_s, r[3], v[3], q[4];
		int k;

		orbit_state(&orb, ts, r, v);
		orbit_anti_nadir_q(r, v, q);
		for (k = 0; k < 4; k++)
			in.q[k] = (float)q[k];
		for (k = 0; k < 3; k++)
			in.pos_km[k] = (float)r[k];
		in.t_tt_s = t0 + (int32_t)ts;
		fdrfw_frame(&ctx, &in, &out);
		run->t_h[i] = ts / 3600.0;
		for (k = 0; k < FDRFW_BODIES; k++)
			run->theta[k][i] = out.theta_deg[k];
		run->stars[i] = out.false_stars_total;
		run->flags[i] = out.flags;
	}
}

int orbit_fly(const struct orbit_fly_opts *o, const struct fdrfw_table *t,
	      struct orbit_run *run, struct stray_error *err)
{
	if (!run_alloc(run, (size_t)(o->hours * 3600.0 / o->step_s) + 1)) {
		orbit_run_free(run);
		return stray_error_set(err, STRAY_ENOMEM, "frames", 0);
	}
	fly(o, t, run);
	return STRAY_OK;
}
