/*
 * diag_test.h - what the diagnose tests share: write a hidden-effect curve
 * with the truth generator, run `stray diagnose --json` on it as a user
 * would, and read the verdict (causes named, parameters, intervals).
 */
#ifndef STRAY_TESTS_DIAG_TEST_H
#define STRAY_TESTS_DIAG_TEST_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cJSON.h>
#include <math.h>

#include "tools/run_cli.h"
#include "truth.h"

/* The logged sweep of the tests: few angles keep them fast. */
static const double diag_test_theta[] = {
	0, 5, 10, 15, 20, 22, 24, 26, 28, 30, 35, 40, 45, 50, 55, 60, 70, 80
};
#define DIAG_TEST_N (sizeof(diag_test_theta) / sizeof(diag_test_theta[0]))
#define DIAG_TEST_RAYS "100000"

/* Write `c` into path (a temporary file of fd, named in argv), run argv;
 * the --json verdict (free it).  DIAG_TEST_KEEP keeps the file to rerun
 * by hand (told: the lens the analysis was told, or NULL). */
static inline cJSON *diagnose_argv(const struct truth_config *c,
				   const char *path, int fd, char **argv,
				   const char *told)
{
	static struct cli_run r;
	cJSON *j;

	assert_true(fd >= 0);
	close(fd);
	assert_int_equal(truth_write(c, path), 0);
	run_stray(&r, argv);
	if (getenv("DIAG_TEST_KEEP"))	/* to rerun by hand */
		fprintf(stderr, "kept %s%s%s\n", path, told ? " with " : "",
			told ? told : "");
	else
		unlink(path);
	if (r.status != 0)
		fprintf(stderr, "stray diagnose: %s\n", r.err);
	assert_int_equal(r.status, 0);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	return j;
}

/* Generate `c` into a temporary file, diagnose it; the JSON (free it). */
static inline cJSON *diagnose_truth(const struct truth_config *c)
{
	char path[] = "/tmp/stray_diag_XXXXXX.csv";
	int fd = mkstemps(path, 4);
	char *argv[] = { "stray", "diagnose", path, "--scene", "ref4",
			 "--rays", DIAG_TEST_RAYS, "--threads", "2", "--json",
			 NULL };

	return diagnose_argv(c, path, fd, argv, NULL);
}

/* The same, the analysis told the scene `scene` (a scene file). */
static inline cJSON *diagnose_truth_on(const struct truth_config *c,
				       const char *scene)
{
	char path[] = "/tmp/stray_diag_XXXXXX.csv";
	int fd = mkstemps(path, 4);
	char *argv[] = { "stray", "diagnose", path, "--scene", (char *)scene,
			 "--rays", DIAG_TEST_RAYS, "--threads", "2", "--json",
			 NULL };

	return diagnose_argv(c, path, fd, argv, NULL);
}

static inline int n_causes(const cJSON *j)
{
	return cJSON_GetArraySize(cJSON_GetObjectItem(j, "causes"));
}

/* The named cause `name`, or NULL. */
static inline const cJSON *cause(const cJSON *j, const char *name)
{
	const cJSON *c;

	cJSON_ArrayForEach(c, cJSON_GetObjectItem(j, "causes")) {
		const cJSON *n = cJSON_GetObjectItem(c, "name");

		if (cJSON_IsString(n) && strcmp(n->valuestring, name) == 0)
			return c;
	}
	return NULL;
}

/* The fitted value of a named cause's parameter, and whether `truth`
 * lies inside its stated interval. */
static inline double param(const cJSON *c, const char *name, double truth,
		    int *inside)
{
	const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(c, "params"),
					     name);
	const cJSON *ci = cJSON_GetObjectItem(
		cJSON_GetObjectItem(c, "intervals"), name);
	double lo, hi;

	assert_true(cJSON_IsNumber(v));
	assert_int_equal(cJSON_GetArraySize(ci), 2);
	lo = cJSON_GetArrayItem(ci, 0)->valuedouble;
	hi = cJSON_GetArrayItem(ci, 1)->valuedouble;
	*inside = truth >= lo && truth <= hi;
	fprintf(stderr, "  %s = %.4g [%.4g, %.4g], truth %.4g: %s\n", name,
		v->valuedouble, lo, hi, truth, *inside ? "inside" : "OUTSIDE");
	return v->valuedouble;
}

static inline double num(const cJSON *j, const char *key)
{
	const cJSON *v = cJSON_GetObjectItem(j, key);

	assert_true(cJSON_IsNumber(v));
	return v->valuedouble;
}

static inline int flag(const cJSON *j, const char *key)
{
	const cJSON *v = cJSON_GetObjectItem(j, key);

	assert_true(cJSON_IsBool(v));
	return cJSON_IsTrue(v);
}

/* Print the verdict so a failure explains itself. */
static inline void show(const char *test, const cJSON *j)
{
	const cJSON *c;

	fprintf(stderr, "%s: significant %d explained %d, rms %.4f -> %.4f, "
		"causes:", test, flag(j, "significant"), flag(j, "explained"),
		num(j, "rms_before"), num(j, "rms_after"));
	cJSON_ArrayForEach(c, cJSON_GetObjectItem(j, "causes"))
		fprintf(stderr, " %s",
			cJSON_GetObjectItem(c, "name")->valuestring);
	fputc('\n', stderr);
}

/* One hidden cause: exactly it named, its parameter inside. */
static inline void expect_one(const char *test, const cJSON *j, const char *name,
		       const char *pname, double truth)
{
	const cJSON *c = cause(j, name);
	int inside = 0;

	show(test, j);
	assert_true(flag(j, "significant"));
	assert_int_equal(n_causes(j), 1);
	assert_non_null(c);
	if (pname) {
		param(c, pname, truth, &inside);
		assert_true(inside);
	}
	assert_true(num(j, "rms_after") < num(j, "rms_before"));
}

#endif /* STRAY_TESTS_DIAG_TEST_H */
