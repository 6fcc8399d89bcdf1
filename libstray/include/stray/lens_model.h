/*
 * lens_model.h - lens curves for a team without lab data (hosted; issue
 * 23 item 3): an ideal lens, and the point-source transmittance (PST) a
 * lens's stray-light analysis in optical-design software exports.
 *
 * A lens curve is alpha_lens(theta) = P_det(theta) / P_det(0) for a
 * collimated source at field angle theta (docs/formats.md), the curve
 * `stray reduce` measures in the lab (thesis §3.4.4) and `--lens` takes.
 */
#ifndef STRAY_LENS_MODEL_H
#define STRAY_LENS_MODEL_H

#include "stray/curve_io.h"
#include "stray/error.h"

/*
 * The ideal lens of field half-angle field_half_deg: the relative
 * illumination of a distortion-free lens, cos^4(theta) (natural
 * vignetting: the pupil's projected area, the inverse square and the
 * obliquity at the focal plane, each cos theta or cos^2), inside the
 * field; 0 beyond it - no ghosts, no scatter in the lens, no mechanical
 * vignetting.  Rows every 0.25 deg, the field edge itself and a step to 0
 * 0.001 deg beyond it, then 90 deg.  field_half_deg in (0, 80].
 */
int stray_lens_ideal(double field_half_deg, struct stray_curve *out,
		     struct stray_error *err);

/* How the PST's input irradiance was taken (which cosine it holds). */
enum stray_pst_input {
	STRAY_PST_BEAM,		/* across the beam (FRED, ASAP, Zemax NSC) */
	STRAY_PST_APERTURE	/* in the entrance-aperture plane */
};

/*
 * A PST table (CSV, `#` comments; columns theta_col and pst_col) to a
 * lens curve: PST(theta) = E_det(theta) / E_in(theta).  With E_in across
 * the beam the power into the aperture falls as cos theta, as the
 * tracer's beam does, so alpha = PST(theta) / PST(0); with E_in in the
 * aperture plane (already times cos theta), alpha = PST(theta) cos theta
 * / PST(0).  A row at theta = 0 with PST > 0 is required; angles in
 * [0, 90), strictly increasing; PST >= 0.
 */
int stray_lens_from_pst(const char *path, const char *theta_col,
			const char *pst_col, enum stray_pst_input input,
			struct stray_curve *out, struct stray_error *err);

#endif /* STRAY_LENS_MODEL_H */
