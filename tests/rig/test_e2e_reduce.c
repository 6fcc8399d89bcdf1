/*
 * test_e2e_reduce.c - the measurement chain end to end: strayrigd sweeps
 * the simulated lab into a folder, `stray reduce` (issue 4, a separate
 * program that knows nothing of the simulator) turns the folder into a
 * lens curve, and the curve must match the virtual lab's own alpha_lens
 * (eq. 3.12 over the same row window) within its stated errors.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <sys/wait.h>

#include "rig_test_util.h"
#include "rig/vlab.h"
#include "stray/table.h"

static const char conf_text[] =
	"{\"camera\":{\"rows\":[960,961,1100,1101],\"col0\":800,"
	"\"n_cols\":256},\"sweep\":{\"theta_stop_deg\":30,"
	"\"theta_step_deg\":5,\"repeats\":3}}";

static int run(const char *cmd)
{
	int status = system(cmd);

	return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void test_e2e_sweep_reduces_to_lens_curve(void **state)
{
	const char *b = getenv("STRAY_BUILD"), *s = getenv("STRAY_BIN");
	char *dir = temp_dir(), conf[600], cmd[2400];
	struct rig_config cfg;
	struct rig_error err;
	struct stray_table t;
	struct stray_error serr;
	int ia, is, i;
	double chi2 = 0;
	FILE *f;

	(void)state;
	snprintf(conf, sizeof(conf), "%s/rig.json", dir);
	f = fopen(conf, "w");
	assert_non_null(f);
	fputs(conf_text, f);
	fclose(f);
	snprintf(cmd, sizeof(cmd), "%s/bin/strayrigd --config %s --sweep "
		 "%s/sweep 2>/dev/null", b ? b : "build", conf, dir);
	assert_int_equal(run(cmd), 0);
	snprintf(cmd, sizeof(cmd), "%s reduce %s/sweep --out %s/lens.csv "
		 ">/dev/null", s ? s : "build/bin/stray", dir, dir);
	assert_int_equal(run(cmd), 0);
	snprintf(cmd, sizeof(cmd), "%s/lens.csv", dir);
	stray_error_clear(&serr);
	assert_int_equal(stray_table_read(cmd, &t, &serr), STRAY_OK);
	ia = stray_table_find(&t, "alpha");
	is = stray_table_find(&t, "sigma");
	assert_true(ia >= 0 && is >= 0 && t.n_rows == 7);
	rig_config_defaults(&cfg);
	rig_error_clear(&err);
	assert_int_equal(rig_config_load(&cfg, conf, &err), RIG_OK);
	for (i = 0; i < (int)t.n_rows; i++) {
		const double *row = t.cell + (size_t)i * t.n_cols;
		double truth = rig_vlab_lens_alpha(&cfg.sim.vlab, row[0],
			cfg.camera.rows, cfg.camera.n_rows, cfg.camera.col0,
			cfg.camera.n_cols);
		double tol = fmax(5 * row[is], 2e-3 * truth);

		print_message("theta %4.1f: alpha %.6f +- %.2g, truth %.6f\n",
			      row[0], row[ia], row[is], truth);
		assert_true(fabs(row[ia] - truth) <= tol);
		if (row[is] > 0)
			chi2 += pow((row[ia] - truth) / row[is], 2);
	}
	print_message("chi2 %.2f over %zu points\n", chi2, t.n_rows - 1);
	/* Deterministic seeds; 3 per point is P < 1e-3 for 6 dof. */
	assert_true(chi2 / (double)(t.n_rows - 1) < 3.0);
	stray_table_free(&t);
	remove_tree(dir);
	free(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_e2e_sweep_reduces_to_lens_curve),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
