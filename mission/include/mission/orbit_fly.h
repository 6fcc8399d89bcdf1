/*
 * orbit_fly.h - `stray orbit` as one call: the flight module (fdrfw.h)
 * flown along a day of a circular sun-synchronous orbit (J2 nodal
 * regression), boresight at the zenith, one fdrfw_frame call per step;
 * the timeline of angles, false stars and flags per frame.  The command
 * (tools/cmd_orbit.c) writes, plots and summarises it.
 */
#ifndef STRAY_MISSION_ORBIT_FLY_H
#define STRAY_MISSION_ORBIT_FLY_H

#include <stddef.h>
#include <stdint.h>

#include "fdrfw/fdrfw.h"
#include "stray/error.h"

struct orbit_fly_opts {
	int year, month, day;	/* the day (UTC) the orbit starts at noon */
	double hours, step_s;	/* how long, and the frame step */
	double altitude_km, ltan_h;	/* the orbit; LTAN in hours */
};

/* One row per frame. */
struct orbit_run {
	size_t n;
	double *t_h, *theta[FDRFW_BODIES], *stars;
	uint32_t *flags;
};

/* Fly table t along the orbit of o into run (free with orbit_run_free);
 * STRAY_ENOMEM naming the frames when the timeline does not fit. */
int orbit_fly(const struct orbit_fly_opts *o, const struct fdrfw_table *t,
	      struct orbit_run *run, struct stray_error *err);

void orbit_run_free(struct orbit_run *run);

#endif /* STRAY_MISSION_ORBIT_FLY_H */
