/*
 * test_plan.c - one sweep folder, one plan, one writer (rig/sweep/plan.c
 * and the sweep store's lock, seen through strayrigd as a user runs it;
 * issue 14): a resume whose config changed the plan (repeats, angles,
 * exposure) is refused with exit 2 naming the key and leaves the folder
 * as it was, unless --force-plan; two `strayrigd --resume` started
 * together on one folder never both run (one refused, exit 1, one line);
 * resuming a finished sweep prints no "nan".
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig_daemon_util.h"
#include "rig_test_util.h"

#define CONF_FMT "{\"camera\":{\"rows\":[960,961,1100,1101],\"col0\":960," \
	"\"n_cols\":128},\"sweep\":{\"theta_stop_deg\":%s,"                 \
	"\"theta_step_deg\":10,\"repeats\":%d,\"t_max_s\":%s},"              \
	"\"sim\":{\"real_delay_s\":%s}}"

struct run {
	char *dir;
	char conf[600], out[600], err[600], err2[600];
};

static void run_init(struct run *r)
{
	r->dir = temp_dir();
	assert_non_null(r->dir);
	snprintf(r->conf, sizeof(r->conf), "%s/rig.json", r->dir);
	snprintf(r->out, sizeof(r->out), "%s/sweep", r->dir);
	snprintf(r->err, sizeof(r->err), "%s/err.txt", r->dir);
	snprintf(r->err2, sizeof(r->err2), "%s/err2.txt", r->dir);
}

static void configure(struct run *r, const char *stop, int repeats,
		      const char *t_max, const char *delay)
{
	char text[600];

	snprintf(text, sizeof(text), CONF_FMT, stop, repeats, t_max, delay);
	put_file(r->conf, text);
}

/* strayrigd --sweep (with --resume, --force-plan as asked); exit code. */
static int sweep(struct run *r, int resume, int force, const char *errpath)
{
	const char *args[8] = { "--config", r->conf, "--sweep", r->out };
	int n = 4;

	if (resume)
		args[n++] = "--resume";
	if (force)
		args[n++] = "--force-plan";
	args[n] = NULL;
	return wait_exit(spawn_rigd(args, errpath), 60000);
}

static struct rig_config loaded(const struct run *r)
{
	struct rig_config cfg;
	struct rig_error err;

	rig_config_defaults(&cfg);
	rig_error_clear(&err);
	assert_int_equal(rig_config_load(&cfg, r->conf, &err), RIG_OK);
	return cfg;
}

static void test_plan_changed_refused_unless_forced(void **state)
{
	static const struct { const char *stop, *t_max, *key; int reps; }
	change[] = {
		{ "30", "1", "sweep.repeats", 3 },
		{ "40", "1", "sweep.theta_stop_deg", 2 },
		{ "30", "0.5", "sweep.t_max_s", 2 },
	};
	struct rig_config cfg;
	struct run r;
	char msg[1024], before[8192], after[8192], path[700];
	size_t i;

	(void)state;
	run_init(&r);
	configure(&r, "30", 2, "1", "0");
	assert_int_equal(sweep(&r, 0, 0, r.err), 0);
	snprintf(path, sizeof(path), "%s/manifest.csv", r.out);
	get_file(path, before, sizeof(before));
	for (i = 0; i < sizeof(change) / sizeof(*change); i++) {
		configure(&r, change[i].stop, change[i].reps, change[i].t_max,
			  "0");
		assert_int_equal(sweep(&r, 1, 0, r.err), 2);
		get_file(r.err, msg, sizeof(msg));
		print_message("%s", msg);
		assert_non_null(strstr(msg, change[i].key));
		assert_non_null(strstr(msg, "--force-plan"));
		assert_ptr_equal(strchr(msg, '\n'), msg + strlen(msg) - 1);
		get_file(path, after, sizeof(after));
		assert_string_equal(before, after);	/* untouched */
	}
	/* The unchanged plan resumes (nothing to do); the forced change
	 * runs and becomes the plan. */
	configure(&r, "30", 2, "1", "0");
	assert_int_equal(sweep(&r, 1, 0, r.err), 0);
	cfg = loaded(&r);
	assert_int_equal(check_sweep(r.out, &cfg).bad, 0);
	configure(&r, "40", 2, "1", "0");
	assert_int_equal(sweep(&r, 1, 1, r.err), 0);
	cfg = loaded(&r);
	assert_int_equal(check_sweep(r.out, &cfg).bad, 0);
	snprintf(path, sizeof(path), "%s/plan.json", r.out);
	get_file(path, msg, sizeof(msg));
	assert_non_null(strstr(msg, "\"sweep.theta_stop_deg\":\t40"));
	assert_int_equal(sweep(&r, 1, 0, r.err), 0);
	remove_tree(r.dir);
	free(r.dir);
}

