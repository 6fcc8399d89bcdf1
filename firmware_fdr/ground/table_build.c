/*
 * table_build.c - the flight table from libstray's ground results.
 *
 * What can be computed once is computed here, in double precision, by the
 * same libstray functions the ground tools use: the detection threshold
 * I_sdt (eq. 2.16) and, for telemetry, the Sun's alpha_req (fig. 2.7) and
 * exclusion angle (fig. 5.1).  Per frame the module only evaluates eq.
 * 2.18 at the frame's own attenuation, exposure and flux.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fdrfw/fdrfw.h"
#include "fdrfw/model_map.h"
#include "fdrfw/table_build.h"
#include "stray/config.h"
#include "stray/fdr.h"
#include "stray/tail.h"

static int params_check(const struct fdrfw_build_params *p,
			struct stray_error *err)
{
	if (!(isfinite(p->f_sun_ph_s_m2) && p->f_sun_ph_s_m2 > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "sun",
			"flux must be finite and > 0", p->f_sun_ph_s_m2);
	if (!(isfinite(p->f_moon_full_ph_s_m2) && p->f_moon_full_ph_s_m2 > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "moon",
			"flux must be finite and > 0", p->f_moon_full_ph_s_m2);
	if (!(isfinite(p->hysteresis_deg) && p->hysteresis_deg >= 0.0 &&
	      p->hysteresis_deg <= 10.0))
		return stray_error_set_value(err, STRAY_EINVAL,
			"hysteresis_deg", "must lie in [0, 10]",
			p->hysteresis_deg);
	if (!(isfinite(p->earth_albedo) && p->earth_albedo >= 0.0 &&
	      p->earth_albedo <= 1.0))
		return stray_error_set_value(err, STRAY_EINVAL, "albedo",
			"must lie in [0, 1]", p->earth_albedo);
	if (p->normalisation != STRAY_NORM_CONSISTENT &&
	    p->normalisation != STRAY_NORM_THESIS)
		return stray_error_set_value(err, STRAY_EINVAL,
			"normalisation", "must be consistent or thesis",
			(double)p->normalisation);
	if ((unsigned)p->detector >= STRAY_DET_COUNT)
		return stray_error_set_value(err, STRAY_EINVAL, "detector",
			"must be thesis, window, threshold or tetra3",
			(double)p->detector);
	if (p->detector == STRAY_DET_TETRA3 && p->detector_sigma > 0.0 &&
	    !(p->detector_sigma >= 0.5 && p->detector_sigma <= 20.0))
		return stray_error_set_value(err, STRAY_EINVAL,
			"detector_sigma", "must lie in 0.5..20",
			p->detector_sigma);
	if (!isfinite(p->rate))
		return stray_error_set_value(err, STRAY_EINVAL, "rate",
			"must be finite", p->rate);
	return STRAY_OK;
}

/* The curve as float log10 alpha and its envelope (max to the right). */
static int curve_fill(const struct stray_curve_view *c, struct fdrfw_table *t,
		      struct stray_error *err)
{
	size_t i;

