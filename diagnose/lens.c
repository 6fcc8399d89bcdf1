/*
 * lens.c - system curves (`stray diagnose --lens`, issue 17 item 3;
 * thesis §4.2): where the light arrives at the lens, so that the lens
 * causes (cause_lens_scale.c, cause_lens_ghost.c) change the lens table
 * only where they act.
 *
 * The system power is linear in the lens table T(phi) (phi the incidence
 * at the pupil): P(theta) = sum_paths c T(phi_path).  Beyond the lens's
 * field (T below half its on-axis value) the incidences are cut into bins
 * of DIAG_LENS_BIN_DEG from the field edge (edges at half degrees, so that
 * the usual integer angles of a sweep, where direct light arrives, sit
 * inside a bin; the first bin from the edge to the next half degree) up to
 * DIAG_LENS_BIN_TOP, and one bin beyond.  One trace per bin with the
 * table T times the bin's indicator (same seed and paths: common random
 * numbers) gives the light at theta that arrives in bin b; one more
 * trace, the table inside the field, the light that arrives there
 * (traced, not the difference of two noisy sums, which a lens factor of
 * 1e-2 would expose).  f_b, f_in: their fractions of the sum.  Then
 *   alpha' = alpha (f_in + k sum_b f_b (1 + (10^g - 1) overlap_b))
 * (lens_scale k, ghost g between lo and hi)
 * with overlap_b the fraction of bin b inside [lo, hi] (continuous in the
 * edges); the state's other causes are taken to leave the fractions as
 * they are (first order).  The bin traces use a quarter of the paths; each bin's table
 * is a file in a temporary directory, named in the runner's spec, so
 * that stray-mpi's ranks trace behind the same table.
 */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "lens.h"
#include "stray/errfmt.h"
#include "tracer/integrator.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

static int oom(struct stray_error *err)
{
	return stray_error_set(err, STRAY_ENOMEM, "diagnose", "out of memory");
}

/* told times the indicator of [lo, hi) (all of it when lo > hi). */
static int bin_lens(const struct tracer_lens *told, double lo, double hi,
		    struct tracer_lens *out)
{
	size_t k, n = 0, cap = told->n + 6;

	out->theta_deg = malloc(cap * sizeof(double));
	out->t = malloc(cap * sizeof(double));
	if (!out->theta_deg || !out->t)
		return -1;
#define PUT(a, v) do { out->theta_deg[n] = (a); out->t[n] = (v); n++; } \
	while (0)
	if (lo > 0.0) {	/* not at 0: a curve file has alpha(0) = 1 */
		PUT(1e-9, 0.0);	/* and the table is clamped below */
		PUT(lo - 1e-6, 0.0);
	}
	PUT(lo, tracer_lens_transmission(told, lo));
	for (k = 0; k < told->n; k++)
		if (told->theta_deg[k] > lo && told->theta_deg[k] < hi)
			PUT(told->theta_deg[k], told->t[k]);
	PUT(hi, tracer_lens_transmission(told, hi));
	if (hi < 180.0) {
		PUT(hi + 1e-6, 0.0);
		PUT(180.0, 0.0);
	}
#undef PUT
	out->n = n;
	return 0;
}

/* Trace the nominal scene behind the lens table in file lens_path (a
 * file, so that stray-mpi's ranks, which rebuild the scene from the spec,
 * trace behind the same table). */
static int trace_with(struct diag_eval *e, const char *lens_path,
		      const double *theta, size_t n_theta,
		      struct tracer_result *r, struct stray_error *err)
{
	struct tracer_scene_spec spec = { e->scene, e->sets, e->n_sets,
					  lens_path, 0.0, 0.0 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_lens lens;
	int rc;

