/*
 * reduce_partial.c - `stray reduce` on a sweep that is still being taken
 * or was left unfinished says so (one line on stderr, the reduction goes
 * on): a curve from part of a sweep looks like a whole one otherwise.
 * Live: strayrigd holds the folder's lock (an exclusive flock on
 * manifest.csv, sweep_store.h).  Partial: an angle of the folder's plan
 * (plan.json, rig/sweep/plan.c) without its FULL frames.
 */
#define _DEFAULT_SOURCE	/* flock */
#include <cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

#include "cli.h"
#include "reduce_report.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sweep_store.h"

#define PLAN_ANGLES_MAX 100000

static int live(const char *dir)
{
	char path[STRAY_SWEEP_DIR_MAX + 32];
	int fd, busy;

	snprintf(path, sizeof(path), "%s/%s", dir, STRAY_SWEEP_MANIFEST);
	fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0)
		return 0;
	busy = flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
	close(fd);	/* releases the shared lock if it was taken */
	return busy;
}

static double num(const cJSON *plan, const char *key, double dflt)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(plan, key);

	return cJSON_IsNumber(v) ? v->valuedouble : dflt;
}

/* Planned visits not complete (FULL and DARK frames short of repeats
 * for that visit; an angle's k-th visit needs (k + 1) x repeats): how
 * many of how many, and the first. */
static void missing(const cJSON *plan, const struct stray_sweep_manifest *m,
		    long *n_miss, long *n_plan, double *first)
{
	const cJSON *list = cJSON_GetObjectItemCaseSensitive(plan,
						"sweep.theta_list_deg");
	double a0 = num(plan, "sweep.theta_start_deg", 0);
	double a1 = num(plan, "sweep.theta_stop_deg", 0);
	double st = num(plan, "sweep.theta_step_deg", 1);
	long reps = (long)num(plan, "sweep.repeats", 1);
	long k, j, n = cJSON_IsArray(list) ? cJSON_GetArraySize(list) :
		    st > 0 && a1 >= a0 ? (long)floor((a1 - a0) / st + 1e-9) + 1
				       : 0;
	double *ang;

	*n_miss = *n_plan = 0;
	if (n > PLAN_ANGLES_MAX || !(ang = malloc((size_t)(n + 1) *
						  sizeof(*ang))))
		return;
	for (k = 0; k < n; k++) {
		const cJSON *v = cJSON_IsArray(list)
				 ? cJSON_GetArrayItem(list, (int)k) : NULL;
		double a = round(1e3 * (v ? cJSON_GetNumberValue(v)
					  : a0 + k * st)) / 1e3;
		long need = reps;

		ang[k] = a;
		for (j = 0; j < k; j++)
			need += fabs(ang[j] - a) < 5e-4 ? reps : 0;
		(*n_plan)++;
		if (stray_sweep_manifest_count(m, a, STRAY_SWEEP_FULL, NULL) >=
		    need && stray_sweep_manifest_count(m, a, STRAY_SWEEP_DARK,
						       NULL) >= need)
			continue;
		if (!(*n_miss)++)
			*first = a;
	}
	free(ang);
}

void reduce_warn_partial(const char *dir)
{
	struct stray_sweep_manifest m;
	struct stray_error err;
	char path[STRAY_SWEEP_DIR_MAX + 32];
	char *text = NULL;
	size_t len = 0;
	cJSON *plan;
	long n_miss, n_plan;
	double first = 0;

	if (live(dir))
		cli_note("reduce", "%s: the sweep is live (strayrigd is "
			 "writing it): the curve covers the frames taken so "
			 "far", dir);
	snprintf(path, sizeof(path), "%s/plan.json", dir);
	stray_error_clear(&err);
	if (stray_file_read(path, &text, &len, &err) != STRAY_OK)
		return;	/* no plan: nothing to compare with */
	plan = cJSON_ParseWithLength(text, len);
	free(text);
	if (!plan)
		return;
	if (stray_sweep_manifest_load(dir, &m, &err) == STRAY_OK) {
		missing(plan, &m, &n_miss, &n_plan, &first);
		if (n_miss > 0)
			cli_note("reduce", "%s: partial sweep: %ld of %ld "
				 "planned visits not complete (the first at %g "
				 "deg); the curve covers what is there (resume: "
				 "strayrigd --resume)", dir, n_miss, n_plan,
				 first);
		stray_sweep_manifest_free(&m);
	}
	cJSON_Delete(plan);
}
