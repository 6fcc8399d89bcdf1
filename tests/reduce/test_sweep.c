/*
 * test_sweep.c - hidden-effect tests of `stray reduce` (thesis §3.2):
 * synthetic sweeps (synth_sweep.c, which keeps the truth) are reduced by
 * build/bin/stray without being told the lens curve, the ghosts, the bad
 * pixels, the saturated spots or the drift; the reduction must recover
 * the curve within its own errors (eq. 3.12), name the bad pixels, keep
 * saturated samples out, see and correct the drift, and track the ghosts.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/curve_io.h"
#include "synth_sweep.h"
#include "test_util.h"
#include "tools/run_cli.h"

struct sweep_case {
	char dir[256], out[300];
	struct synth_config cfg;
	struct synth_truth truth;
	struct cli_run run;
	cJSON *json;
};

static struct sweep_case *make_case(const char *tag,
				    void (*tweak)(struct synth_config *))
{
	struct sweep_case *k = calloc(1, sizeof(*k));
	char tmpl[] = "/tmp/stray_reduce_XXXXXX";

	assert_non_null(k);
	assert_non_null(mkdtemp(tmpl));
	snprintf(k->dir, sizeof(k->dir), "%s/%s", tmpl, tag);
	snprintf(k->out, sizeof(k->out), "%s/curve.csv", tmpl);
	synth_default(&k->cfg);
	if (tweak)
		tweak(&k->cfg);
	assert_int_equal(synth_write_sweep(k->dir, &k->cfg, &k->truth), 0);
	return k;
}

static int reduce(struct sweep_case *k)
{
	char *argv[] = { "stray", "--json", "reduce", k->dir, "--out", k->out,
			 NULL };

	run_stray(&k->run, argv);
	if (k->run.status == 0) {
		k->json = cJSON_Parse(k->run.out);
		assert_non_null(k->json);
	}
	return k->run.status;
}

static void free_case(struct sweep_case *k)
{
	char cmd[600];

	cJSON_Delete(k->json);
	snprintf(cmd, sizeof(cmd), "rm -rf '%.*s'", (int)(strrchr(k->dir, '/') - k->dir),
		 k->dir);
	if (system(cmd) != 0)
		fprintf(stderr, "could not remove %s\n", k->dir);
	free(k);
}

static double num(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);

	assert_non_null(v);
	return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/*
 * eq. 3.12 against the truth, from the CSV the command wrote: the reduced
 * chi-square of the off-axis points with their covariance (each sigma
 * includes the shared error s of P(0), so C = D + s^2 alpha alpha^T,
 * inverted by Sherman-Morrison), and the worst deviation in sigma.
 */
static void check_curve(const struct sweep_case *k, double *chi2_red,
			double *worst)
{
	struct stray_curve c;
	struct stray_error err;
	double s = num(k->json, "p0_rel_sigma"), s2 = s * s;
	double q = 0.0, u = 0.0, w = 0.0;
	size_t i, n = 0;

	stray_error_clear(&err);
	assert_true(s > 0.0 && s < 0.01);
	assert_int_equal(stray_curve_load(k->out, &c, &err), 0);
	assert_non_null(c.sigma);
	assert_int_equal(c.n, k->truth.n_angles);
	assert_int_equal(c.n_extra, 1);
	assert_string_equal(c.extra_name[0], "noise_floor");
	*worst = 0.0;
	for (i = 0; i < c.n; i++) {
		double r, d;

		assert_near(c.theta_deg[i], k->truth.theta_deg[i], 1e-9);
		if (c.theta_deg[i] == 0.0) {
			assert_near(c.alpha[i], 1.0, 1e-12);
			continue;
		}
		assert_true(c.extra[0][i] > 0.0);
		r = c.alpha[i] - k->truth.alpha[i];
		d = c.sigma[i] * c.sigma[i] - s2 * c.alpha[i] * c.alpha[i];
		assert_true(d > 0.0);	/* each point has its own noise too */
		q += r * r / d;
		u += r * c.alpha[i] / d;
		w += c.alpha[i] * c.alpha[i] / d;
		*worst = fmax(*worst, fabs(r) / c.sigma[i]);
		n++;
	}
	*chi2_red = (q - s2 * u * u / (1.0 + s2 * w)) / (double)n;
	print_message("curve: %zu points, reduced chi2 %.3f, worst %.2f sigma\n",
		      n, *chi2_red, *worst);
	stray_curve_free(&c);
}

/* Every listed pixel is a true one and every true one is listed. */
static void check_pixels(const cJSON *list, long (*truth)[2], size_t n)
{
	const cJSON *p;
	size_t found = 0, i;

	assert_int_equal(cJSON_GetArraySize(list), (int)n);
	cJSON_ArrayForEach(p, list) {
		long r = (long)cJSON_GetArrayItem(p, 0)->valuedouble;
		long c = (long)cJSON_GetArrayItem(p, 1)->valuedouble;

		for (i = 0; i < n; i++)
			if (truth[i][0] == r && truth[i][1] == c)
				found++;
	}
	assert_int_equal(found, n);
}

