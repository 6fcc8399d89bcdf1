/*
 * table_build.h - the ground side of the flight table (host only): build
 * it from a curve, a sensor and the reference fluxes with libstray, and
 * write it as C source.  `stray firmware-table` is the command for it.
 */
#ifndef FDRFW_TABLE_BUILD_H
#define FDRFW_TABLE_BUILD_H

#include <stdio.h>

#include "fdrfw/table.h"
#include "stray/curve.h"
#include "stray/detector.h"
#include "stray/error.h"
#include "stray/sensor.h"

struct fdrfw_build_params {
	double f_sun_ph_s_m2;		/* reference fluxes (photometry) */
	double f_moon_full_ph_s_m2;
	double f_drs_ph_s_m2;
	double rate;			/* tolerated FDR; <= 0: the sensor's */
	double hysteresis_deg;
	double earth_albedo;
	/* k_px of eq. 2.3 (docs/normalisation.md); zero: consistent. */
	enum stray_normalisation normalisation;
	/* The tracker's detector (issue 28); zero: thesis, eq. 2.18 on
	 * board as before.  detector_sigma: tetra3's k (<= 0: 3). */
	enum stray_detector_kind detector;
	double detector_sigma;
};

/* Defaults: hysteresis 0.5 deg, albedo 0.3, the sensor's rate. */
#define FDRFW_BUILD_HYSTERESIS_DEG 0.5
#define FDRFW_BUILD_ALBEDO 0.3

/*
 * Fill and seal a table: I_sdt (eq. 2.16), the Sun's alpha_req (fig. 2.7)
 * and exclusion angle (fig. 5.1) by libstray's one verdict
 * (stray_exclusion_interval); the curve as log10 alpha.  A Sun the baffle
 * does not exclude (the curve reaches alpha_req only at the geometric zero
 * of the aperture plane) is carried as the first traced angle in or beyond
 * that plane (90 deg for a curve traced to 90): the Sun is in the
 * exclusion zone wherever it is in front of the tracker.  A curve that
 * ends above the Sun's alpha_req has no angle the module could accept:
 * refused (STRAY_EINVAL).
 */
int fdrfw_table_build(const struct stray_curve_view *curve,
		      const struct stray_sensor *sensor,
		      const struct fdrfw_build_params *p,
		      struct fdrfw_table *t, struct stray_error *err);

/* The same, with the Sun's verdict (sun->excluded, reason) when sun is
 * not NULL: what `stray firmware-table` reports beside the table. */
int fdrfw_table_build_verdict(const struct stray_curve_view *curve,
			      const struct stray_sensor *sensor,
			      const struct fdrfw_build_params *p,
			      struct fdrfw_table *t,
			      struct stray_exclusion *sun,
			      struct stray_error *err);

/*
 * A curve longer than the table's FDRFW_CURVE_MAX rows thinned to them
 * (curve_thin.c): the ends kept, and the two samples around the last fall
 * below each of keep_crossings (an alpha_req: the exclusion angle then
 * comes out of the same two samples as from the whole curve), then
 * greedily the sample the kept ones interpolate worst in log10 alpha, as
 * the module interpolates; *out views theta_deg/alpha (FDRFW_CURVE_MAX
 * each, the caller's) or, for a curve that fits, is *in itself.  r says
 * what was left out.
 */
struct fdrfw_thin_report {
	size_t rows_in, rows_out;
	double max_err_dex;	/* largest |log10 alpha| error left */
	double at_deg;		/* where (NaN: nothing left out) */
};
int fdrfw_curve_thin(const struct stray_curve_view *in,
		     const double *keep_crossings, size_t n_keep,
		     double *theta_deg, double *alpha,
		     struct stray_curve_view *out, struct fdrfw_thin_report *r,
		     struct stray_error *err);

/* The table of `stray firmware-table` (curve_thin.c): fdrfw_table_build_
 * verdict on the curve thinned to the table's rows, keeping the samples
 * around the Sun's crossing so the table's Sun angle is the whole
 * curve's; thin says what was left out. */
int fdrfw_table_build_thinned(const struct stray_curve_view *curve,
			      const struct stray_sensor *sensor,
			      const struct fdrfw_build_params *p,
			      struct fdrfw_table *t, struct stray_exclusion *sun,
			      struct fdrfw_thin_report *thin,
			      struct stray_error *err);

/*
 * libstray's verdict on a sealed table's own curve and Sun alpha_req (a
 * table from before the verdict may carry 89.98 deg for a Sun the baffle
 * never excludes): what `stray availability` reports per head.
 */
int fdrfw_table_sun_verdict(const struct fdrfw_table *t,
			    struct stray_exclusion *sun,
			    struct stray_error *err);

/* The word of the table a status of fdrfw_table_check or fdrfw_init
 * refuses (FDRFW_EFIELD_OF), -1 for any other status; its name, or NULL. */
#define FDRFW_FIELD_OF(rc) (((rc) >= FDRFW_EFIELD && \
	(rc) < FDRFW_EFIELD_WORD(FDRFW_TABLE_WORDS)) ? \
	(rc) - FDRFW_EFIELD : -1)
const char *fdrfw_field_name(int word);

/* The detector grid's nodes: FDRFW_DET_PER_DECADE a decade of I_px, the
 * Sun's binding background on node FDRFW_DET_BELOW (5 decades above node
 * 0, where the light is negligible; the last node is past every
 * requirement). */
#define FDRFW_DET_PER_DECADE 8
#define FDRFW_DET_BELOW 40

/*
 * The named detector in the table (det_grid.c): its setup for the
 * sensor's model m (the camera's read noise and dark current added, into
 * *g), and the grid of both its failure modes over the background, the
 * Sun's binding alpha_req on node FDRFW_DET_BELOW.
 */
int fdrfw_det_setup(const struct stray_sensor *s,
		    const struct fdrfw_build_params *p,
		    const struct stray_fdr_model *m, struct stray_detector *d,
		    struct stray_fdr_model *g, struct stray_error *err);
int fdrfw_det_grid_fill(const struct stray_detector *d,
			const struct stray_fdr_model *g, double alpha_req,
			struct fdrfw_table *t, struct stray_error *err);

/* The attenuation of a source of flux f_src at grid node i. */
double fdrfw_det_node_alpha(const struct fdrfw_table *t, double f_src,
			    int i);

/* The failure mode that sets the table's Sun angle (thesis: false
 * stars); the table's detector by name ("unknown" outside the enum). */
enum stray_failure_mode fdrfw_table_binding(const struct fdrfw_table *t);
const char *fdrfw_table_detector_name(const struct fdrfw_table *t);

/*
 * A table read for detector kind (tetra3: at k = sigma) that was built
 * for another: STRAY_EINVAL naming the file, field "detector" and the
 * table's detector, and how to rebuild it.
 */
int fdrfw_table_detector_check(const struct fdrfw_table *t,
			       enum stray_detector_kind kind, double sigma,
			       const char *path, struct stray_error *err);

/* The table as C source: `const struct fdrfw_table NAME = {...};`. */
int fdrfw_table_write_c(FILE *out, const struct fdrfw_table *t,
			const char *name);

#endif /* FDRFW_TABLE_BUILD_H */
