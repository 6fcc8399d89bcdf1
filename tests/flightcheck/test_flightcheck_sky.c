/*
 * test_flightcheck_sky.c - issue 24's hidden-effect test on the real sky:
 * full flight frames rendered by the generator (make_flight, truth.c:
 * test side only) from the shipped Hipparcos extract with the stars'
 * colours and proper motion to 2026, a 40" attitude error, exposures of
 * 0.05, 0.1 and 0.2 s, a 1.6 e-/DN gain, a 180 DN bias (BIAS, GAIN
 * keywords) and the times as DATE-BEG/DATE-END in TT; the stray light
 * 1.45 x the model's level, hidden.  `stray flightcheck --catalogue`
 * must recover the scale within 5 % with a 95 % interval that holds it,
 * and DN per photo-electron within 3 % of 1/1.6.  The same frames as a
 * camera writes them (a folder or a list of files, no manifest, no lab
 * keyword) give the same answer;
 * one without BIAS is refused.  Frames with the Moon near are screened
 * out of the fit.  A catalogue of too few stars, and the
 * wrong sky, are refused with their reason (exit 1), never a number.  STRAY_BIN=/work/old/bin/stray fails every test.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <cJSON.h>
#include <fitsio.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tools/run_cli.h"
#include "scratch.h"
#include "stray/starcat.h"

#define MAKE_FLIGHT "build/tests/flightcheck/make_flight"
#define CATALOGUE "libstray/data/hip2_hp6.5.dat"
#define HIDDEN_SCALE 1.45
#define GAIN_E_PER_DN 1.6	/* make_flight's real-sky camera */

static char work[] = "/tmp/fc_sky_XXXXXX";
static char frames[128], aem[128], model[128];

static int setup(void **state)
{
	char cmd[1024];
	FILE *f;
	int i;

	(void)state;
	if (!mkdtemp(work))
		return -1;
	snprintf(frames, sizeof(frames), "%s/frames", work);
	snprintf(aem, sizeof(aem), "%s/fl.aem", work);
	snprintf(model, sizeof(model), "%s/model.csv", work);
	/* the model's shape is the truth's: only the level is hidden */
	if (!(f = fopen(model, "w")))
		return -1;
	fprintf(f, "theta_deg,alpha\n");
	for (i = 0; i < 15; i++) {
		double th = 15.0 + 5.5 * i;

		fprintf(f, "%g,%.6e\n", th, 2e-7 * pow(10.0, -(th - 20.0) / 35.0));
	}
	fclose(f);
	/* 12 full frames, Sun offset 20 - 90 deg */
	snprintf(cmd, sizeof(cmd), MAKE_FLIGHT " '%s' '%s' '%s' %g 12 0 20 90 "
		 CATALOGUE, frames, aem, model, HIDDEN_SCALE);
	return system(cmd) == 0 ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(work);
}

static struct cli_run r;

static int flightcheck_dir(const char *dir, const char *cat, int json)
{
	char *argv[12] = { "stray", "flightcheck", (char *)dir, "--aem", aem,
			   "--model", model, NULL };
	int k = 7;

	if (json)
		argv[k++] = "--json";
	if (cat) {
		argv[k++] = "--catalogue";
		argv[k++] = (char *)cat;
	}
	argv[k] = NULL;
	return run_stray(&r, argv);
}

static int flightcheck(const char *cat, int json)
{
	return flightcheck_dir(frames, cat, json);
}

static double num(const cJSON *o, const char *k)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);

	assert_non_null(v);
	return v->valuedouble;
}