/* A track that follows ghost g: its columns within 1 px of the truth at
 * every angle it has, over at least 90% of the angles the ghost exists,
 * and its power share within 25% (the row vignette is not in the truth's
 * share, and neighbours bias the background). */
static int track_matches(const cJSON *track, const struct synth_truth *t,
			 int g)
{
	const cJSON *th = cJSON_GetObjectItem(track, "theta_deg");
	const cJSON *col = cJSON_GetObjectItem(track, "column");
	const cJSON *rel = cJSON_GetObjectItem(track, "rel_power");
	size_t i, k, n_true = 0, hit = 0;

	for (i = 0; i < t->n_angles; i++)
		n_true += !isnan(t->ghost_col[g][i]);
	for (k = 0; k < (size_t)cJSON_GetArraySize(th); k++) {
		double a = cJSON_GetArrayItem(th, (int)k)->valuedouble;
		double c = cJSON_GetArrayItem(col, (int)k)->valuedouble;

		for (i = 0; i < t->n_angles; i++)
			if (fabs(t->theta_deg[i] - a) < 1e-9)
				break;
		if (i == t->n_angles || isnan(t->ghost_col[g][i]) ||
		    fabs(t->ghost_col[g][i] - c) > 1.0)
			return 0;
		assert_near(cJSON_GetArrayItem(rel, (int)k)->valuedouble,
			    t->ghost_rel[g][i], 0.25 * t->ghost_rel[g][i]);
		hit++;
	}
	return hit >= (9 * n_true + 9) / 10;
}

static void check_ghosts(const struct sweep_case *k)
{
	const cJSON *ghosts = cJSON_GetObjectItem(k->json, "ghosts"), *tr;
	int g, matched[2] = { 0, 0 };

	assert_true(cJSON_IsArray(ghosts));
	assert_int_equal(cJSON_GetArraySize(ghosts), 2);	/* no spurious */
	cJSON_ArrayForEach(tr, ghosts)
		for (g = 0; g < 2; g++)
			matched[g] += track_matches(tr, &k->truth, g);
	assert_int_equal(matched[0], 1);
	assert_int_equal(matched[1], 1);
}

static void drifting(struct synth_config *c)
{
	c->drift = 0.04;
	c->seed = 7;
}

/* The full hidden-effect sweep: everything at once, nothing told. */
static void test_sweep_recovers_curve_pixels_drift_ghosts(void **state)
{
	struct sweep_case *k = make_case("full", drifting);
	const cJSON *drift;
	double chi2, worst;

	(void)state;
	assert_int_equal(reduce(k), 0);
	check_curve(k, &chi2, &worst);
	assert_true(chi2 > 0.3 && chi2 < 2.0);
	assert_true(worst < 4.0);
	check_pixels(cJSON_GetObjectItem(k->json, "hot_pixels"), k->truth.hot,
		     k->truth.n_hot);
	check_pixels(cJSON_GetObjectItem(k->json, "dead_pixels"), k->truth.dead,
		     k->truth.n_dead);
	/* Each 3x3 spot in one frame: 9 samples left out, none averaged in. */
	assert_true(num(k->json, "saturated_samples") >= 9.0 *
		    (double)k->truth.n_sat_spots);
	drift = cJSON_GetObjectItem(k->json, "drift");
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(drift, "detected")));
	assert_near(num(drift, "rel_change"), 0.04, 0.01);
	check_ghosts(k);
	free_case(k);
}

static void sampled_monitor(struct synth_config *c)
{
	c->sampled = 1;
	c->n_rows = 14;		/* 7 pairs, as the thesis read */
	c->col0 = 1001;		/* odd phases: the Bayer map must follow */
	c->row0 = 301;
	c->monitor = 1;
	c->drift = 0.05;
	c->ghosts = 0;
	c->amb_longer = 1;	/* t2 != t1: the channel darks matter */
	c->seed = 11;
}

/* Row-sampled frames with a source monitor: drift normalised away. */
static void test_sweep_sampled_rows_with_monitor(void **state)
{
	struct sweep_case *k = make_case("sampled", sampled_monitor);
	const cJSON *drift;
	double chi2, worst;

	(void)state;
	assert_int_equal(reduce(k), 0);
	check_curve(k, &chi2, &worst);
	assert_true(chi2 > 0.2 && chi2 < 2.5);
	assert_true(worst < 4.0);
	drift = cJSON_GetObjectItem(k->json, "drift");
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(drift, "monitor")));
	assert_false(cJSON_IsTrue(cJSON_GetObjectItem(drift, "detected")));
	assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(k->json,
								 "ghosts")), 0);
	check_pixels(cJSON_GetObjectItem(k->json, "hot_pixels"), k->truth.hot,
		     k->truth.n_hot);
	free_case(k);
}

static void short_sweep(struct synth_config *c)
{
	c->n_angles = 4;
	c->n_hot = c->n_dead = 0;
}