	memset(r, 0, sizeof(*r));
	tracer_scene_init(&s);
	rc = tracer_lens_load(lens_path, &lens, err);
	if (!rc)
		rc = tracer_scene_load(e->scene, e->sets, e->n_sets, &s, err);
	if (!rc)
		rc = tracer_scene_commit(&s, err);
	if (!rc) {
		tracer_trace_defaults(&o);
		o.theta_deg = theta;
		o.n_theta = n_theta;
		o.n_paths = (e->n_paths + 3) / 4;
		o.seed = e->seed;
		o.threads = e->threads;
		o.lens = &lens;
		rc = tracer_run(e->runner, &spec, &s, &o, r, err);
	}
	if (!rc) {
		e->trace_seconds += r->seconds;
		e->n_traces++;
	}
	tracer_scene_free(&s);
	tracer_lens_free(&lens);
	return rc;
}

static int write_lens(const struct tracer_lens *l, const char *path,
		      struct stray_error *err)
{
	FILE *f = fopen(path, "w");
	size_t k;

	if (!f)
		return stray_error_set(err, STRAY_EIO, "diagnose",
				       "cannot write a lens bin table");
	fprintf(f, "theta_deg,alpha\n");
	for (k = 0; k < l->n; k++)
		fprintf(f, "%.17g,%.17g\n", l->theta_deg[k], l->t[k]);
	return fclose(f) == 0 ? STRAY_OK :
		stray_error_set(err, STRAY_EIO, "diagnose",
				"cannot write a lens bin table");
}

int diag_lens_prepare(struct diag_eval *e, const double *alpha_nominal,
		      struct stray_error *err)
{
	struct tracer_lens told = { 0, NULL, NULL };
	struct tracer_result r;
	char dir[] = "/tmp/stray_lensbins_XXXXXX", bin_path[64];
	double *theta = NULL, *whole = NULL, t0, field = 0.0, pw, sg;
	size_t i, b;
	int rc, have_dir = 0;