/* The hidden scale and the gain, from the real sky. */
static void test_real_sky_scale(void **state)
{
	cJSON *o, *iv;
	double s, lo, hi, g;

	(void)state;
	assert_int_equal(flightcheck(CATALOGUE, 1), 0);
	assert_non_null(o = cJSON_Parse(r.out));
	s = num(o, "scale_over_k_px");
	iv = cJSON_GetObjectItemCaseSensitive(o, "scale_over_k_px_interval");
	assert_true(cJSON_IsArray(iv) && cJSON_GetArraySize(iv) == 2);
	lo = cJSON_GetArrayItem(iv, 0)->valuedouble;
	hi = cJSON_GetArrayItem(iv, 1)->valuedouble;
	g = num(o, "dn_per_e");
	printf("# real sky: scale/k_px %.4f [%.4f, %.4f] (truth %.2f); DN/e- %.4f +- %.4f (truth %.4f) from %d stars; %d of %d found, residual %.2f px\n",
	       s, lo, hi, HIDDEN_SCALE, g, num(o, "dn_per_e_sigma"),
	       1.0 / GAIN_E_PER_DN, (int)num(o, "calibration_stars"),
	       (int)num(o, "stars_matched"), (int)num(o, "stars_predicted"),
	       num(o, "plate_residual_px"));
	assert_true(fabs(s / HIDDEN_SCALE - 1.0) < 0.05);
	assert_true(lo <= HIDDEN_SCALE && HIDDEN_SCALE <= hi);
	assert_true(fabs(g * GAIN_E_PER_DN - 1.0) < 0.03);
	assert_true(num(o, "calibration_stars") >= 10);
	assert_non_null(strstr(cJSON_GetObjectItemCaseSensitive(o, "catalogue")->valuestring,
			       "hip2"));
	cJSON_Delete(o);
}

/* The same stars as a CSV (positions at J1991.25, proper motions): the
 * same answer, so the CSV reader and the epoch are the hip2 reader's. */
static void test_csv_catalogue(void **state)
{
	struct stray_starcat c;
	struct stray_error err = { 0 };
	char csv[160];
	cJSON *o;
	double s_hip, s_csv;
	size_t i;
	FILE *f;

	(void)state;
	assert_int_equal(stray_starcat_load(CATALOGUE, &c, &err), STRAY_OK);
	snprintf(csv, sizeof(csv), "%s/stars.csv", work);
	assert_non_null(f = fopen(csv, "w"));
	fprintf(f, "hip,ra_deg,dec_deg,v_mag,b_v,pmra_mas_yr,pmdec_mas_yr,epoch_jyear\n");
	for (i = 0; i < c.n; i++)
		fprintf(f, "%ld,%.10f,%.10f,%.5f,%.4f,%.3f,%.3f,%.2f\n", c.s[i].id,
			c.s[i].ra_deg, c.s[i].dec_deg, c.s[i].v_mag, c.s[i].b_v,
			c.s[i].pmra_mas_yr, c.s[i].pmdec_mas_yr, c.s[i].epoch_jyear);
	fclose(f);
	stray_starcat_free(&c);
	assert_int_equal(flightcheck(CATALOGUE, 1), 0);
	assert_non_null(o = cJSON_Parse(r.out));
	s_hip = num(o, "scale_over_k_px");
	cJSON_Delete(o);
	assert_int_equal(flightcheck(csv, 1), 0);
	assert_non_null(o = cJSON_Parse(r.out));
	s_csv = num(o, "scale_over_k_px");
	cJSON_Delete(o);
	assert_true(fabs(s_csv / s_hip - 1.0) < 1e-3);
}

/* Three stars cannot calibrate 12 frames: refused, with the reason. */
static void test_too_few_stars(void **state)
{
	char csv[160];
	FILE *f;

	(void)state;
	snprintf(csv, sizeof(csv), "%s/three.csv", work);
	assert_non_null(f = fopen(csv, "w"));
	fprintf(f, "ra_deg,dec_deg,v_mag,b_v\n10,10,5,0.5\n20,20,5,0.5\n30,30,5,0.5\n");
	fclose(f);
	assert_int_equal(flightcheck(csv, 0), 1);
	assert_non_null(strstr(r.err, "cannot be calibrated"));
	assert_non_null(strstr(r.err, "calibration stars (at least 3"));
	assert_int_equal(r.err_lines, 1);
	assert_null(strstr(r.out, "consistent"));
	assert_null(strstr(r.out, "scale"));
}

