/*
 * test_lab_reduce.c - issue 29, the reduction as a lab uses it: several
 * folders of one lens reduced together, a live or partial sweep said so.
 * strayrigd and `stray` run as programs (rig_ops_util.h).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig_test_util.h"
#include "rig_ops_util.h"
#include "rig/vlab.h"
#include "stray/table.h"
#include <cJSON.h>

#define WINDOW "\"camera\":{\"rows\":[960,961],\"col0\":960,\"n_cols\":64}"

static void sweep_into(const char *dir, const char *name, const char *conf)
{
	char cmd[2048], out[8192];

	put(dir, "c.json", conf);
	snprintf(cmd, sizeof(cmd), "%s --config %s/c.json --sweep %s/%s",
		 rigd(), dir, dir, name);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
}

/* A second folder (the field edge, next day) has no 0 deg visit: alone
 * it is refused with what to do, reduced with the first it joins the
 * curve.  Before: "expected one SWEEP_DIR". */
static void test_two_folders_one_curve(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192], csv[800];
	struct stray_table t;
	struct stray_error se;
	struct rig_config cfg;
	size_t i;
	int ia;

	(void)state;
	sweep_into(dir, "a", "{" WINDOW ",\"sweep\":{\"theta_list_deg\":"
		   "[0,5,10,0],\"repeats\":2}}");
	sweep_into(dir, "b", "{" WINDOW ",\"sweep\":{\"theta_list_deg\":"
		   "[12,15,20],\"repeats\":2}}");
	snprintf(csv, sizeof(csv), "%s/lens.csv", dir);
	snprintf(cmd, sizeof(cmd), "%s reduce %s/b --out %s", stray(), dir,
		 csv);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 2);
	assert_non_null(strstr(out, "stray reduce A B"));
	snprintf(cmd, sizeof(cmd), "%s reduce %s/a %s/b --out %s", stray(),
		 dir, dir, csv);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	print_message("%s", out);
	stray_error_clear(&se);
	assert_int_equal(stray_table_read(csv, &t, &se), STRAY_OK);
	assert_int_equal(t.n_rows, 6);
	ia = stray_table_find(&t, "alpha");
	rig_config_defaults(&cfg);
	cfg.camera.n_rows = 2;
	cfg.camera.rows[0] = 960;
	cfg.camera.rows[1] = 961;
	cfg.camera.col0 = 960;
	cfg.camera.n_cols = 64;
	for (i = 0; i < t.n_rows; i++) {
		double th = t.cell[i * t.n_cols];
		double truth = rig_vlab_lens_alpha(&cfg.sim.vlab, th,
			cfg.camera.rows, 2, 960, 64);

		assert_true(fabs(t.cell[i * t.n_cols + (size_t)ia] / truth -
				 1) < 0.01);
	}
	stray_table_free(&t);
	remove_tree(dir);
	free(dir);
}

/* Reducing a sweep that was killed half-way, or one still being taken,
 * says so on stderr and goes on.  Before: not a word. */
static void test_partial_and_live_said(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192], conf[700], sock[700];
	char args[800];
	pid_t pid;

	(void)state;
	put(dir, "k.json", "{" WINDOW ",\"sweep\":{\"theta_list_deg\":"
	    "[0,5,10,0],\"repeats\":2},\"sim\":{\"faults\":[{\"device\":"
	    "\"camera\",\"kind\":\"kill\",\"at\":25}]}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/k.json --sweep %s/k",
		 rigd(), dir, dir);
	assert_int_not_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	snprintf(cmd, sizeof(cmd), "%s reduce %s/k --out %s/k.csv", stray(),
		 dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	print_message("%s", out);
	assert_non_null(strstr(out, "partial sweep: 3 of 4 planned visits"));
	/* live: a socket daemon taking it slowly */
	put(dir, "l.json", "{" WINDOW ",\"sweep\":{\"theta_list_deg\":"
	    "[0,5,10,0],\"repeats\":2},\"sim\":{\"real_delay_s\":0.05}}");
	snprintf(conf, sizeof(conf), "%s/l.json", dir);
	snprintf(sock, sizeof(sock), "%s/rig.sock", dir);
	pid = serve(dir, conf, sock);
	snprintf(args, sizeof(args), "sweep %s/l", dir);
	assert_int_equal(rig_cli(dir, sock, args, out, sizeof(out)), 0);
	nap(1500);	/* the first visit's frames */
	snprintf(cmd, sizeof(cmd), "%s reduce %s/l --out %s/l.csv", stray(),
		 dir, dir);
	run_out(cmd, dir, out, sizeof(out));
	stop(pid);
	print_message("%s", out);
	assert_non_null(strstr(out, "the sweep is live"));
	remove_tree(dir);
	free(dir);
}

/* The demo sweep's one simulated ghost (vlab: 1000 + 8 px/deg) is one
 * track, following its line.  Before: ghosts A 14-16, B 16-18, C 18-25
 * and D 19-23 deg, a peak that splits in two some 6 px apart. */
static void test_one_ghost_one_track(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[65536];
	cJSON *r, *g, *th, *col;
	int i;

	(void)state;
	snprintf(cmd, sizeof(cmd), "%s --config examples/rig-demo.json "
		 "--sweep %s/demo", rigd(), dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	snprintf(cmd, sizeof(cmd), "%s reduce %s/demo --out %s/lens.csv "
		 "--json 2>/dev/null", stray(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	r = cJSON_Parse(out);
	assert_non_null(r);
	g = cJSON_GetObjectItem(r, "ghosts");
	print_message("%d ghost track(s)\n", cJSON_GetArraySize(g));
	assert_int_equal(cJSON_GetArraySize(g), 1);
	th = cJSON_GetObjectItem(cJSON_GetArrayItem(g, 0), "theta_deg");
	col = cJSON_GetObjectItem(cJSON_GetArrayItem(g, 0), "column");
	assert_true(cJSON_GetArraySize(th) >= 10);
	for (i = 0; i < cJSON_GetArraySize(th); i++) {
		double t = cJSON_GetNumberValue(cJSON_GetArrayItem(th, i));
		double c = cJSON_GetNumberValue(cJSON_GetArrayItem(col, i));

		print_message("  %4.1f deg: column %.1f\n", t, c);
		assert_true(fabs(c - (1000 + 8 * t)) < 12);
	}
	cJSON_Delete(r);
	remove_tree(dir);
	free(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_folders_one_curve),
		cmocka_unit_test(test_partial_and_live_said),
		cmocka_unit_test(test_one_ghost_one_track),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
