/*
 * test_footprint.c - the Cortex-M4F footprint in the test log (issue #6):
 * runs `make firmware`'s report on the built image and holds the flight
 * code (the module and the libstray core compiled into it, in float) to
 * issue #6's budgets: code <= 8 KiB, static RAM <= 64 B, static stack of
 * a frame and of init <= 512 B.  The whole image with newlib's libm is
 * printed and discussed in firmware_fdr/README.md.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>

#include <cmocka.h>

static void test_module_within_budget(void **state)
{
	char line[512];
	FILE *p;
	int lines = 0;

	(void)state;
	p = popen("python3 firmware_fdr/target/footprint.py build/firmware/obj "
		  "build/firmware/fdrfw_footprint.elf.map --check 2>&1", "r");
	assert_non_null(p);
	while (fgets(line, sizeof(line), p)) {
		fputs(line, stdout);
		lines++;
	}
	assert_int_equal(pclose(p), 0);
	assert_true(lines > 8);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_module_within_budget),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
