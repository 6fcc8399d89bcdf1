/*
 * test_input_limits.c - the hosted layer under hostile input (issue 14):
 * CR-only lines that once made table.c free a block twice, the row and
 * file-size limits, a directory or device as an input, the physics of a
 * curve, escaped bytes in messages, and atomic writes that leave no
 * temporary behind on a failure, an exit or a SIGTERM.
 */
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

#include "../test_util.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/spectrum_io.h"
#include "stray/table.h"

static char msg[1024];

static int curve_text(const char *text, size_t len)
{
	struct stray_curve c;
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_curve_parse("c.csv", text, len, &c, &err);
	stray_error_format(&err, msg, sizeof(msg));
	if (rc == STRAY_OK)
		stray_curve_free(&c);
	return rc;
}

static void expect_refused(const char *text, const char *needle)
{
	assert_int_equal(curve_text(text, strlen(text)), STRAY_EPARSE);
	if (!strstr(msg, needle))
		fail_msg("message '%s' lacks '%s'", msg, needle);
	assert_null(strchr(msg, '\n'));
}

/* b'\r\r\n' * 66: a zero-column header, then 65 zero-cell rows; the 65th
 * grew the cell array by realloc(p, 0), which freed it (double free). */
static void test_cr_only_lines_no_double_free(void **state)
{
	char text[3 * 200 + 1];
	int k;

	(void)state;
	for (k = 0; k < 200; k++)
		memcpy(text + 3 * k, "\r\r\n", 3);
	text[600] = '\0';
	assert_int_equal(curve_text(text, 600), STRAY_EPARSE);
	assert_non_null(strstr(msg, "no header row"));
	/* a header that splits into no fields at all is refused too */
	assert_int_equal(curve_text("\"\"\r\r\n0,1\n", 9), STRAY_EPARSE);
}

static void test_bom_accepted(void **state)
{
	const char text[] = "\xEF\xBB\xBFtheta_deg,alpha\n0,1\n10,0.1\n";

	(void)state;
	assert_int_equal(curve_text(text, strlen(text)), STRAY_OK);
}

static void test_row_limit(void **state)
{
	size_t n = STRAY_TABLE_ROWS_MAX + 1, k, len = 0;
	char *text = malloc(16 + n * 12);
	struct stray_table t;
	struct stray_error err;

	(void)state;
	len += (size_t)sprintf(text, "a\n");
	for (k = 0; k < n; k++)
		len += (size_t)sprintf(text + len, "%zu\n", k);
	stray_error_clear(&err);
	assert_int_equal(stray_table_parse("t.csv", text, len, &t, &err),
			 STRAY_EPARSE);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, "t.csv:100002: row"));
	assert_non_null(strstr(msg, "more than 100000 rows"));
	/* one row fewer is a table */
	len -= strlen(text + len - 7);	/* drop the last line "100000\n" */
	stray_error_clear(&err);
	assert_int_equal(stray_table_parse("t.csv", text, len, &t, &err),
			 STRAY_OK);
	assert_int_equal(t.n_rows, STRAY_TABLE_ROWS_MAX);
	stray_table_free(&t);
	free(text);
}

static void read_expect(const char *path, int code, const char *needle)
{
	struct stray_error err;
	char *buf;
	size_t len;

	stray_error_clear(&err);
	assert_int_equal(stray_file_read(path, &buf, &len, &err), code);
	assert_true(stray_status_is_bad_input(code));
	stray_error_format(&err, msg, sizeof(msg));
	if (!strstr(msg, needle))
		fail_msg("message '%s' lacks '%s'", msg, needle);
}

static void test_directory_and_device_refused(void **state)
{
	(void)state;
	read_expect("/tmp", STRAY_EINVAL, "/tmp: is a directory");
	read_expect("/dev/zero", STRAY_EINVAL, "/dev/zero: is not a regular file");
}

static void test_file_size_limit(void **state)
{
	char path[64];
	FILE *f;

	(void)state;
	snprintf(path, sizeof(path), "/tmp/stray_big_%d.csv", (int)getpid());
	f = fopen(path, "wb");
	assert_non_null(f);
	/* sparse: no disk is used */
	assert_int_equal(fseek(f, STRAY_FILE_READ_MAX, SEEK_SET), 0);
	fputc('\n', f);
	fclose(f);
	read_expect(path, STRAY_EINVAL, "input limit");
	unlink(path);
}