	if (!e->lens)
		return STRAY_OK;
	rc = tracer_lens_load(e->lens, &told, err);
	theta = malloc((e->n + 1) * sizeof(*theta));
	whole = malloc((e->n + 1) * sizeof(*whole));
	e->lens_alpha_nom = malloc((e->n ? e->n : 1) * sizeof(double));
	if (!rc && (!theta || !whole || !e->lens_alpha_nom))
		rc = oom(err);
	if (rc)
		goto out;
	memcpy(e->lens_alpha_nom, alpha_nominal, e->n * sizeof(double));
	theta[0] = 0.0;
	for (i = 0; i < e->n; i++)
		theta[i + 1] = fmin(fabs(e->theta_deg[i]), 180.0);
	/* the field edge: the first angle where the table is below half */
	t0 = tracer_lens_transmission(&told, 0.0);
	for (field = 0.0; field < 90.0 &&
	     tracer_lens_transmission(&told, field) >= 0.5 * t0;
	     field += 0.05)
		;
	/* bins: [field, next half degree), then whole degrees from half to
	 * half, then one to 180 */
	e->lens_bin_lo = field;
	e->lens_bin_first = floor(field - 0.5) + 1.5;
	if (e->lens_bin_first - field < 0.05)
		e->lens_bin_first += DIAG_LENS_BIN_DEG;
	if (!(field < 90.0)) {	/* nothing beyond the field to scale */
		rc = stray_error_set_value(err, STRAY_EINVAL, "alpha",
			"the lens table stays above half its on-axis value to "
			"90 deg: no out-of-field part for the lens causes",
			tracer_lens_transmission(&told, 90.0));
		stray_error_locate(err, e->lens, 0);
		goto out;
	}
	/* a field edge beyond DIAG_LENS_BIN_TOP (a wide lens) leaves its
	 * edge bin and the one to 180 deg: never fewer than two bins (the
	 * count went negative, calloc's size huge: "out of memory") */
	e->n_lens_bins = 2 + (int)ceil((DIAG_LENS_BIN_TOP -
					e->lens_bin_first) / DIAG_LENS_BIN_DEG);
	if (e->n_lens_bins < 2)
		e->n_lens_bins = 2;
	if (e->n_lens_bins > DIAG_LENS_BINS_MAX)
		e->n_lens_bins = DIAG_LENS_BINS_MAX;
	e->lens_bin = calloc((size_t)(e->n_lens_bins + 1) * (e->n ? e->n : 1),
			     sizeof(double));
	if (!e->lens_bin) {
		rc = oom(err);
		goto out;
	}
	if (!mkdtemp(dir)) {
		rc = stray_error_set(err, STRAY_EIO, "diagnose",
				     "no temporary directory for the lens bins");
		goto out;
	}
	have_dir = 1;
	snprintf(bin_path, sizeof(bin_path), "%s/bin.csv", dir);
	/* the normalisation: the whole table, same paths and seed */
	rc = trace_with(e, e->lens, theta, e->n + 1, &r, err);
	for (i = 0; !rc && i < e->n; i++)
		tracer_result_power(&r, i + 1, -1, &whole[i], &sg);
	tracer_result_free(&r);
	/* the bins, then (b = n_lens_bins) the field itself, traced too:
	 * not the difference of two noisy sums */
	for (b = 0; !rc && b <= (size_t)e->n_lens_bins; b++) {
		struct tracer_lens bl = { 0, NULL, NULL };
		double lo = 0.0, hi = e->lens_bin_lo;

		if (b < (size_t)e->n_lens_bins)
			diag_lens_bin_edges(e, (int)b, &lo, &hi);
		if (bin_lens(&told, lo, hi, &bl)) {
			tracer_lens_free(&bl);
			rc = oom(err);
			break;
		}
		rc = write_lens(&bl, bin_path, err);
		if (!rc)
			rc = trace_with(e, bin_path, theta, e->n + 1, &r, err);
		for (i = 0; !rc && i < e->n; i++) {
			tracer_result_power(&r, i + 1, -1, &pw, &sg);
			e->lens_bin[b * e->n + i] = whole[i] > 0.0 ?
				pw / whole[i] : 0.0;
		}
		tracer_result_free(&r);
		tracer_lens_free(&bl);
	}
	for (i = 0; !rc && i < e->n; i++) {	/* fractions: of the sum */
		double sum = 0.0;

		for (b = 0; b < (size_t)e->n_lens_bins; b++)
			sum += e->lens_bin[b * e->n + i];
		sum += e->lens_bin[(size_t)e->n_lens_bins * e->n + i];
		for (b = 0; sum > 0.0 && b <= (size_t)e->n_lens_bins; b++)
			e->lens_bin[b * e->n + i] /= sum;
	}
out:
	if (have_dir) {
		unlink(bin_path);
		rmdir(dir);
	}
	free(theta);
	free(whole);
	tracer_lens_free(&told);
	return rc;
}

void diag_lens_bin_edges(const struct diag_eval *e, int b, double *lo,
			 double *hi)
{
	*lo = b == 0 ? e->lens_bin_lo :
		e->lens_bin_first + (b - 1) * DIAG_LENS_BIN_DEG;
	*hi = b + 1 == e->n_lens_bins ? 180.0 :
		e->lens_bin_first + b * DIAG_LENS_BIN_DEG;
}

double diag_lens_apply(const struct diag_eval *e, const struct diag_state *s,
		       size_t i, double a)
{
	double k = pow(10.0, s->lens_log10), g = 0.0, in, out = 0.0;
	int b;

	if (!e->lens_bin || (s->lens_log10 == 0.0 && !isfinite(s->ghost_log10)))
		return a;
	if (isfinite(s->ghost_log10))
		g = pow(10.0, s->ghost_log10) - 1.0;
	in = e->lens_bin[(size_t)e->n_lens_bins * e->n + i];
	for (b = 0; b < e->n_lens_bins; b++) {
		double lo, hi, v = e->lens_bin[(size_t)b * e->n + i], ov = 0.0;

		diag_lens_bin_edges(e, b, &lo, &hi);
		if (g != 0.0)
			ov = fmax(0.0, (fmin(hi, s->ghost_hi_deg) -
					fmax(lo, s->ghost_lo_deg)) / (hi - lo));
		out += v * (1.0 + g * ov);
	}
	if (in + out <= 0.0)	/* no light traced here: as it is */
		return a;
	a *= in + k * out;	/* the fractions sum to 1 */
	return a > 0.0 ? a : 0.0;
}

void diag_lens_free(struct diag_eval *e)
{
	free(e->lens_bin);
	free(e->lens_alpha_nom);
	e->lens_bin = NULL;
	e->lens_alpha_nom = NULL;
	e->n_lens_bins = 0;
}
