/*
 * trace_job.c - a run of `stray trace` as library calls (trace_job.h):
 * the angles (requested, or fitted to the scene's direct cut-off, with
 * the reference angle 0 added), the lens, the spectral band, the trace
 * through the caller's runner, the on-axis check, and the curve with its
 * scatter orders and provenance as a curve file.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "tracer/angles.h"
#include "tracer/trace_job.h"

const char *const tracer_order_names[TRACER_ORDERS] = {
	"direct", "order1", "order2", "order3plus"
};

/* Angles to trace: the requested ones (without --angles or with
 * "auto", the grid fitted to the committed scene's direct cut-off), with
 * 0 added as the reference. */
static int make_angles(struct tracer_job *j, const struct tracer_scene *s,
		       double **theta, size_t *n, size_t *first_out,
		       struct stray_error *err)
{
	int added = 0, rc = j->auto_angles
		? tracer_angles_auto(s, theta, n, &j->cutoff_deg, err)
		: tracer_angles_parse(j->angles, theta, n, err);

	if (!rc)
		rc = tracer_angles_with_zero(theta, n, &added, err);
	*first_out = (size_t)added;
	return rc;
}

int tracer_job_prepare(struct tracer_job *j, struct tracer_scene *s,
		       struct stray_error *err)
{
	int rc = tracer_scene_commit(s, err);

	if (!rc)
		rc = make_angles(j, s, &j->theta, &j->n_theta, &j->first, err);
	if (!rc && j->lens)
		rc = tracer_lens_load(j->lens, &j->lens_model, err);
	if (rc)
		return rc;
	j->o.theta_deg = j->theta;
	j->o.n_theta = j->n_theta;
	j->o.lens = j->lens ? &j->lens_model : NULL;
	if (tracer_scene_spectral(s)) {	/* a "reflectance_table" */
		rc = tracer_band_load(j->spectrum, j->response, &j->band, err);
		j->o.record_paths = 1;
	}
	return rc;
}

int tracer_job_angle_index(const struct tracer_job *j, double angle_deg,
			   size_t *k, struct stray_error *err)
{
	for (*k = 0; *k < j->o.n_theta; (*k)++)
		if (fabs(j->o.theta_deg[*k] - angle_deg) < 1e-9)
			return STRAY_OK;
	return stray_error_set_value(err, STRAY_EINVAL, "--map-angle",
				     "is not one of --angles", angle_deg);
}

/* alpha = P_det(theta) / P_det(0) (§3.4): with nothing on the detector
 * on axis (a plate blocking the beam, a lens curve of zeros) every alpha
 * would be 0/0, printed as 0 +- 0.  Refuse the scene instead. */
static int check_on_axis(const struct tracer_job *j,
			 const struct tracer_result *r, struct stray_error *err)
{
	double p0, s0;

	tracer_result_power(r, 0, -1, &p0, &s0);
	if (p0 > 0.0)
		return STRAY_OK;
	return stray_error_at(err, STRAY_EINVAL, j->scene, 0, "beam",
		"no on-axis power reaches the detector (is the beam blocked?): "
		"alpha = P(theta) / P(0) would be 0/0");
}

int tracer_job_run(struct tracer_job *j, struct tracer_scene *s,
		   struct tracer_result *r, struct stray_error *err)
{
	struct tracer_scene_spec spec = { j->scene, j->sets, j->n_sets,
					  j->lens, 0.0, 0.0 };
	int rc = tracer_run(j->runner, &spec, s, &j->o, r, err);

	if (!rc && tracer_scene_spectral(s)) {
		rc = tracer_result_apply_band(r, s, &j->band, err);
		if (rc)
			tracer_result_free(r);
	}
	if (rc)
		return rc;
	rc = check_on_axis(j, r, err);
	if (rc)
		tracer_result_free(r);
	return rc;
}

static int add_meta(struct stray_curve *c, const struct tracer_job *j,
		    struct stray_error *err)
{
	char buf[512];
	int rc = stray_curve_add_meta(c, "kind", j->lens ? "system" : "baffle",
				      err);
	size_t k, len;

	len = (size_t)snprintf(buf, sizeof(buf), "%s", j->scene);
	for (k = 0; k < (size_t)j->n_sets && len < sizeof(buf); k++)
		len += (size_t)snprintf(buf + len, sizeof(buf) - len, "%s%s",
					k ? ", " : " with --set ", j->sets[k]);
	if (!rc)
		rc = stray_curve_add_meta(c, "scene", buf, err);
	if (!rc && j->lens)	/* a curve path or ideal:DEG */
		rc = stray_curve_add_meta(c, "lens", j->lens, err);
	if (!rc && j->scene_note)
		rc = stray_curve_add_meta(c, "mesh", j->scene_note, err);
	snprintf(buf, sizeof(buf), "stray trace, adjoint Monte Carlo with "
		 "next-event connections%s; %llu paths, seed %llu",
		 j->o.light_paths ? " and light-side single scatter (MIS)" :
		 "", (unsigned long long)j->o.n_paths,
		 (unsigned long long)j->o.seed);
	if (!rc)
		rc = stray_curve_add_meta(c, "source", buf, err);
	snprintf(buf, sizeof(buf), "one standard error from %d batches",
		 j->o.n_batches);
	if (!rc)
		rc = stray_curve_add_meta(c, "sigma", buf, err);
	if (j->auto_angles) {
		snprintf(buf, sizeof(buf), "auto: 1 deg, 0.1 deg within 1 deg "
			 "of the direct cut-off at %.1f deg, 0.5 deg beyond",
			 j->cutoff_deg);
		if (!rc)
			rc = stray_curve_add_meta(c, "angles", buf, err);
	}
	return rc;
}

int tracer_job_curve(const struct tracer_job *j,
		     const struct tracer_result *r, struct stray_curve *out,
		     struct stray_error *err)
{
	struct stray_curve c;
	double *col = NULL;
	size_t first = j->first, n = r->n_theta - first, i;
	int rc = stray_curve_alloc(&c, n, 1, err), k;

	if (rc)
		return rc;
	col = malloc(n * sizeof(double));
	if (!col) {
		rc = stray_error_set(err, STRAY_ENOMEM, "--out", "out of memory");
		goto out_free;
	}
	for (i = 0; i < n; i++) {
		c.theta_deg[i] = j->o.theta_deg[first + i];
		tracer_result_alpha(r, first + i, 0, -1, &c.alpha[i],
				    &c.sigma[i]);
	}
	for (k = 0; k < TRACER_ORDERS && !rc; k++) {
		for (i = 0; i < n; i++) {
			double s;

			tracer_result_alpha(r, first + i, 0, k, &col[i], &s);
		}
		rc = stray_curve_add_column(&c, tracer_order_names[k], col,
					    err);
	}
	if (!rc)
		rc = add_meta(&c, j, err);
out_free:
	free(col);
	if (rc)
		stray_curve_free(&c);
	else
		*out = c;
	return rc;
}

int tracer_job_write_curve(const struct tracer_job *j,
			   const struct tracer_result *r, const char *path,
			   struct stray_error *err)
{
	struct stray_curve c;
	int rc = tracer_job_curve(j, r, &c, err);

	if (rc)
		return rc;
	rc = stray_curve_save(path, &c, err);
	stray_curve_free(&c);
	return rc;
}

void tracer_job_free(struct tracer_job *j)
{
	tracer_lens_free(&j->lens_model);
	free(j->theta);
	j->theta = NULL;
}