	if (c->n < 2 || c->n > FDRFW_CURVE_MAX)
		return stray_error_set_value(err, STRAY_EINVAL, "theta_deg",
			"curve must have 2..128 rows for the flight table",
			(double)c->n);
	if (!(c->theta_deg[0] >= 0.0 && c->theta_deg[c->n - 1] <= 180.0))
		return stray_error_set_value(err, STRAY_EINVAL, "theta_deg",
			"must lie in [0, 180]", c->theta_deg[0]);
	t->n_curve = (uint32_t)c->n;
	for (i = 0; i < c->n; i++) {
		double l = c->alpha[i] > 0.0 ? log10(c->alpha[i])
					     : (double)FDRFW_LOG10_ALPHA_FLOOR;

		if (l > 6.0)
			return stray_error_set_value(err, STRAY_EINVAL, "alpha",
				"must be <= 1e6", c->alpha[i]);
		t->theta_deg[i] = (float)c->theta_deg[i];
		t->log10_alpha[i] = (float)fmax(l,
					(double)FDRFW_LOG10_ALPHA_FLOOR);
		if (i > 0 && !(t->theta_deg[i] > t->theta_deg[i - 1]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"theta_deg", "too close to the previous angle "
				"for single precision", c->theta_deg[i]);
	}
	t->log10_alpha_tail[c->n - 1] = t->log10_alpha[c->n - 1];
	for (i = c->n - 1; i > 0; i--)
		t->log10_alpha_tail[i - 1] = fmaxf(t->log10_alpha[i - 1],
						   t->log10_alpha_tail[i]);
	return STRAY_OK;
}

/* A Sun the baffle does not exclude: the first sample in or beyond the
 * aperture plane after the last one at or above alpha_req (the curve is
 * below it from there on: the module's own check holds), NaN when the
 * curve ends above. */
static double sun_not_excluded(const struct stray_curve_view *c,
			       const struct stray_exclusion *ex)
{
	if (ex->reason != NULL &&
	    strcmp(ex->reason, STRAY_EXCL_PLANE_ONLY) == 0) {
		size_t i;

		for (i = 0; i < c->n; i++)
			if (c->theta_deg[i] > ex->last_above_deg)
				return c->theta_deg[i];
	}
	return NAN;
}

/* The model constants, the threshold and the Sun's ground results. */
static int model_fill(const struct stray_curve_view *c,
		      const struct stray_sensor *s,
		      const struct fdrfw_build_params *p, struct fdrfw_table *t,
		      struct stray_exclusion *ex, struct stray_error *err)
{
	struct stray_fdr_model m, g;
	struct stray_detector d;
	struct stray_detector_req req;
	double i_sdt, alpha_req, theta_x, z;
	double rate = p->rate > 0.0 ? p->rate : s->fdr_tolerated;
	int rc;

