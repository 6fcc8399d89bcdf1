/*
 * test_lab_time.c - issue 29: time in every frame and manifest row, the
 * drift fitted against it, and plans as labs write them (an angle list
 * with returns to 0 deg, ranges with their own steps).  strayrigd and
 * `stray` run as programs (rig_ops_util.h), a sweep with a pause in
 * process on the simulator.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig_test_util.h"
#include "rig_ops_util.h"
#include "rig/sim.h"
#include "rig/vlab.h"
#include "stray/table.h"

#define WINDOW "\"camera\":{\"rows\":[960,961],\"col0\":960,\"n_cols\":64}"

/* A FITS keyword's string value ("" when absent). */
static void fits_str(const char *path, const char *key, char *out)
{
	fitsfile *f = NULL;
	int st = 0;

	out[0] = '\0';
	if (fits_open_file(&f, path, READONLY, &st) == 0)
		fits_read_key(f, TSTRING, key, out, NULL, &st);
	if (f) {
		st = 0;
		fits_close_file(f, &st);
	}
	if (st)
		out[0] = '\0';
}

/* Every frame says when it was taken (DATE-OBS, DATE-END, TIMESYS UTC)
 * and so does its manifest row (date_obs), in the order taken.  Before:
 * no time anywhere. */
static void test_time_in_frames_and_manifest(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192], path[900];
	char k0[80], k1[80], ts[80];
	struct stray_sweep_manifest mf;
	struct stray_error se;
	size_t i;

	(void)state;
	put(dir, "c.json", "{" WINDOW ",\"sweep\":{\"theta_stop_deg\":10,"
	    "\"theta_step_deg\":5,\"repeats\":2}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/c.json --sweep %s/s",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	snprintf(path, sizeof(path), "%s/s", dir);
	stray_error_clear(&se);
	assert_int_equal(stray_sweep_manifest_load(path, &mf, &se), STRAY_OK);
	assert_true(mf.has_date && mf.n == 24);
	for (i = 0; i < mf.n; i++) {
		char want[STRAY_SWEEP_UTC_LEN];

		assert_true(isfinite(mf.e[i].date_obs));
		if (i > 0)
			assert_true(mf.e[i].date_obs >= mf.e[i - 1].date_obs);
		snprintf(path, sizeof(path), "%s/s/%s", dir, mf.e[i].file);
		fits_str(path, "DATE-OBS", k0);
		fits_str(path, "DATE-END", k1);
		fits_str(path, "TIMESYS", ts);
		stray_sweep_utc_format(mf.e[i].date_obs, want, sizeof(want));
		want[strlen(want) - 1] = '\0';	/* FITS: no Z */
		assert_string_equal(k0, want);
		assert_true(strcmp(k1, k0) >= 0);
		assert_string_equal(ts, "UTC");
	}
	stray_sweep_manifest_free(&mf);
	remove_tree(dir);
	free(dir);
}

/* alpha at one angle from `stray reduce` (its CSV), or NAN. */
static double alpha_at(const char *csv, double theta)
{
	struct stray_table t;
	struct stray_error se;
	double a = NAN;
	size_t i;
	int ia;

	stray_error_clear(&se);
	if (stray_table_read(csv, &t, &se) != STRAY_OK)
		return NAN;
	ia = stray_table_find(&t, "alpha");
	for (i = 0; ia >= 0 && i < t.n_rows; i++)
		if (fabs(t.cell[i * t.n_cols] - theta) < 1e-6)
			a = t.cell[i * t.n_cols + (size_t)ia];
	stray_table_free(&t);
	return a;
}

/* An angle list returning to 0 deg, a lamp drifting 20 %/h and an hour's
 * pause between the last two on-axis visits: fitted against row order
 * (before) the line puts 10 deg halfway through the pause and alpha(10)
 * comes out ~10 % low; against time it is right. */
