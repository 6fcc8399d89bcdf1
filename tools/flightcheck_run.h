/*
 * flightcheck_run.h - `stray flightcheck`'s input: a sweep folder of
 * flight frames (manifest.csv, FITS with DATE-OBS in UTC and EXPTIME)
 * and the AEM of the head, through the per-frame step of flightcheck.h.
 */
#ifndef STRAY_TOOLS_FLIGHTCHECK_RUN_H
#define STRAY_TOOLS_FLIGHTCHECK_RUN_H

#include <stddef.h>

#include "flightcheck.h"
#include "stray/aem.h"
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

/* As fc_run_dir with a real catalogue cat (NULL: the synthetic sky) and
 * its colour term (NULL: none). */
int fc_run_dir_sky(const char *dir, const struct stray_aem *aem,
		   const struct stray_sensor *s, const struct stray_fluxes *fl,
		   const struct stray_starcat *cat,
		   const struct stray_colour *colour, struct fc_cfg *cfg,
		   struct fc_frame **frames, size_t *n, struct stray_error *err);

#endif /* STRAY_TOOLS_FLIGHTCHECK_RUN_H */