/* The synthetic sky against frames of the real one: the stars that
 * "match" are chance; refused, never a scale printed as consistent. */
static void test_wrong_sky_refused(void **state)
{
	(void)state;
	assert_int_equal(flightcheck(NULL, 0), 1);
	assert_non_null(strstr(r.err, "cannot be calibrated"));
	assert_null(strstr(r.out, "consistent"));
}

/* Copy the frames to dir without manifest.csv and without the lab
 * keywords (and without `drop` too, when given). */
static void camera_frames(const char *dir, const char *drop)
{
	static const char *const lab[] = { "FRAMETYP", "ANGLE", "NDTRANS",
					   "SEQNUM", "SATLEVEL", "TALPHA",
					   "TSCALE", "STARSRC" };
	char cmd[1024], path[300];
	int i, k;

	snprintf(cmd, sizeof(cmd), "rm -rf '%s' && mkdir '%s' && cp '%s'/*.fits '%s'/",
		 dir, dir, frames, dir);
	assert_int_equal(system(cmd), 0);
	for (i = 0; i < 12; i++) {
		fitsfile *f;
		int status = 0;

		snprintf(path, sizeof(path), "%s/a+000.000_FULL_%03d.fits", dir, i);
		assert_int_equal(fits_open_file(&f, path, READWRITE, &status), 0);
		for (k = 0; k < (int)(sizeof(lab) / sizeof(lab[0])); k++) {
			fits_delete_key(f, lab[k], &status);
			status = 0;
		}
		if (drop && i == 5)
			fits_delete_key(f, drop, &status);
		status = 0;
		assert_int_equal(fits_close_file(f, &status), 0);
	}
}

/* Frames as a camera writes them: a folder of FITS, no manifest, no lab
 * keyword; the same numbers as the sweep folder. */
static void test_camera_frames(void **state)
{
	char dir[160];
	cJSON *o;
	double s_sweep, s_cam;

	(void)state;
	assert_int_equal(flightcheck(CATALOGUE, 1), 0);
	assert_non_null(o = cJSON_Parse(r.out));
	s_sweep = num(o, "scale_over_k_px");
	cJSON_Delete(o);
	snprintf(dir, sizeof(dir), "%s/camera", work);
	camera_frames(dir, NULL);
	if (flightcheck_dir(dir, CATALOGUE, 1))
		fprintf(stderr, "%s", r.err);
	assert_int_equal(r.status, 0);
	assert_non_null(o = cJSON_Parse(r.out));
	s_cam = num(o, "scale_over_k_px");
	assert_int_equal((int)num(o, "frames"), 12);
	cJSON_Delete(o);
	assert_true(fabs(s_cam / s_sweep - 1.0) < 1e-9);
	{	/* the same frames as a list of files */
		static char names[12][200];
		char *argv[24];
		int i, k = 0;

		argv[k++] = "stray";
		argv[k++] = "flightcheck";
		for (i = 0; i < 12; i++) {
			snprintf(names[i], sizeof(names[i]),
				 "%s/a+000.000_FULL_%03d.fits", dir, i);
			argv[k++] = names[i];
		}
		argv[k++] = "--aem";
		argv[k++] = aem;
		argv[k++] = "--model";
		argv[k++] = model;
		argv[k++] = "--catalogue";
		argv[k++] = CATALOGUE;
		argv[k++] = "--json";
		argv[k] = NULL;
		assert_int_equal(run_stray(&r, argv), 0);
		assert_non_null(o = cJSON_Parse(r.out));
		assert_true(fabs(num(o, "scale_over_k_px") / s_sweep - 1.0) < 1e-9);
		cJSON_Delete(o);
	}

	/* the bias is never assumed */
	camera_frames(dir, "BIAS");
	assert_int_equal(flightcheck_dir(dir, CATALOGUE, 0), 2);
	assert_non_null(strstr(r.err, "FULL_005.fits: BIAS"));
	assert_int_equal(r.err_lines, 1);
}