static void test_curve_physics(void **state)
{
	(void)state;
	expect_refused("theta_deg,alpha\n0,1\n10,0.1\n1e300,0.01\n",
		       "c.csv:4: theta_deg '1e+300': must be in [0, 180]");
	expect_refused("theta_deg,alpha\n-400,1\n10,0.1\n",
		       "c.csv:2: theta_deg '-400'");
	expect_refused("theta_deg,alpha\n10,0\n20,0\n", "every value is 0");
	expect_refused("theta_deg,alpha\n0,0\n10,0\n", "must be 1 at theta_deg 0");
	expect_refused("theta_deg,alpha\n0,0.5\n10,0.1\n", "alpha '0.5'");
	/* within 3 sigma of 1 on axis is a measurement */
	assert_int_equal(curve_text("theta_deg,alpha,sigma\n0,0.9,0.04\n",
				    32), STRAY_OK);
	expect_refused("theta_deg,alpha,sigma\n0,0.9,0.01\n10,0.1,0\n",
		       "alpha '0.9'");
	assert_int_equal(curve_text("theta_deg,alpha\n5,0.3\n180,0\n", 28),
			 STRAY_OK);
}

static void test_qe_above_one_refused(void **state)
{
	char path[64];
	struct stray_spectrum_data d;
	struct stray_error err;
	FILE *f;

	(void)state;
	snprintf(path, sizeof(path), "/tmp/stray_qe_%d.csv", (int)getpid());
	f = fopen(path, "w");
	fputs("wavelength_nm,qe\n400,0.5\n500,1.7\n", f);
	fclose(f);
	stray_error_clear(&err);
	assert_int_equal(stray_spectrum_load(path, &d, &err), STRAY_EPARSE);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, ":3: qe '1.7': a quantum efficiency"));
	unlink(path);
}

static void test_message_escapes_bytes(void **state)
{
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	stray_error_at(&err, STRAY_EPARSE, "f", 0, "x", "bad");
	stray_error_text(&err, "a\033[2J\x01\xff");
	stray_error_format(&err, msg, sizeof(msg));
	assert_string_equal(msg, "f: x 'a\\x1b[2J\\x01\\xff': bad");
}

static int tmp_count(const char *dir)
{
	char cmd[256], out[32] = "";
	FILE *p;

	snprintf(cmd, sizeof(cmd), "ls %s | grep -c '\\.tmp\\.' ", dir);
	p = popen(cmd, "r");
	if (p && !fgets(out, sizeof(out), p))
		out[0] = '\0';
	if (p)
		pclose(p);
	return atoi(out);
}

/* The child opens an atomic file and then dies by SIGTERM (how == 0),
 * returns from main without abort (1), or aborts (2). */
static void atomic_child(const char *dir, int how)
{
	char target[256];
	struct stray_file_out out;
	struct stray_error err;
	pid_t pid;
	int st;

	snprintf(target, sizeof(target), "%s/out.csv", dir);
	pid = fork();
	if (pid == 0) {
		stray_error_clear(&err);
		if (stray_file_open_atomic(&out, target, &err) != STRAY_OK)
			_exit(3);
		fputs("partial", out.f);
		fflush(out.f);
		if (how == 0)
			raise(SIGTERM);
		if (how == 2)
			stray_file_abort(&out);
		exit(0);
	}
	waitpid(pid, &st, 0);
	if (how == 0)
		assert_true(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM);
	else
		assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
	assert_int_equal(tmp_count(dir), 0);
	assert_int_equal(access(target, F_OK), -1);	/* never half-written */
}

static void test_atomic_write_leaves_nothing(void **state)
{
	char dir[] = "/tmp/stray_atomic_XXXXXX";
	int how;

	(void)state;
	assert_non_null(mkdtemp(dir));
	for (how = 0; how < 3; how++)
		atomic_child(dir, how);
	rmdir(dir);
}

/* A device is written in place, never renamed over (as root the old
 * rename replaced /dev/null by a regular file). */
static void test_atomic_write_to_device(void **state)
{
	struct stray_file_out out;
	struct stray_error err;
	struct stat st;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_file_open_atomic(&out, "/dev/null", &err),
			 STRAY_OK);
	fputs("x\n", out.f);
	assert_int_equal(stray_file_commit(&out, &err), STRAY_OK);
	assert_int_equal(stat("/dev/null", &st), 0);
	assert_true(S_ISCHR(st.st_mode));
	assert_int_equal(stray_file_open_atomic(&out, "/tmp", &err),
			 STRAY_EINVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cr_only_lines_no_double_free),
		cmocka_unit_test(test_bom_accepted),
		cmocka_unit_test(test_row_limit),
		cmocka_unit_test(test_directory_and_device_refused),
		cmocka_unit_test(test_file_size_limit),
		cmocka_unit_test(test_curve_physics),
		cmocka_unit_test(test_qe_above_one_refused),
		cmocka_unit_test(test_message_escapes_bytes),
		cmocka_unit_test(test_atomic_write_leaves_nothing),
		cmocka_unit_test(test_atomic_write_to_device),
	};

	if (getenv("STRAY_TEST_FILTER"))	/* one test (a crash ends all) */
		cmocka_set_test_filter(getenv("STRAY_TEST_FILTER"));
	return cmocka_run_group_tests(tests, NULL, NULL);
}
