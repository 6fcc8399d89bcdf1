/*
 * test_vectors.c - the shared vectors (tests/vectors/fdrfw_vectors.h,
 * ground libstray in double precision) reproduced by the firmware: on the
 * host, and on an emulated Cortex-M4F (qemu-system-arm -M mps2-an386,
 * semihosting) running the cross-compiled module with the flight table
 * that `stray firmware-table` wrote as C source.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fdrfw/fdrfw.h"
#include "fixture.h"
#include "stray/curve_io.h"
#include "vectors.h"
#include "../vectors/fdrfw_vectors.h"

#define N_VEC (sizeof(fdrfw_vectors) / sizeof(fdrfw_vectors[0]))
#define TARGET_ELF "build/firmware/fdrfw_vectors.elf"
#define TARGET_DET_ELF "build/firmware/fdrfw_detector.elf"
#define QEMU "timeout 120 qemu-system-arm -M mps2-an386 -nographic " \
	"-monitor none -serial none " \
	"-semihosting-config enable=on,target=native -icount shift=0 -kernel "

/* The vectors' curve file is the fixture's curve (make_vectors.c). */
static void test_curve_file_is_the_fixture(void **state)
{
	const struct stray_curve_view *f = fixture_curve();
	struct stray_curve c;
	struct stray_error err;
	size_t i;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_curve_load("tests/vectors/fdrfw_curve.csv", &c,
					  &err), 0);
	assert_int_equal(c.n, f->n);
	for (i = 0; i < c.n; i++) {
		assert_near(c.theta_deg[i], f->theta_deg[i], 1e-12);
		assert_near(c.alpha[i], f->alpha[i], 1e-9 * f->alpha[i]);
	}
	stray_curve_free(&c);
}

static void test_host_reproduces_vectors(void **state)
{
	struct fdrfw_table t;
	double worst = 0.0;
	size_t i;
	unsigned excluded = 0;

	(void)state;
	fixture_table(&t);
	for (i = 0; i < N_VEC; i++) {
		struct fdrfw_ctx ctx;
		struct fdrfw_input in;
		struct fdrfw_output out;
		int bad;

		assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
		fdrfw_vector_input(&fdrfw_vectors[i], &in);
		assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
		bad = fdrfw_vector_check(&fdrfw_vectors[i], &out, &worst);
		if (bad)
			fail_msg("vector %zu: field %d (flags 0x%02x want 0x%02x,"
				 " ln_fdr %.9g %.9g want %.9g %.9g)", i, bad,
				 (unsigned)out.flags,
				 (unsigned)fdrfw_vectors[i].flags,
				 (double)out.ln_fdr[0], (double)out.ln_fdr[1],
				 fdrfw_vectors[i].ln_fdr[0],
				 fdrfw_vectors[i].ln_fdr[1]);
		excluded += (fdrfw_vectors[i].flags & FDRFW_SUN_EXCLUDED) != 0;
	}
	printf("host: %zu/%zu vectors agree, worst |d ln FDR| %.3g\n",
	       (size_t)N_VEC, (size_t)N_VEC, worst);
	/* The set exercises both sides of the Sun's exclusion angle. */
	assert_true(excluded > 10 && excluded < N_VEC - 10);
}

static void test_emulated_cortex_m4(void **state)
{
	char line[256], all[2048] = "";
	FILE *p;
	int status, agreed = 0;

	(void)state;
	p = popen(QEMU TARGET_ELF " 2>&1", "r");
	assert_non_null(p);
	while (fgets(line, sizeof(line), p)) {
		unsigned ok, n;

		fputs(line, stdout);
		if (strlen(all) + strlen(line) < sizeof(all))
			strcat(all, line);
		if (sscanf(line, "fdrfw-target: %u/%u vectors agree", &ok,
			   &n) == 2)
			agreed = ok == N_VEC && n == N_VEC;
	}
	status = pclose(p);
	if (status != 0 || !agreed)
		fail_msg("emulated run failed (status %d): %s", status, all);
}

/* A detector table (tetra3, version 3) on the emulated Cortex-M4F: its
 * 72 grid nodes answered in float as the table says, the Sun's flag
 * turning at the table's exclusion angle (target_detector.c). */
static void test_emulated_detector_table(void **state)
{
	char line[256], all[2048] = "";
	unsigned nodes = 0, failures = 1;
	FILE *p;
	int status;

	(void)state;
	p = popen(QEMU TARGET_DET_ELF " 2>&1", "r");
	assert_non_null(p);
	while (fgets(line, sizeof(line), p)) {
		const char *f = strstr(line, " deg, ");

		fputs(line, stdout);
		if (strlen(all) + strlen(line) < sizeof(all))
			strcat(all, line);
		if (sscanf(line, "fdrfw-det-target: tetra3 table, %u nodes",
			   &nodes) == 1 && f)
			sscanf(f, " deg, %u failures", &failures);
	}
	status = pclose(p);
	if (status != 0 || nodes != FDRFW_DET_MAX || failures != 0)
		fail_msg("emulated detector run failed (status %d, %u nodes, "
			 "%u failures): %s", status, nodes, failures, all);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_curve_file_is_the_fixture),
		cmocka_unit_test(test_host_reproduces_vectors),
		cmocka_unit_test(test_emulated_cortex_m4),
		cmocka_unit_test(test_emulated_detector_table),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
