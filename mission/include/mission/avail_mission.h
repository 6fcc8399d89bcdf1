/*
 * avail_mission.h - the pieces of `stray availability`: the demo mission
 * written as OEM/AEM, the heads file, the flight module flown per head,
 * the albedo fed to it, the statistics and the plots.
 */
#ifndef STRAY_MISSION_AVAIL_MISSION_H
#define STRAY_MISSION_AVAIL_MISSION_H

#include <stdint.h>

#include "fdrfw/fdrfw.h"
#include "stray/aem.h"
#include "stray/avail.h"
#include "stray/oem.h"

#define MISSION_HEADS_MAX 8	/* AVAIL_HEADS_MAX */

/* An epoch neither file covers (in a gap, stray_ccsds_gap_s): not flown,
 * not counted (stray_avail_summarise). */
#define MISSION_UNCOVERED STRAY_AVAIL_UNCOVERED
#define MISSION_SKY_MAX 3000	/* points per path in a sky plot */

struct mission_args {
	const char *oem, *aem, *heads, *csv, *plot;
	const char *write_oem, *write_aem;
	const char *iers;	/* IERS finals table for Earth-fixed frames */
	double step_s, hours, gen_step_s;
	int hours_given;
	int year, month, day;
	/* the mission --write-oem/--write-aem generates (any circular orbit) */
	double altitude_km, ltan_h, incl_deg;	/* incl_deg < 0: sun-synchronous */
	int attitude;				/* enum mission_attitude */
	int orbit_given, incl_given;
	/* --detector, --detector-sigma: every head's table must be built for
	 * it (NULL: each flies the detector its table carries) */
	const char *detector;
	double detector_sigma;
};

enum mission_attitude { MISSION_NADIR, MISSION_INERTIAL, MISSION_SUN };

struct mission_head {
	char name[32];
	double m_bs[3][3];		/* body -> head (rows: head axes) */
	struct fdrfw_table table;	/* its flight table; albedo fed per epoch */
	struct fdrfw_ctx ctx;
	int after_gap;			/* ctx to be started afresh */
	uint8_t *mask;			/* STRAY_AVAIL_* per epoch */
	float *stars;			/* predicted false stars per frame */
	double *sky[3][2];		/* Sun, Moon, Earth limb: x, y [deg] */
	struct stray_avail_stats st;
	double stars_mean, stars_max;
	/* libstray's verdict on the table's curve: 0 when the baffle never
	 * excludes the Sun (reason: why), whatever angle the table carries */
	int sun_excluded;
	const char *sun_reason;
};

struct mission {
	struct stray_oem oem;
	struct stray_aem aem;
	size_t n_heads, n, n_sky;
	struct mission_head head[MISSION_HEADS_MAX];
	double t0, step_s;		/* TT s since J2000 of the first frame */
	uint8_t *any_mask;		/* blind only where every head is */
	float *albedo;			/* fed to the Earth term, per epoch */
	struct stray_avail_stats any;
	char *oem_text, *aem_text;	/* --write-*: what was written */
	size_t oem_len, aem_len;
};

/* The mission of a (orbit and attitude) written to a->write_oem and a->write_aem, its text
 * kept in m->oem_text / aem_text for mission_load (the files themselves
 * are renamed into place only when the command succeeds). */
int mission_write_demo(const struct mission_args *a, struct mission *m,
		       struct stray_error *err);
int mission_load(const struct mission_args *a, struct mission *m,
		 struct stray_error *err);
int mission_fly(const struct mission_args *a, struct mission *m,
		struct stray_error *err);
void mission_free(struct mission *m);

/* The flight module's attitude quaternion (w, x, y, z), Hamilton,
 * v_s = R(q) v_i, of the inertial -> head matrix m (rows: head axes). */
void mission_fw_q(const double m[3][3], float q[4]);

/* Effective albedo of the sunlit cap seen from pos_km with the Sun along
 * sun (unit): the zonal albedo weighted as the module weights the cap's
 * light (cos of incidence times solid angle); 0.3 on the night side. */
double mission_cap_albedo(const float pos_km[3], const float sun[3]);

#endif /* STRAY_MISSION_AVAIL_MISSION_H */
