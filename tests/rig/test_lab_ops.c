/*
 * test_lab_ops.c - the lab as an operator runs it (issue 29): strayrigd
 * and `stray` run as programs (STRAY_BUILD/bin/strayrigd, STRAY_BIN), so
 * each test fails on a build without the fix.  This file: configs
 * checked against the devices, the reduction refusing clipped frames.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig_test_util.h"
#include "rig_ops_util.h"
#include "rig/sim.h"

/* The reproducer: a 14-bit saturation level on the 12-bit
 * camera is refused before anything moves, naming the key and the
 * camera's limit; no sweep folder is made. */
static void test_sat_dn_above_adc_refused(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192], path[700];
	struct stat st;

	(void)state;
	put(dir, "c.json", "{\"backend\":\"sim\",\"camera\":{\"sat_dn\":16383,"
	    "\"rows\":[960,961],\"col0\":960,\"n_cols\":64},"
	    "\"sweep\":{\"theta_stop_deg\":10,\"theta_step_deg\":5}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/c.json --sweep %s/s",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 2);
	print_message("%s", out);
	assert_non_null(strstr(out, "camera.sat_dn"));
	assert_non_null(strstr(out, "12-bit"));
	assert_non_null(strstr(out, "4095"));
	snprintf(path, sizeof(path), "%s/s/manifest.csv", dir);
	assert_int_not_equal(stat(path, &st), 0);
	remove_tree(dir);
	free(dir);
}

/* A wheel with fewer slots than wheel.trans lists is refused too. */
static void test_wheel_slots_checked(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192];

	(void)state;
	put(dir, "c.json", "{\"sim\":{\"wheel_slots\":4},"
	    "\"camera\":{\"rows\":[960,961],\"col0\":960,\"n_cols\":64},"
	    "\"sweep\":{\"theta_stop_deg\":10,\"theta_step_deg\":5}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/c.json --sweep %s/s",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 2);
	print_message("%s", out);
	assert_non_null(strstr(out, "wheel.trans"));
	assert_non_null(strstr(out, "reports 4"));
	remove_tree(dir);
	free(dir);
}

/* A folder whose frames clip at 4095 while SATLEVEL says 16383 (taken
 * by a lab opened with the right level, then given the wrong one, as a
 * build without the start-up check would) is refused by the reduction
 * whatever the header says: before, alpha 1.0000 at every angle. */
static void test_reduce_refuses_clipped_frames(void **state)
{
	char *dir = temp_dir(), sub[700], cmd[2048], out[8192];
	struct rig_config cfg;
	struct rig_sim sim;
	struct rig_hal hal;
	struct rig_lab lab;
	struct rig_sweep sw;
	struct rig_error err;

	(void)state;
	small_config(&cfg);
	cfg.sweep.theta_stop_deg = 10;
	rig_error_clear(&err);
	assert_int_equal(rig_sim_init(&sim, &cfg, &hal), RIG_OK);
	assert_int_equal(rig_lab_open(&lab, &cfg, &hal, &err), RIG_OK);
	cfg.camera.sat_dn = 16383;
	snprintf(sub, sizeof(sub), "%s/s", dir);
	assert_int_equal(rig_sweep_open(&sw, &lab, sub, 0, &err), RIG_OK);
	assert_int_equal(rig_sweep_run(&sw, NULL, &err), RIG_OK);
	rig_sweep_close(&sw);
	rig_lab_close(&lab);
	rig_sim_fini(&sim);
	snprintf(cmd, sizeof(cmd), "%s reduce %s --out %s/lens.csv", stray(),
		 sub, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 2);
	print_message("%s", out);
	assert_non_null(strstr(out, "clipped at 4095"));
	assert_non_null(strstr(out, "camera.sat_dn"));
	remove_tree(dir);
	free(dir);
}

/* A standalone --sweep beside the socket daemon on the same lab (other
 * socket, other folder) is refused by the device locks, naming the
 * device and the holder, before it touches a device or makes a folder. */
static void test_device_lock_lab_wide(void **state)
{
	char *dir = temp_dir(), conf[700], sock[700], cmd[2048], out[8192];
	char text[1200], path[700];
	struct stat st;
	pid_t pid;

	(void)state;
	snprintf(text, sizeof(text), "{\"lock_dir\":\"%s\",\"camera\":"
		 "{\"rows\":[960,961],\"col0\":960,\"n_cols\":64},"
		 "\"sweep\":{\"theta_stop_deg\":10,\"theta_step_deg\":5}}",
		 dir);
	put(dir, "c.json", text);
	snprintf(conf, sizeof(conf), "%s/c.json", dir);
	snprintf(sock, sizeof(sock), "%s/rig.sock", dir);
	pid = serve(dir, conf, sock);
	snprintf(cmd, sizeof(cmd), "%s --config %s --sweep %s/s", rigd(),
		 conf, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 1);
	stop(pid);
	print_message("%s", out);
	assert_non_null(strstr(out, "in use by another daemon"));
	assert_non_null(strstr(out, "pid"));
	snprintf(path, sizeof(path), "%s/s", dir);
	assert_int_not_equal(stat(path, &st), 0);
	/* Released at exit: the same sweep now runs. */
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 0);
	remove_tree(dir);
	free(dir);
}

/* Errors say their cause and what to do: a folder that cannot be made
 * names the system's reason; a plan the disk cannot hold is refused
 * before the first move, with both figures.  Before: "cannot create the
 * sweep folder", and a sweep that ran into the full disk. */
static void test_errors_with_causes(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192], path[700];
	struct stat st;

	(void)state;
	put(dir, "c.json", "{\"camera\":{\"rows\":[960,961],\"col0\":960,"
	    "\"n_cols\":64},\"sweep\":{\"theta_stop_deg\":10,"
	    "\"theta_step_deg\":5}}");
	put(dir, "afile", "not a folder\n");
	snprintf(cmd, sizeof(cmd), "%s --config %s/c.json --sweep %s/afile/s",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 1);
	print_message("%s", out);
	assert_non_null(strstr(out, "Not a directory"));
	assert_non_null(strstr(out, "choose another"));
	/* 1781 angles x 1000 repeats of 14 full rows: ~600 GB */
	put(dir, "big.json", "{\"sweep\":{\"theta_ranges_deg\":"
	    "[[0,89,0.05]],\"repeats\":1000}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/big.json --sweep %s/big",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 1);
	print_message("%s", out);
	assert_non_null(strstr(out, "not enough free space"));
	assert_non_null(strstr(out, "MB free"));
	snprintf(path, sizeof(path), "%s/big", dir);
	assert_int_not_equal(stat(path, &st), 0);
	remove_tree(dir);
	free(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sat_dn_above_adc_refused),
		cmocka_unit_test(test_wheel_slots_checked),
		cmocka_unit_test(test_reduce_refuses_clipped_frames),
		cmocka_unit_test(test_device_lock_lab_wide),
		cmocka_unit_test(test_errors_with_causes),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