/* Streaming: the per-pixel workspace does not grow with the sweep. */
static void test_sweep_memory_bounded(void **state)
{
	struct sweep_case *a = make_case("short", short_sweep);
	struct sweep_case *b = make_case("long", NULL);
	double wa, wb, n_pix = 64.0 * 96.0;

	(void)state;
	assert_int_equal(reduce(a), 0);
	assert_int_equal(reduce(b), 0);
	wa = num(a->json, "workspace_bytes");
	wb = num(b->json, "workspace_bytes");
	assert_true(num(b->json, "frames") > 3.0 * num(a->json, "frames"));
	assert_near(wa, wb, 0.0);
	/* 31 bytes a pixel plus the fixed 2 MiB of dark histograms. */
	assert_true(wb <= 32.0 * n_pix + 8.0 * 65536.0 * 4.0);
	free_case(a);
	free_case(b);
}

static void two_passes(struct synth_config *c)
{
	c->n_angles = 6;
	c->two_pass = 1;
	c->ghosts = 0;
	c->seed = 3;
}

/* A sweep taken as all FULL frames, then all AMBIENT frames: each angle's
 * two runs are paired into one visit. */
static void test_sweep_two_passes(void **state)
{
	struct sweep_case *k = make_case("twopass", two_passes);
	double chi2, worst;

	(void)state;
	assert_int_equal(reduce(k), 0);
	assert_int_equal((int)num(k->json, "visits"), 7);
	check_curve(k, &chi2, &worst);
	assert_true(chi2 < 3.0);
	assert_true(worst < 4.0);
	free_case(k);
}

static int png_ok(const char *dir, const char *name)
{
	static const unsigned char sig[8] = { 0x89, 'P', 'N', 'G', 13, 10, 26, 10 };
	unsigned char buf[8] = { 0 };
	char path[400];
	FILE *f;
	size_t n;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	f = fopen(path, "rb");
	if (!f)
		return 0;
	n = fread(buf, 1, 8, f);
	fclose(f);
	return n == 8 && memcmp(buf, sig, 8) == 0;
}

/* The other outputs: Zemax TABLE coating (one ANGL/WAVE pair per point,
 * T = alpha of the CSV), the FDR region map, and the figures. */
static void test_sweep_zemax_map_plots(void **state)
{
	struct sweep_case *k = make_case("outputs", short_sweep);
	char zemax[320], map[320], plots[300], line[256];
	char *argv[] = { "stray", "reduce", k->dir, "--out", k->out,
			 "--zemax", zemax, "--map", map, "--image-angle", "2",
			 "--plot-dir", plots, NULL };
	struct stray_curve c;
	struct stray_error err;
	double ang, wave, rs, rp, ts, tp, frac = 0.0, rel = 0.0, f, a;
	size_t n_angl = 0;
	FILE *z;

	(void)state;
	snprintf(zemax, sizeof(zemax), "%s.dat", k->out);
	snprintf(map, sizeof(map), "%s.map.csv", k->out);
	snprintf(plots, sizeof(plots), "%.*s", (int)(strrchr(k->out, '/') - k->out),
		 k->out);
	run_stray(&k->run, argv);
	assert_int_equal(k->run.status, 0);
	stray_error_clear(&err);
	assert_int_equal(stray_curve_load(k->out, &c, &err), 0);
	z = fopen(zemax, "r");
	assert_non_null(z);
	assert_non_null(fgets(line, sizeof(line), z));	/* comments */
	assert_non_null(fgets(line, sizeof(line), z));
	assert_non_null(fgets(line, sizeof(line), z));
	assert_string_equal(line, "TABLE LENS_ATTEN\n");
	while (fscanf(z, " ANGL %lf WAVE %lf %lf %lf %lf %lf", &ang, &wave, &rs,
		      &rp, &ts, &tp) == 6) {
		assert_near(ang, c.theta_deg[n_angl], 1e-9);
		assert_near(ts, c.alpha[n_angl], 1e-9 * c.alpha[n_angl]);
		assert_near(tp, ts, 0);
		assert_near(rs + rp, 0, 0);
		assert_near(wave, 0.55, 0);
		n_angl++;
	}
	fclose(z);
	assert_int_equal(n_angl, c.n);
	z = fopen(map, "r");
	assert_non_null(z);
	while (fgets(line, sizeof(line), z))
		if (sscanf(line, "%lf,%lf", &f, &a) == 2) {
			frac += f;
			rel += f * a;
		}
	fclose(z);
	assert_near(frac, 1.0, 1e-9);
	assert_near(rel, 1.0, 1e-6);	/* the map keeps the mean */
	assert_true(png_ok(plots, "alpha.png"));
	assert_true(png_ok(plots, "profiles.png"));
	assert_true(png_ok(plots, "j.png"));
	stray_curve_free(&c);
	free_case(k);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sweep_recovers_curve_pixels_drift_ghosts),
		cmocka_unit_test(test_sweep_sampled_rows_with_monitor),
		cmocka_unit_test(test_sweep_memory_bounded),
		cmocka_unit_test(test_sweep_zemax_map_plots),
		cmocka_unit_test(test_sweep_two_passes),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
