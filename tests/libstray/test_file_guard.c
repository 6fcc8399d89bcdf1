/*
 * test_file_guard.c - one run's inputs and outputs (stray/file.h): after
 * stray_file_run_begin an output may not be a file the run read (by
 * identity: a hard link too) nor another output of the run (by canonical
 * path); without a run, nothing is refused.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>

#include "../scratch.h"
#include "stray/errfmt.h"
#include "stray/file.h"

static char dir[64], a[128], b[128], dotted[160], link_a[128];

static int setup(void **state)
{
	FILE *f;

	(void)state;
	snprintf(dir, sizeof(dir), "/tmp/stray_guard_%d", (int)getpid());
	mkdir(dir, 0700);
	snprintf(a, sizeof(a), "%s/a.csv", dir);
	snprintf(b, sizeof(b), "%s/b.csv", dir);
	snprintf(dotted, sizeof(dotted), "%s/./b.csv", dir);
	snprintf(link_a, sizeof(link_a), "%s/link.csv", dir);
	f = fopen(a, "w");
	fputs("x\n", f);
	fclose(f);
	return link(a, link_a);
}

static int teardown(void **state)
{
	(void)state;
	stray_file_run_end();
	return scratch_remove(dir);
}

static int write_one(const char *path, struct stray_error *err)
{
	struct stray_file_out out;
	int rc;

	stray_error_clear(err);
	rc = stray_file_open_atomic(&out, path, err);

	if (rc != STRAY_OK)
		return rc;
	fputs("y\n", out.f);
	return stray_file_commit(&out, err);
}

static void test_input_not_replaced(void **state)
{
	struct stray_error err;
	char *text;
	size_t len;

	(void)state;
	stray_error_clear(&err);
	stray_file_run_begin();
	assert_int_equal(stray_file_read(a, &text, &len, &err), STRAY_OK);
	free(text);
	assert_int_equal(write_one(a, &err), STRAY_EINVAL);
	assert_non_null(strstr(err.reason, "is also an input of this run"));
	assert_int_equal(write_one(link_a, &err), STRAY_EINVAL);
	/* still the input's bytes */
	assert_int_equal(stray_file_read(a, &text, &len, &err), STRAY_OK);
	assert_string_equal(text, "x\n");
	free(text);
	/* a store's stale entry, replaced on purpose */
	stray_file_forget_input(a);
	stray_file_forget_input(link_a);
	assert_int_equal(write_one(a, &err), STRAY_OK);
}

static void test_output_once(void **state)
{
	struct stray_error err;
	struct stray_dir_out d;

	(void)state;
	stray_file_run_begin();
	assert_int_equal(write_one(b, &err), STRAY_OK);
	assert_int_equal(write_one(dotted, &err), STRAY_EINVAL);
	assert_non_null(strstr(err.reason, "is named twice as an output"));
	assert_int_equal(stray_dir_open_atomic(&d, b, &err), STRAY_EINVAL);
	/* devices are written as often as asked */
	assert_int_equal(write_one("/dev/null", &err), STRAY_OK);
	assert_int_equal(write_one("/dev/null", &err), STRAY_OK);
	/* a progress record rewritten on purpose (stray review's
	 * manifest.json), once forgotten, and only then */
	stray_file_forget_output(dotted);
	assert_int_equal(write_one(b, &err), STRAY_OK);
	assert_int_equal(write_one(b, &err), STRAY_EINVAL);
}

static void test_no_run_no_rule(void **state)
{
	struct stray_error err;
	char *text;
	size_t len;

	(void)state;
	stray_file_run_end();
	assert_int_equal(stray_file_read(a, &text, &len, &err), STRAY_OK);
	free(text);
	assert_int_equal(write_one(a, &err), STRAY_OK);
	assert_int_equal(write_one(a, &err), STRAY_OK);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_input_not_replaced, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_output_once, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_no_run_no_rule, setup,
						teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
