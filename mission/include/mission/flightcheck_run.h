/*
 * flightcheck_run.h - `stray flightcheck`'s input: a sweep folder of
 * flight frames (manifest.csv, FITS with DATE-OBS in UTC and EXPTIME)
 * and the AEM of the head, through the per-frame step of flightcheck.h.
 */
#ifndef STRAY_MISSION_FLIGHTCHECK_RUN_H
#define STRAY_MISSION_FLIGHTCHECK_RUN_H

#include <stddef.h>

#include "mission/flightcheck.h"
#include "stray/aem.h"
#include "stray/oem.h"
#include "stray/error.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

/*
 * Analyse every FULL frame of dir; *frames (malloc'd, *n of them) in
 * manifest order.  The first frame fixes the size and the window's place
 * (COL0, ROW0); errors name the file and keyword.
 */
int fc_run_dir(const char *dir, const struct stray_aem *aem,
	       const struct stray_sensor *s, const struct stray_fluxes *fl,
	       struct fc_cfg *cfg, struct fc_frame **frames, size_t *n,
	       struct stray_error *err);

/* What the sky holds besides the frames (issue 24): a real catalogue
 * and its colour term (NULL: the synthetic sky, no colours), the orbit
 * (NULL: the Moon seen from the Earth's centre, no Earth limb), and the
 * Moon and Earth-limb offset angles under which a frame is screened out
 * of the scale fit. */
struct fc_sky {
	const struct stray_starcat *cat;
	const struct stray_colour *colour;
	const struct stray_oem *oem;
	double moon_min_deg, limb_min_deg;
	char *const *files;	/* frame files instead of the folder, or NULL */
	size_t n_files;
};

#define FC_MOON_MIN_DEG 25.0
#define FC_LIMB_MIN_DEG 30.0

/* As fc_run_dir under sky. */
int fc_run_dir_sky(const char *dir, const struct stray_aem *aem,
		   const struct stray_sensor *s, const struct stray_fluxes *fl,
		   const struct fc_sky *sky, struct fc_cfg *cfg,
		   struct fc_frame **frames, size_t *n, struct stray_error *err);

#endif /* STRAY_MISSION_FLIGHTCHECK_RUN_H */
