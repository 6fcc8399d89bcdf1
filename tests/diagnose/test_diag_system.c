/*
 * test_diag_system.c - system curves (issue 17 item 3): a baffle + lens
 * measurement diagnosed with `stray diagnose --lens L.csv`.  The truth is
 * traced through a lens whose table differs from the one the analysis is
 * given (a ghost: x5 between 17 and 23 deg) and through a baffle whose
 * coating differs (reflectance 0.06 against 0.04): both must be named,
 * each on its side, the reflectance within its interval; and a lens table
 * off by x3 beyond the field alone must be named as the lens's scale, not
 * as a baffle cause.
 */
#include "diag_test.h"

#include <string.h>

static const double theta[] = {
	0, 5, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30, 35, 40, 45, 50,
	60, 70, 80
};
#define N (sizeof(theta) / sizeof(theta[0]))

/* The lens the analysis is told about: flat in the field, falling to
 * 1e-2 at 12 deg and 1e-3 beyond 30 deg. */
static const double lens_th[] = { 0, 8, 10, 12, 16, 20, 30, 90 };
static const double lens_t[] = { 1, 1, 0.6, 1e-2, 5e-3, 3e-3, 1e-3, 1e-3 };
#define NL (sizeof(lens_th) / sizeof(lens_th[0]))

/* Write the lens table, times ghost inside [lo, hi] (the truth's bump
 * as extra nodes) and times out_factor where below half on axis. */
static void write_lens(const char *path, double ghost, double lo, double hi,
		       double out_factor)
{
	FILE *f = fopen(path, "w");
	double th;

	assert_non_null(f);
	fprintf(f, "theta_deg,alpha\n");
	for (th = 0.0; th <= 90.0 + 1e-9; th += 0.25) {
		size_t k = 0;
		double t;

		while (k + 2 < NL && th > lens_th[k + 1])
			k++;
		t = lens_t[k] + (lens_t[k + 1] - lens_t[k]) *
			(th - lens_th[k]) / (lens_th[k + 1] - lens_th[k]);
		if (t < 0.5)
			t *= out_factor;
		if (th >= lo && th <= hi)
			t *= ghost;
		fprintf(f, "%.2f,%.9g\n", th, t);
	}
	fclose(f);
}

static cJSON *diagnose_system(struct truth_config *c, const char *told)
{
	char path[] = "/tmp/stray_sys_XXXXXX.csv";
	int fd = mkstemps(path, 4);
	char *argv[] = { "stray", "diagnose", path, "--scene", "ref4",
			 "--lens", (char *)told, "--rays", DIAG_TEST_RAYS,
			 "--threads", "2", "--json", NULL };

	return diagnose_argv(c, path, fd, argv, told);
}

static void print_causes(const char *name, const cJSON *j)
{
	const cJSON *c;

	printf("%s: rms %.4f -> %.4f, sun %.2f -> %.2f deg\n", name,
	       cJSON_GetObjectItem(j, "rms_before")->valuedouble,
	       cJSON_GetObjectItem(j, "rms_after")->valuedouble,
	       cJSON_GetObjectItem(j, "sun_deg_before")->valuedouble,
	       cJSON_GetObjectItem(j, "sun_deg_after")->valuedouble);
	cJSON_ArrayForEach(c, cJSON_GetObjectItem(j, "causes")) {
		const cJSON *p;

		printf("  %s (%s):", cJSON_GetObjectItem(c, "name")->valuestring,
		       cJSON_GetObjectItem(c, "side")->valuestring);
		cJSON_ArrayForEach(p, cJSON_GetObjectItem(c, "params")) {
			const cJSON *ci = cJSON_GetObjectItem(
				cJSON_GetObjectItem(c, "intervals"), p->string);

			printf(" %s %.4g [%.4g, %.4g]", p->string, p->valuedouble,
			       cJSON_GetArrayItem(ci, 0)->valuedouble,
			       cJSON_GetArrayItem(ci, 1)->valuedouble);
		}
		printf("\n");
	}
}

static const char *side_of(const cJSON *j, const char *name)
{
	const cJSON *c;

	cJSON_ArrayForEach(c, cJSON_GetObjectItem(j, "causes"))
		if (strcmp(cJSON_GetObjectItem(c, "name")->valuestring,
			   name) == 0)
			return cJSON_GetObjectItem(c, "side")->valuestring;
	return NULL;
}

static void test_ghost_and_reflectance(void **state)
{
	char told[] = "/tmp/stray_lens_told_XXXXXX.csv";
	char truth[] = "/tmp/stray_lens_true_XXXXXX.csv";
	struct truth_config c;
	const cJSON *k;
	cJSON *j;
	int in = 0;

	(void)state;
	close(mkstemps(told, 4));
	close(mkstemps(truth, 4));
	write_lens(told, 1.0, 0.0, -1.0, 1.0);
	write_lens(truth, 5.0, 17.0, 23.0, 1.0);
	truth_defaults(&c, theta, N);
	c.floor_sigma = 1e-9;	/* a camera behind the lens, not a photometer */
	c.lens = truth;
	c.sets[c.n_sets++] = "reflectance=0.06";
	j = diagnose_system(&c, told);
	print_causes(__func__, j);
	if (!getenv("DIAG_TEST_KEEP"))
		unlink(told);
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(j, "significant")));
	assert_non_null(side_of(j, "lens_ghost"));
	assert_string_equal(side_of(j, "lens_ghost"), "lens");
	assert_non_null(side_of(j, "reflectance"));
	assert_string_not_equal(side_of(j, "reflectance"), "lens");
	k = cause(j, "reflectance");
	param(k, "reflectance", 0.06, &in);
	assert_true(in);
	k = cause(j, "lens_ghost");
	param(k, "log10_bump", log10(5.0), &in);
	assert_true(in);
	assert_true(cJSON_GetObjectItem(j, "rms_after")->valuedouble <
		    0.5 * cJSON_GetObjectItem(j, "rms_before")->valuedouble);
	if (!getenv("DIAG_TEST_KEEP"))
		unlink(told);
	unlink(truth);
	cJSON_Delete(j);
}

static void test_lens_scale_alone(void **state)
{
	char told[] = "/tmp/stray_lens_told_XXXXXX.csv";
	char truth[] = "/tmp/stray_lens_true_XXXXXX.csv";
	struct truth_config c;
	cJSON *j;
	int in = 0;

	(void)state;
	close(mkstemps(told, 4));
	close(mkstemps(truth, 4));
	write_lens(told, 1.0, 0.0, -1.0, 1.0);
	write_lens(truth, 1.0, 0.0, -1.0, 3.0);
	truth_defaults(&c, theta, N);
	c.floor_sigma = 1e-9;	/* a camera behind the lens, not a photometer */
	c.lens = truth;
	j = diagnose_system(&c, told);
	print_causes(__func__, j);
	assert_non_null(side_of(j, "lens_scale"));
	assert_int_equal(n_causes(j), 1);	/* nothing on the baffle's side */
	param(cause(j, "lens_scale"), "log10_factor", log10(3.0), &in);
	assert_true(in);
	unlink(told);
	unlink(truth);
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ghost_and_reflectance),
		cmocka_unit_test(test_lens_scale_alone),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