/* The Moon's offset angle per frame (104-174 deg in this sweep): frames
 * with it nearer than --moon-min are left out of the fit, said; all of
 * them left out is a refusal. */
static void test_moon_screening(void **state)
{
	char *argv[] = { "stray", "flightcheck", frames, "--aem", aem,
			 "--model", model, "--catalogue", CATALOGUE,
			 "--moon-min", "150", "--json", NULL };
	cJSON *o, *pf;
	int i, screened = 0;

	(void)state;
	assert_int_equal(run_stray(&r, argv), 0);
	assert_non_null(o = cJSON_Parse(r.out));
	assert_int_equal((int)num(o, "frames_screened"), 8);
	pf = cJSON_GetObjectItemCaseSensitive(o, "per_frame");
	for (i = 0; i < cJSON_GetArraySize(pf); i++) {
		cJSON *e = cJSON_GetArrayItem(pf, i);
		double m = num(e, "moon_deg");

		assert_true(m > 100.0 && m < 180.0);
		assert_int_equal(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(e,
				"screened")), m < 150.0);
		screened += m < 150.0;
	}
	assert_int_equal(screened, 8);
	/* the 4 frames left still give the scale */
	assert_true(fabs(num(o, "scale_over_k_px") / HIDDEN_SCALE - 1.0) < 0.05);
	cJSON_Delete(o);
	argv[10] = "180";
	argv[11] = NULL;
	assert_int_equal(run_stray(&r, argv), 1);
	assert_non_null(strstr(r.err, "cannot be calibrated: every frame has the Moon"));
	assert_null(strstr(r.out, "scale"));
}

/* With the orbit (the demo mission's OEM): the Earth limb's angle per
 * frame, frames under --limb-min screened. */
static void test_earth_limb(void **state)
{
	char oem[160], oaem[160];
	char *gen[] = { "stray", "availability", "--write-oem", oem,
			"--write-aem", oaem, "--hours", "12", NULL };
	char *argv[] = { "stray", "flightcheck", frames, "--aem", aem,
			 "--model", model, "--catalogue", CATALOGUE, "--oem", oem,
			 "--limb-min", "50", "--json", NULL };
	cJSON *o, *pf;
	int i, under = 0;

	(void)state;
	snprintf(oem, sizeof(oem), "%s/demo.oem", work);
	snprintf(oaem, sizeof(oaem), "%s/demo.aem", work);
	assert_int_equal(run_stray(&r, gen), 0);
	assert_int_equal(run_stray(&r, argv), 0);
	assert_non_null(o = cJSON_Parse(r.out));
	pf = cJSON_GetObjectItemCaseSensitive(o, "per_frame");
	for (i = 0; i < cJSON_GetArraySize(pf); i++) {
		cJSON *e = cJSON_GetArrayItem(pf, i);
		double l = num(e, "earth_limb_deg");

		/* the Earth from 550 km: 67 deg in radius */
		assert_true(l > 0.0 && l < 90.0);
		assert_int_equal(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(e,
				"screened")), l < 50.0);
		under += l < 50.0;
	}
	assert_true(under > 0 && under < 12);
	assert_int_equal((int)num(o, "frames_screened"), under);
	cJSON_Delete(o);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_real_sky_scale),
		cmocka_unit_test(test_csv_catalogue),
		cmocka_unit_test(test_camera_frames),
		cmocka_unit_test(test_moon_screening),
		cmocka_unit_test(test_earth_limb),
		cmocka_unit_test(test_too_few_stars),
		cmocka_unit_test(test_wrong_sky_refused),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
