/*
 * test_resume.c - crash and resume.  A child process running a sweep is
 * killed with SIGKILL, by the simulator at a chosen device event (between
 * any two protocol exchanges) or by this process at a random moment of a
 * real-time strayrigd run; the sweep is then resumed, possibly killed
 * again, and the folder is checked: every frame present once, labelled as
 * its FITS header says, hashes matching, nothing extra.
 * RIG_TEST_SEED picks other kill points (default 1).
 */
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <time.h>

#include "rig/lab.h"
#include "rig/sim.h"
#include "rig/sweep.h"
#include "rig_child_util.h"
#include "rig_test_util.h"

static unsigned seed(void)
{
	const char *s = getenv("RIG_TEST_SEED");

	return s ? (unsigned)strtoul(s, NULL, 10) : 1u;
}

static void test_resume_after_kills_at_device_events(void **state)
{
	static const int devs[] = { RIG_DEV_CAMERA, RIG_DEV_CAMERA,
				    RIG_DEV_STAGE, RIG_DEV_WHEEL,
				    RIG_DEV_GPIO };
	struct rig_config cfg, killer;
	struct sweep_check c;
	char *dir = temp_dir();
	int round, status;

	(void)state;
	srand(seed());
	small_config(&cfg);
	/* First run is fresh; every later one resumes; each is killed. */
	for (round = 0; round < 5; round++) {
		struct rig_fault *f = &killer.sim.faults[0];

		killer = cfg;
		killer.sim.n_faults = 1;
		f->device = devs[round];
		f->kind = RIG_FAULT_KILL;
		f->at = 1 + (unsigned)rand() %
			(devs[round] == RIG_DEV_CAMERA ? 12 : 3);
		f->count = 1;
		status = run_child(&killer, dir, round > 0);
		print_message("round %d: kill at event %u of device %d: %s\n",
			      round, f->at, f->device,
			      WIFSIGNALED(status) ? "killed" : "finished");
		if (WIFSIGNALED(status))
			assert_int_equal(WTERMSIG(status), SIGKILL);
		else
			assert_int_equal(WEXITSTATUS(status), 0);
	}
	status = run_child(&cfg, dir, 1);
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	c = check_sweep(dir, &cfg);
	assert_int_equal(c.bad, 0);
	assert_true(c.rows >= 4 * 2 * 3);
	remove_tree(dir);
	free(dir);
}

/* A torn manifest line, a leftover temporary and an unlisted frame are
 * what a kill inside a write leaves; resume must clean and redo them. */
static void test_resume_repairs_torn_tail(void **state)
{
	struct rig_config cfg, killer;
	char *dir = temp_dir(), path[1024], cmd[2200];
	int fd, status;

	(void)state;
	small_config(&cfg);
	killer = cfg;
	killer.sim.n_faults = 1;
	killer.sim.faults[0] = (struct rig_fault){ RIG_DEV_CAMERA,
					       RIG_FAULT_KILL, 14, 1, 0 };
	status = run_child(&killer, dir, 0);
	assert_true(WIFSIGNALED(status));
	snprintf(path, sizeof(path), "%s/manifest.csv", dir);
	fd = open(path, O_WRONLY | O_APPEND);
	assert_true(fd >= 0);
	assert_int_equal(write(fd, "a+010.000_FU", 12), 12);
	close(fd);
	snprintf(cmd, sizeof(cmd),
		 "cp '%s'/a+000.000_FULL_000.fits '%s'/a+030.000_FULL_001.fits"
		 " && echo junk > '%s'/a+030.000_DARK_000.fits.tmp", dir, dir,
		 dir);
	assert_int_equal(system(cmd), 0);
	status = run_child(&cfg, dir, 1);
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	assert_int_equal(check_sweep(dir, &cfg).bad, 0);
	remove_tree(dir);
	free(dir);
}

/* rig_sweep_open's code when resuming dir. */
static int resume_code(const struct rig_config *cfg, const char *dir)
{
	struct rig_sim sim;
	struct rig_hal hal;
	struct rig_lab lab;
	struct rig_sweep sw;
	struct rig_error err;
	int rc;

	rig_error_clear(&err);
	rig_sim_init(&sim, cfg, &hal);
	assert_int_equal(rig_lab_open(&lab, cfg, &hal, &err), RIG_OK);
	rc = rig_sweep_open(&sw, &lab, dir, 1, &err);
	print_message("resume: %s\n", err.msg);
	if (rc == RIG_OK)
		rig_sweep_close(&sw);
	rig_lab_close(&lab);
	rig_sim_fini(&sim);
	return rc;
}

