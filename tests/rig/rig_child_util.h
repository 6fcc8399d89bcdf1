/*
 * rig_child_util.h - a sweep run in a child process on the simulated lab,
 * for the rig tests that kill and resume it (test_resume.c, test_sigma.c).
 * Include after cmocka.h.
 */
#ifndef RIG_CHILD_UTIL_H
#define RIG_CHILD_UTIL_H

#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#include "rig/config.h"
#include "rig/lab.h"
#include "rig/sim.h"
#include "rig/sweep.h"

/* Child body: one sweep run, resume or fresh; exit 0 when complete. */
static inline int child_sweep(const struct rig_config *cfg, const char *dir,
			      int resume)
{
	struct rig_sim sim;
	struct rig_hal hal;
	struct rig_lab lab;
	struct rig_sweep sw;
	struct rig_error err;
	int rc;

	rig_error_clear(&err);
	rig_sim_init(&sim, cfg, &hal);
	rc = rig_lab_open(&lab, cfg, &hal, &err);
	if (rc == RIG_OK)
		rc = rig_sweep_open(&sw, &lab, dir, resume, &err);
	if (rc == RIG_OK)
		rc = rig_sweep_run(&sw, NULL, &err);
	if (rc != RIG_OK)
		fprintf(stderr, "child: %s\n", err.msg);
	return rc == RIG_OK ? 0 : 1;
}

/* Run a child; returns its wait status. */
static inline int run_child(const struct rig_config *cfg, const char *dir,
			    int resume)
{
	pid_t pid = fork();
	int status = 0;

	assert_true(pid >= 0);
	if (pid == 0)
		_exit(child_sweep(cfg, dir, resume));
	assert_int_equal(waitpid(pid, &status, 0), pid);
	return status;
}

#endif /* RIG_CHILD_UTIL_H */
