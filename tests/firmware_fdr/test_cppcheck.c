/*
 * test_cppcheck.c - issue #6 asks firmware_fdr to be cppcheck clean, with
 * the findings of its MISRA C:2012 addon fixed or justified in
 * firmware_fdr/README.md.  General checks must find nothing; MISRA
 * findings may not exceed, rule by rule, the deviations the README
 * justifies (a ratchet: a new kind or a new instance fails).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define SOURCES "firmware_fdr/*.c"
#define INCLUDES "-Ifirmware_fdr/include -Ilibstray/include"

/* The README's table of justified deviations. */
static const struct { const char *rule; int allowed; } justified[] = {
	{ "12.1", 64 }, { "15.6", 22 }, { "15.5", 16 }, { "10.8", 15 },
	{ "12.3", 15 }, { "10.4", 6 }, { "2.5", 17 }, { "2.3", 3 },
	{ "2.4", 2 }, { "8.9", 2 }, { "20.10", 2 }, { "8.7", 3 },
	{ "20.7", 5 },
};

#define N_JUSTIFIED (sizeof(justified) / sizeof(justified[0]))

static int have_cppcheck(void)
{
	return system("cppcheck --version >/dev/null 2>&1") == 0;
}

static void test_general_checks_clean(void **state)
{
	char line[512];
	FILE *p;
	int findings = 0, status;

	(void)state;
	assert_true(have_cppcheck());
	p = popen("cppcheck -q --std=c99 "
		  "--enable=warning,style,performance,portability "
		  "--suppress=missingIncludeSystem " INCLUDES " "
		  SOURCES " firmware_fdr/ground/*.c 2>&1", "r");
	assert_non_null(p);
	while (fgets(line, sizeof(line), p)) {
		fputs(line, stdout);
		findings++;
	}
	status = pclose(p);
	assert_int_equal(status, 0);
	assert_int_equal(findings, 0);
}

static void test_misra_within_justified(void **state)
{
	int count[N_JUSTIFIED] = { 0 }, unjustified = 0;
	char line[512];
	size_t i;
	FILE *p;

	(void)state;
	assert_true(have_cppcheck());
	p = popen("cppcheck -q --std=c99 --addon=misra "
		  "--suppress=missingIncludeSystem " INCLUDES " " SOURCES
		  " 2>&1", "r");
	assert_non_null(p);
	while (fgets(line, sizeof(line), p)) {
		const char *r = strstr(line, "[misra-c2012-");
		int known = 0;

		if (!r)
			continue;
		r += strlen("[misra-c2012-");
		for (i = 0; i < N_JUSTIFIED; i++) {
			size_t n = strlen(justified[i].rule);

			if (strncmp(r, justified[i].rule, n) == 0 && r[n] == ']') {
				count[i]++;
				known = 1;
			}
		}
		if (!known) {
			printf("unjustified: %s", line);
			unjustified++;
		}
	}
	assert_int_equal(pclose(p), 0);
	for (i = 0; i < N_JUSTIFIED; i++) {
		printf("misra-c2012-%s: %d (justified %d)\n", justified[i].rule,
		       count[i], justified[i].allowed);
		assert_true(count[i] <= justified[i].allowed);
	}
	assert_int_equal(unjustified, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_general_checks_clean),
		cmocka_unit_test(test_misra_within_justified),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