/* A manifest row whose file changed is refused, never silently reused. */
static void test_resume_refuses_hash_mismatch(void **state)
{
	struct rig_config cfg;
	struct stray_sweep_manifest mf;
	struct stray_error err;
	char *dir = temp_dir(), cmd[1200], msg[400];

	(void)state;
	small_config(&cfg);
	assert_int_equal(run_child(&cfg, dir, 0), 0);
	snprintf(cmd, sizeof(cmd), "printf X >> '%s'/a+010.000_DARK_000.fits",
		 dir);
	assert_int_equal(system(cmd), 0);
	stray_error_clear(&err);
	assert_int_not_equal(stray_sweep_store_open(&mf, dir, 1, &err),
			     STRAY_OK);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, "a+010.000_DARK_000.fits"));
	assert_non_null(strstr(msg, "sha256"));
	stray_sweep_manifest_free(&mf);
	/* The sweep refuses the resume as an I/O fault (strayrigd exit 1). */
	assert_int_equal(resume_code(&cfg, dir), RIG_EIO);
	remove_tree(dir);
	free(dir);
}

/* One writer per sweep folder: a second one is refused while the first
 * holds it, and admitted once it let go. */
static void test_store_one_writer(void **state)
{
	struct stray_sweep_manifest a, b;
	struct stray_error err;
	char *dir = temp_dir(), sub[600], msg[400];

	(void)state;
	snprintf(sub, sizeof(sub), "%s/s", dir);
	stray_error_clear(&err);
	assert_int_equal(stray_sweep_store_open(&a, sub, 0, &err), STRAY_OK);
	assert_int_equal(stray_sweep_store_open(&b, sub, 1, &err), STRAY_EIO);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, "another writer"));
	stray_sweep_manifest_free(&a);
	stray_error_clear(&err);
	assert_int_equal(stray_sweep_store_open(&b, sub, 1, &err), STRAY_OK);
	assert_int_equal(b.n, 0);
	stray_sweep_manifest_free(&b);
	remove_tree(dir);
	free(dir);
}

static void write_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

/* strayrigd itself, killed by this process at random moments. */
static void test_resume_daemon_killed_by_parent(void **state)
{
	const char *bin_dir = getenv("STRAY_BUILD");
	char bin[512], conf[1100], out[1100];
	char *dir = temp_dir();
	struct rig_config cfg;
	int round;

	(void)state;
	snprintf(bin, sizeof(bin), "%s/bin/strayrigd",
		 bin_dir ? bin_dir : "build");
	snprintf(conf, sizeof(conf), "%s/rig.json", dir);
	snprintf(out, sizeof(out), "%s/sweep", dir);
	write_file(conf, "{\"camera\":{\"rows\":[960,961,1100,1101],"
		   "\"col0\":960,\"n_cols\":128},"
		   "\"sweep\":{\"theta_stop_deg\":30,\"theta_step_deg\":10,"
		   "\"repeats\":2},\"sim\":{\"real_delay_s\":0.002}}");
	srand(seed() + 7);
	for (round = 0; round < 4; round++) {
		struct timespec ts = { 0, 1000000L * (5 + rand() % 150) };
		pid_t pid = fork();
		int status;

		assert_true(pid >= 0);
		if (pid == 0) {
			int nul = open("/dev/null", O_WRONLY);

			dup2(nul, 2);
			if (round == 0)
				execl(bin, bin, "--config", conf, "--sweep",
				      out, (char *)NULL);
			else
				execl(bin, bin, "--config", conf, "--sweep",
				      out, "--resume", (char *)NULL);
			_exit(127);
		}
		nanosleep(&ts, NULL);
		kill(pid, SIGKILL);
		assert_int_equal(waitpid(pid, &status, 0), pid);
		print_message("round %d: kill after %ld ms: %s\n", round,
			      ts.tv_nsec / 1000000,
			      WIFSIGNALED(status) ? "killed" : "had finished");
	}
	rig_config_defaults(&cfg);
	{
		struct rig_error err;

		rig_error_clear(&err);
		assert_int_equal(rig_config_load(&cfg, conf, &err), RIG_OK);
	}
	assert_int_equal(run_child(&cfg, out, 1), 0);
	assert_int_equal(check_sweep(out, &cfg).bad, 0);
	remove_tree(dir);
	free(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_resume_after_kills_at_device_events),
		cmocka_unit_test(test_resume_repairs_torn_tail),
		cmocka_unit_test(test_resume_refuses_hash_mismatch),
		cmocka_unit_test(test_store_one_writer),
		cmocka_unit_test(test_resume_daemon_killed_by_parent),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