/* Resuming a finished sweep: progress lines name a real angle. */
static void test_plan_resume_finished_no_nan(void **state)
{
	struct run r;
	char msg[8192];

	(void)state;
	run_init(&r);
	configure(&r, "30", 2, "1", "0");
	assert_int_equal(sweep(&r, 0, 0, r.err), 0);
	assert_int_equal(sweep(&r, 1, 0, r.err), 0);
	get_file(r.err, msg, sizeof(msg));
	print_message("%s", msg);
	assert_non_null(strstr(msg, "complete"));
	assert_null(strstr(msg, "nan"));
	assert_non_null(strstr(msg, "theta 30.000 deg"));
	remove_tree(r.dir);
	free(r.dir);
}

/* The first of two children to exit: its index; *code its exit code. */
static int first_exit(const pid_t pid[2], int *code, long limit_ms)
{
	double t0 = ms_now();
	int k, status;

	while (ms_now() - t0 < limit_ms) {
		for (k = 0; k < 2; k++)
			if (waitpid(pid[k], &status, WNOHANG) == pid[k]) {
				*code = WIFEXITED(status) ? WEXITSTATUS(status)
							  : 128 + WTERMSIG(status);
				return k;
			}
		nap_ms(5);
	}
	return -1;
}

/* Two `--resume` on one folder at once, a few times: the first to exit
 * is the refused one (exit 1, one line naming the folder in use, before
 * it touched the lab); the other runs, is killed in the first rounds and
 * completes the sweep in the last; the folder then checks clean. */
static void test_plan_two_daemons_one_folder(void **state)
{
	const char *args[] = { "--config", NULL, "--sweep", NULL, "--resume",
			       NULL };
	struct rig_config cfg;
	struct run r;
	char msg[1024];
	int round, rc, k;
	pid_t pid[2];

	(void)state;
	run_init(&r);
	configure(&r, "30", 2, "1", "0.05");
	args[1] = r.conf;
	args[3] = r.out;
	/* A fresh sweep, killed early: the folder exists for the resumes. */
	args[4] = NULL;
	pid[0] = spawn_rigd(args, r.err);
	nap_ms(200);
	kill(pid[0], SIGKILL);
	wait_exit(pid[0], 5000);
	args[4] = "--resume";
	for (round = 0; round < 3; round++) {
		pid[0] = spawn_rigd(args, r.err);
		pid[1] = spawn_rigd(args, r.err2);
		k = first_exit(pid, &rc, 20000);
		assert_true(k >= 0);
		get_file(k ? r.err2 : r.err, msg, sizeof(msg));
		print_message("round %d: daemon %d exits first with %d: %s",
			      round, k, rc, msg);
		assert_int_equal(rc, 1);
		assert_non_null(strstr(msg, "another writer"));
		assert_ptr_equal(strchr(msg, '\n'), msg + strlen(msg) - 1);
		if (round < 2)
			kill(pid[1 - k], SIGKILL);
		rc = wait_exit(pid[1 - k], 60000);
		assert_int_equal(rc, round < 2 ? 128 + SIGKILL : 0);
	}
	cfg = loaded(&r);
	assert_int_equal(check_sweep(r.out, &cfg).bad, 0);
	remove_tree(r.dir);
	free(r.dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_plan_changed_refused_unless_forced),
		cmocka_unit_test(test_plan_resume_finished_no_nan),
		cmocka_unit_test(test_plan_two_daemons_one_folder),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