static void test_drift_fitted_against_time(void **state)
{
	char *dir = temp_dir(), sub[700], cmd[2048], out[8192], csv[800];
	struct rig_config cfg;
	struct rig_sim sim;
	struct rig_hal hal;
	struct rig_lab lab;
	struct rig_sweep sw;
	struct rig_error err;
	static const double list[5] = { 0, 5, 0, 10, 0 };
	int paused = 0;
	double a, truth;

	(void)state;
	small_config(&cfg);
	memcpy(cfg.sweep.list, list, sizeof(list));
	cfg.sweep.n_list = 5;
	cfg.sim.vlab.lamp_drift_per_h = 0.2;
	rig_error_clear(&err);
	assert_int_equal(rig_sim_init(&sim, &cfg, &hal), RIG_OK);
	assert_int_equal(rig_lab_open(&lab, &cfg, &hal, &err), RIG_OK);
	snprintf(sub, sizeof(sub), "%s/s", dir);
	assert_int_equal(rig_sweep_open(&sw, &lab, sub, 0, &err), RIG_OK);
	while (!sw.finished) {
		if (sw.i_angle == 4 && !paused) {
			rig_hal_sleep(&hal, 3600);	/* lunch, lamp on */
			paused = 1;
		}
		assert_int_equal(rig_sweep_step(&sw, &err), RIG_OK);
	}
	rig_sweep_close(&sw);
	rig_lab_close(&lab);
	rig_sim_fini(&sim);
	snprintf(csv, sizeof(csv), "%s/lens.csv", dir);
	snprintf(cmd, sizeof(cmd), "%s reduce %s --out %s", stray(), sub, csv);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	print_message("%s", out);
	a = alpha_at(csv, 10);
	truth = rig_vlab_lens_alpha(&cfg.sim.vlab, 10, cfg.camera.rows,
				    cfg.camera.n_rows, cfg.camera.col0,
				    cfg.camera.n_cols);
	print_message("alpha(10) %.5f, truth %.5f\n", a, truth);
	assert_true(fabs(a / truth - 1) < 0.01);
	assert_non_null(strstr(out, "fitted against time"));
	remove_tree(dir);
	free(dir);
}

/* The lab's plan: a list in the order taken (0 deg again at the end is
 * a second visit, its frames numbered on), and ranges with their own
 * steps; reduced, with the drift over the returns.  Before: unknown
 * keys. */
static void test_angle_list_and_ranges(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192], path[900];
	struct stray_sweep_manifest mf;
	struct stray_error se;
	const struct stray_sweep_entry *first;

	(void)state;
	put(dir, "l.json", "{" WINDOW ",\"sweep\":{\"theta_list_deg\":"
	    "[0,12,3,0],\"repeats\":2}}");
	put(dir, "r.json", "{" WINDOW ",\"sweep\":{\"theta_ranges_deg\":"
	    "[[0,10,5],[10,11,0.5]],\"repeats\":1}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/l.json --sweep %s/l",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	snprintf(path, sizeof(path), "%s/l", dir);
	stray_error_clear(&se);
	assert_int_equal(stray_sweep_manifest_load(path, &mf, &se), STRAY_OK);
	assert_int_equal(mf.n, 4 * 8);
	assert_true(fabs(mf.e[8].angle_deg - 12) < 1e-9);	/* list order */
	assert_true(fabs(mf.e[16].angle_deg - 3) < 1e-9);
	assert_int_equal(stray_sweep_manifest_count(&mf, 0, STRAY_SWEEP_FULL,
						    &first), 4);
	assert_int_equal(mf.e[24].seqnum, 2);	/* the return: FULL 2, 3 */
	stray_sweep_manifest_free(&mf);
	snprintf(cmd, sizeof(cmd), "%s reduce %s/l --out %s/l.csv", stray(),
		 dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	assert_non_null(strstr(out, "from 2 on-axis visits"));
	snprintf(cmd, sizeof(cmd), "%s --config %s/r.json --sweep %s/r",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	snprintf(path, sizeof(path), "%s/r", dir);
	assert_int_equal(stray_sweep_manifest_load(path, &mf, &se), STRAY_OK);
	/* 0 5 10 10.5 11: the shared end of the ranges taken once */
	assert_int_equal(mf.n, 5 * 4);
	assert_true(fabs(mf.e[mf.n - 1].angle_deg - 11) < 1e-9);
	stray_sweep_manifest_free(&mf);
	/* an angle outside the stage is named by its key */
	put(dir, "bad.json", "{\"sweep\":{\"theta_list_deg\":[0,95]}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/bad.json --sweep %s/b",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 2);
	assert_non_null(strstr(out, "sweep.theta_list_deg"));
	remove_tree(dir);
	free(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_time_in_frames_and_manifest),
		cmocka_unit_test(test_drift_fitted_against_time),
		cmocka_unit_test(test_angle_list_and_ranges),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