	stray_sensor_fdr_model(s, p->f_sun_ph_s_m2, p->f_drs_ph_s_m2, &m);
	m.k_px = stray_sensor_k_px(s, p->normalisation);
	if ((rc = stray_fdr_threshold(&m, &i_sdt, err)) != STRAY_OK ||
	    (rc = stray_gauss_q_inv(m.pr_drs, &z, err)) != STRAY_OK)
		return rc;
	/* The Sun's alpha_req: eq. 2.18 (thesis), or where the named
	 * detector's first failure mode binds (`stray exclusion`'s). */
	if (p->detector == STRAY_DET_THESIS)
		rc = stray_fdr_alpha_required(&m, rate, &alpha_req, err);
	else if ((rc = fdrfw_det_setup(s, p, &m, &d, &g, err)) == STRAY_OK &&
		 (rc = stray_detector_alpha_required(&d, &g, rate, s->pr_drs,
						     &req, err)) == STRAY_OK) {
		alpha_req = req.alpha_req;
		rc = fdrfw_det_grid_fill(&d, &g, alpha_req, t, err);
	}
	if (rc != STRAY_OK ||
	    (rc = stray_exclusion_interval(c, alpha_req, 0.0, ex, err)))
		return rc;
	theta_x = ex->excluded ? ex->theta_deg : sun_not_excluded(c, ex);
	if (isnan(theta_x))
		return stray_error_set_value(err, STRAY_EINVAL, "alpha",
			"the Sun is not excluded by the baffle and the curve "
			"ends above its alpha_required: no angle the flight "
			"module accepts (trace to the aperture plane, 90 deg)",
			c->alpha[c->n - 1]);
	fdrfw_table_from_model(&m, t);
	t->i_sdt_e = (float)i_sdt;
	t->fdr_tolerated = (float)rate;
	t->f_sun_ph_s_m2 = (float)p->f_sun_ph_s_m2;
	t->f_moon_full_ph_s_m2 = (float)p->f_moon_full_ph_s_m2;
	t->moon_full_mag = (float)s->moon_mag;
	t->earth_albedo = (float)p->earth_albedo;
	t->fov_half_deg = (float)s->fov_half_deg;
	t->hysteresis_deg = (float)p->hysteresis_deg;
	t->alpha_req_sun = (float)alpha_req;
	t->exclusion_sun_deg = (float)theta_x;
	t->z_drs = (float)z;
	return STRAY_OK;
}

/* The scalars' names and domains, in the lists' order. */
static const struct {
	const char *name, *domain;
	float lo, hi;
} scalars[] = {
#define FDRFW_NAME_M(tf, mf, lo, hi) \
	{ #tf, "must lie in [" #lo ", " #hi "]", lo, hi },
#define FDRFW_NAME_S(tf, lo, hi) \
	{ #tf, "must lie in [" #lo ", " #hi "]", lo, hi },
	FDRFW_MODEL_FIELDS(FDRFW_NAME_M)
	FDRFW_TABLE_SCALARS(FDRFW_NAME_S)
};

STRAY_STATIC_ASSERT(sizeof(scalars) / sizeof(scalars[0]) == FDRFW_SCALARS,
		    every_scalar_named);

/* The other fields a check refuses, by word. */
static const struct {
	size_t word;
	const char *name, *domain;
} others[] = {
	{ offsetof(struct fdrfw_table, n_curve) / 4, "n_curve",
	  "must lie in [2, 128]" },
	{ offsetof(struct fdrfw_table, theta_deg) / 4, "theta_deg",
	  "must increase within [0, 180]" },
	{ offsetof(struct fdrfw_table, log10_alpha) / 4, "log10_alpha",
	  "must lie in [-40, 6] with some alpha > 0" },
	{ offsetof(struct fdrfw_table, log10_alpha_tail) / 4,
	  "log10_alpha_tail", "must be the envelope of log10_alpha" },
	{ offsetof(struct fdrfw_table, detector) / 4, "detector",
	  "must be 0..3 (thesis, window, threshold, tetra3)" },
	{ offsetof(struct fdrfw_table, n_det) / 4, "n_det",
	  "must be 0 for thesis, 72 for a detector's grid" },
	{ offsetof(struct fdrfw_table, det_ln_false) / 4, "det_ln_false",
	  "must lie in [-69.08, 1000] and never fall" },
	{ offsetof(struct fdrfw_table, det_p_drs) / 4, "det_p_drs",
	  "must lie in [0, 1] and never rise" },
};

const char *fdrfw_field_name(int word)
{
	size_t i;

	if (word >= (int)FDRFW_SCALAR_WORD &&
	    word < (int)(FDRFW_SCALAR_WORD + FDRFW_SCALARS))
		return scalars[word - (int)FDRFW_SCALAR_WORD].name;
	for (i = 0; i < sizeof(others) / sizeof(others[0]); i++)
		if ((int)others[i].word == word)
			return others[i].name;
	return NULL;
}

/* The flight module's own check of the sealed table (fdrfw_init: ranges,
 * curve, then I_sdt, alpha_req and the Sun on the boresight against the
 * model): what the module would refuse is never written. */
static int table_refused(const struct fdrfw_table *t, struct stray_error *err)
{
	struct fdrfw_ctx ctx;
	int rc = fdrfw_init(&ctx, t);
	int w = FDRFW_FIELD_OF(rc);
	size_t i;
	float v;

	if (rc == FDRFW_OK)
		return STRAY_OK;
	if (w >= (int)FDRFW_SCALAR_WORD &&
	    w < (int)(FDRFW_SCALAR_WORD + FDRFW_SCALARS)) {
		i = (size_t)w - FDRFW_SCALAR_WORD;
		memcpy(&v, (const unsigned char *)t + 4 * (size_t)w, 4);
		if (w == FDRFW_FIELD_OF(FDRFW_EFIELD_OF(exclusion_sun_deg)))
			return stray_error_set_value(err, STRAY_EINVAL,
				scalars[i].name, "the curve does not reach the "
				"Sun's alpha_req where it claims (0: nowhere), "
				"so the Sun would not be flagged", v);
		return stray_error_set_value(err, STRAY_EINVAL,
			scalars[i].name, (v >= scalars[i].lo &&
			v <= scalars[i].hi) ? "is inconsistent with the "
			"table's other fields (the flight module refuses it)" :
			scalars[i].domain, v);
	}
	for (i = 0; i < sizeof(others) / sizeof(others[0]); i++)
		if ((int)others[i].word == w)
			return stray_error_set(err, STRAY_EINVAL,
				others[i].name, others[i].domain);
	return stray_error_set(err, STRAY_EINVAL, "table",
		"the flight module refuses the model it makes");
}

int fdrfw_table_build(const struct stray_curve_view *curve,
		      const struct stray_sensor *sensor,
		      const struct fdrfw_build_params *p,
		      struct fdrfw_table *t, struct stray_error *err)
{
	return fdrfw_table_build_verdict(curve, sensor, p, t, NULL, err);
}

int fdrfw_table_build_verdict(const struct stray_curve_view *curve,
			      const struct stray_sensor *sensor,
			      const struct fdrfw_build_params *p,
			      struct fdrfw_table *t,
			      struct stray_exclusion *sun,
			      struct stray_error *err)
{
	struct stray_exclusion own;
	int rc;

	if (!sun)
		sun = &own;

	memset(t, 0, sizeof(*t));
	if ((rc = params_check(p, err)) != STRAY_OK ||
	    (rc = stray_sensor_check(sensor, err)) != STRAY_OK ||
	    (rc = stray_curve_check(curve, err)) != STRAY_OK ||
	    (rc = curve_fill(curve, t, err)) != STRAY_OK ||
	    (rc = model_fill(curve, sensor, p, t, sun, err)) != STRAY_OK)
		return rc;
	t->magic = FDRFW_TABLE_MAGIC;
	t->version = FDRFW_TABLE_VERSION;
	fdrfw_table_seal(t);
	return table_refused(t, err);
}

int fdrfw_table_sun_verdict(const struct fdrfw_table *t,
			    struct stray_exclusion *sun,
			    struct stray_error *err)
{
	double th[FDRFW_CURVE_MAX], al[FDRFW_CURVE_MAX];
	struct stray_curve_view v;
	uint32_t i;

	if (t->n_curve < 2u || t->n_curve > FDRFW_CURVE_MAX)
		return stray_error_set_value(err, STRAY_EINVAL, "n_curve",
			"must lie in [2, 128]", (double)t->n_curve);
	for (i = 0; i < t->n_curve; i++) {
		th[i] = (double)t->theta_deg[i];
		/* the floor stands for alpha = 0 (curve_fill) */
		al[i] = t->log10_alpha[i] <= FDRFW_LOG10_ALPHA_FLOOR ? 0.0 :
			pow(10.0, (double)t->log10_alpha[i]);
	}
	v.n = t->n_curve;	/* the view made once the arrays are filled */
	v.theta_deg = th;
	v.alpha = al;
	v.sigma = NULL;
	return stray_exclusion_interval(&v, (double)t->alpha_req_sun, 0.0,
					sun, err);
}

static void write_floats(FILE *out, const char *field, const float *v,
			 uint32_t n)
{
	uint32_t i;

	fprintf(out, "\t.%s = {", field);
	for (i = 0; i < n; i++)
		fprintf(out, "%s%af", i == 0 ? "\n\t\t" :
			i % 4 ? ", " : ",\n\t\t", (double)v[i]);
	fprintf(out, "\n\t},\n");
}

int fdrfw_table_write_c(FILE *out, const struct fdrfw_table *t,
			const char *name)
{
	fprintf(out, "/* Generated by `stray firmware-table`: do not edit. */\n"
		"#include \"fdrfw/table.h\"\n\n"
		"const struct fdrfw_table %s = {\n"
		"\t.magic = 0x%08lXu,\n\t.version = %luu,\n"
		"\t.n_curve = %luu,\n", name, (unsigned long)t->magic,
		(unsigned long)t->version, (unsigned long)t->n_curve);
#define F(field) fprintf(out, "\t." #field " = %af, /* %.9g */\n", \
			 (double)t->field, (double)t->field)
#define FDRFW_WRITE_FIELD(tf, mf, lo, hi) F(tf);
	FDRFW_MODEL_FIELDS(FDRFW_WRITE_FIELD)
	F(i_sdt_e); F(fdr_tolerated);
	F(f_sun_ph_s_m2); F(f_moon_full_ph_s_m2); F(moon_full_mag);
	F(earth_albedo); F(fov_half_deg); F(hysteresis_deg);
	F(alpha_req_sun); F(exclusion_sun_deg);
	F(z_drs); F(detector_sigma); F(det_u0); F(det_du);
#undef F
	fprintf(out, "\t.detector = %luu, /* %s */\n\t.n_det = %luu,\n",
		(unsigned long)t->detector, fdrfw_table_detector_name(t),
		(unsigned long)t->n_det);
	write_floats(out, "theta_deg", t->theta_deg, t->n_curve);
	write_floats(out, "log10_alpha", t->log10_alpha, t->n_curve);
	write_floats(out, "log10_alpha_tail", t->log10_alpha_tail, t->n_curve);
	if (t->n_det > 0u) {
		write_floats(out, "det_ln_false", t->det_ln_false, t->n_det);
		write_floats(out, "det_p_drs", t->det_p_drs, t->n_det);
	}
	fprintf(out, "\t.crc32 = 0x%08lXu,\n};\n", (unsigned long)t->crc32);
	return ferror(out) ? STRAY_EIO : STRAY_OK;
}
