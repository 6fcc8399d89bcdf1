/*
 * test_lab_safety.c - issue 29: safety that never overstates, the event
 * log, and `safe` keeping the sweep.  strayrigd and `stray rig` run as
 * programs (rig_ops_util.h).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig_test_util.h"
#include "rig_ops_util.h"

#define WINDOW "\"camera\":{\"rows\":[960,961],\"col0\":960,\"n_cols\":64}"

/* The GPIO chip lost mid-sweep (socket mode): the daemon must not say
 * "safe", status names each line it cannot read back and `stray rig
 * status` exits non-zero while faulted.  Before: "sweep stopped safe",
 * lamp -1 and exit 0. */
static void test_gpio_lost_socket_mode(void **state)
{
	char *dir = temp_dir(), conf[700], sock[700], out[8192], err[8192];
	char args[800], path[700];
	pid_t pid;

	(void)state;
	put(dir, "c.json", "{" WINDOW ",\"sweep\":{\"theta_stop_deg\":10,"
	    "\"theta_step_deg\":5},\"sim\":{\"faults\":[{\"device\":\"gpio\","
	    "\"kind\":\"disconnect\",\"at\":30,\"count\":1000}]}}");
	snprintf(conf, sizeof(conf), "%s/c.json", dir);
	snprintf(sock, sizeof(sock), "%s/rig.sock", dir);
	pid = serve(dir, conf, sock);
	snprintf(args, sizeof(args), "sweep %s/s", dir);
	assert_int_equal(rig_cli(dir, sock, args, out, sizeof(out)), 0);
	assert_true(wait_for_state(dir, sock, "faulted", out, sizeof(out)));
	print_message("%s", out);
	assert_non_null(strstr(out, "\"safe\":false"));
	assert_non_null(strstr(out, "lamp unknown"));
	assert_null(strstr(out, ":-1"));
	assert_int_equal(rig_cli(dir, sock, "status", out, sizeof(out)), 1);
	print_message("%s", out);
	assert_non_null(strstr(out, "safe: NO"));
	assert_non_null(strstr(out, "faulted"));
	stop(pid);
	snprintf(path, sizeof(path), "%s/served.err", dir);
	slurp(path, err, sizeof(err));
	print_message("%s", err);
	assert_null(strstr(err, "stopped safe"));
	assert_non_null(strstr(err, "safe state NOT confirmed"));
	remove_tree(dir);
	free(dir);
}

/* --sweep mode says it in the same words. */
static void test_gpio_lost_sweep_mode(void **state)
{
	char *dir = temp_dir(), cmd[2048], out[8192];

	(void)state;
	put(dir, "c.json", "{" WINDOW ",\"sweep\":{\"theta_stop_deg\":10,"
	    "\"theta_step_deg\":5},\"sim\":{\"faults\":[{\"device\":\"gpio\","
	    "\"kind\":\"disconnect\",\"at\":30,\"count\":1000}]}}");
	snprintf(cmd, sizeof(cmd), "%s --config %s/c.json --sweep %s/s",
		 rigd(), dir, dir);
	assert_int_equal(run_out(cmd, dir, out, sizeof(out)), 1);
	assert_non_null(strstr(out, "safe state NOT confirmed: shutter "
				    "unknown, beam_block unknown, lamp "
				    "unknown"));
	remove_tree(dir);
	free(dir);
}

/* The event log: start, the plan and owner, each fault retried and its
 * recovery, operator commands and completion, stamped in UTC, in the
 * sweep folder.  Before: no log at all, recoveries only a count. */
static void test_event_log_in_folder(void **state)
{
	char *dir = temp_dir(), conf[700], sock[700], out[8192];
	char log[16384], args[800], path[700];
	pid_t pid;

	(void)state;
	put(dir, "c.json", "{" WINDOW ",\"sweep\":{\"theta_stop_deg\":10,"
	    "\"theta_step_deg\":5},\"sim\":{\"faults\":[{\"device\":"
	    "\"camera\",\"kind\":\"timeout\",\"at\":12,\"count\":1}]}}");
	snprintf(conf, sizeof(conf), "%s/c.json", dir);
	snprintf(sock, sizeof(sock), "%s/rig.sock", dir);
	pid = serve(dir, conf, sock);
	snprintf(args, sizeof(args), "sweep %s/s", dir);
	assert_int_equal(rig_cli(dir, sock, args, out, sizeof(out)), 0);
	assert_true(wait_for_state(dir, sock, "idle", out, sizeof(out)));
	stop(pid);
	snprintf(path, sizeof(path), "%s/s/events.log", dir);
	slurp(path, log, sizeof(log));
	print_message("%s", log);
	/* every line begins with its UTC time */
	assert_true(strlen(log) > 24 && log[4] == '-' && log[10] == 'T' &&
		    log[23] == 'Z');
	assert_non_null(strstr(log, "sweep started in"));
	assert_non_null(strstr(log, "3 angles 0..10 deg (0 returns)"));
	assert_non_null(strstr(log, "retry 1 of 3"));
	assert_non_null(strstr(log, "camera recovered after 1 retry"));
	assert_non_null(strstr(log, "sweep complete"));
	snprintf(path, sizeof(path), "%s/s/plan.json", dir);
	slurp(path, log, sizeof(log));
	assert_non_null(strstr(log, "\"owner\""));
	remove_tree(dir);
	free(dir);
}

/* `safe` during a sweep makes the lab safe and keeps the sweep: status
 * shows it paused, `resume` finishes it.  Before: the sweep was dropped
 * without a word. */
static void test_safe_keeps_sweep(void **state)
{
	char *dir = temp_dir(), conf[700], sock[700], out[8192], args[800];
	pid_t pid;

	(void)state;
	put(dir, "c.json", "{" WINDOW ",\"sweep\":{\"theta_stop_deg\":20,"
	    "\"theta_step_deg\":5},\"sim\":{\"real_delay_s\":0.01}}");
	snprintf(conf, sizeof(conf), "%s/c.json", dir);
	snprintf(sock, sizeof(sock), "%s/rig.sock", dir);
	pid = serve(dir, conf, sock);
	snprintf(args, sizeof(args), "sweep %s/s", dir);
	assert_int_equal(rig_cli(dir, sock, args, out, sizeof(out)), 0);
	nap(100);
	assert_int_equal(rig_cli(dir, sock, "safe", out, sizeof(out)), 0);
	print_message("%s", out);
	assert_non_null(strstr(out, "resume"));
	assert_int_equal(rig_cli(dir, sock, "--json status", out, sizeof(out)),
			 0);
	assert_non_null(strstr(out, "\"state\":\"paused\""));
	assert_non_null(strstr(out, "\"sweep\""));
	assert_non_null(strstr(out, "\"safe\":true"));
	assert_int_equal(rig_cli(dir, sock, "resume", out, sizeof(out)), 0);
	assert_true(wait_for_state(dir, sock, "idle", out, sizeof(out)));
	assert_non_null(strstr(out, "\"finished\":true"));
	stop(pid);
	remove_tree(dir);
	free(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_gpio_lost_socket_mode),
		cmocka_unit_test(test_gpio_lost_sweep_mode),
		cmocka_unit_test(test_event_log_in_folder),
		cmocka_unit_test(test_safe_keeps_sweep),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
