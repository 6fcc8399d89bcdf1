/*
 * diag_result.h - the whole diagnosis as data: what the simulation gets
 * wrong against a measured curve, which registered causes explain it,
 * the gain and the Sun exclusion angle before and after.  Presentation
 * (text, JSON, plots) is the caller's (tools/diag_report.h).
 */
#ifndef DIAGNOSE_DIAG_RESULT_H
#define DIAGNOSE_DIAG_RESULT_H

#include <stddef.h>

#include "diagnose/diag_data.h"
#include "diagnose/diag_eval.h"
#include "diagnose/diag_fit.h"
#include "stray/detector.h"
#include "stray/error.h"

/* The detector of the Sun exclusion angle (issue 28): name as given
 * (--detector; NULL: the sensor file's, else thesis), its kind and
 * tetra3's k (<= 0: the sensor file's, else 3) once resolved, and the
 * failure mode that sets alpha_required. */
struct diag_detector {
	const char *name;
	enum stray_detector_kind kind;
	double sigma;
	enum stray_failure_mode binding;
};

#define DIAG_BIC_MARGIN 10.0	/* Kass & Raftery 1995: "very strong" */
#define DIAG_P_ACCEPT 0.01

struct diag_result {
	double chi2_before, chi2_after, p_before, p_after;
	int dof_before, dof_after;
	double rms_before, rms_after;
	double rms_region_before[DIAG_REGIONS], rms_region_after[DIAG_REGIONS];
	int n_region[DIAG_REGIONS];
	int significant;	/* the baseline does not fit */
	int explained;		/* the final model fits (p >= DIAG_P_ACCEPT) */
	struct diag_fit named;	/* the causes named (n_causes may be 0) */
	struct diag_fit tentative;	/* best model when unexplained */
	struct diag_fit single[16];	/* each cause alone */
	int n_single;
	double *model_before, *model_after, *resid_before, *resid_after;
	double *rsig_before, *rsig_after;
	double worst_theta_deg, worst_pull;	/* largest final residual */
	double sun_deg_before, sun_deg_after, sun_alpha_req;
	char sensor[64];	/* whose FDR model gives sun_alpha_req */
	struct diag_detector detector;	/* and with which detector */
	/* the surface at fault explains what the registry left (one
	 * verdict: diag_result_surfaces): its groups are named causes */
	int by_surface;
	double p_surface;
};

/* Run the whole diagnosis; progress lines go to log when not NULL. */
int diag_run(struct diag_eval *e, const struct diag_data *d,
	     struct diag_result *r, void (*log)(const char *line),
	     struct stray_error *err);
void diag_result_free(struct diag_result *r);

struct diag_surfaces;
/* The surface at fault's verdict (issue 23): when the registry left the
 * residual unexplained and the named surface groups fit (p >=
 * DIAG_P_ACCEPT over the points fitted), they are the named causes and
 * the residual is explained (r->by_surface, r->explained).  1 then. */
int diag_result_surfaces(struct diag_result *r,
			 const struct diag_surfaces *s);

/* Survival function of chi2 with dof degrees of freedom. */
double diag_chi2_pvalue(double chi2, int dof);

/* Sun exclusion angle of a curve at the sensor (a name or JSON file;
 * NULL: st16-like), by libstray's one verdict: NaN where the curve does
 * not exclude the Sun (stray_exclusion_angle); name (64 bytes, may be
 * NULL) gets the sensor's name. */
int diag_sun_exclusion(const char *sensor, const double *theta_deg,
		       const double *alpha, size_t n, double *theta_excl,
		       double *alpha_req, char *name,
		       struct stray_error *err);

/* The same for a named detector (issue 28): name NULL takes the sensor
 * file's (else thesis, eq. 2.18 as above); binding gets the failure mode
 * that sets alpha_required.  dd NULL: diag_sun_exclusion. */
int diag_sun_exclusion_det(const char *sensor, struct diag_detector *dd,
			   const double *theta_deg, const double *alpha,
			   size_t n, double *theta_excl, double *alpha_req,
			   char *name, struct stray_error *err);

#endif /* DIAGNOSE_DIAG_RESULT_H */
