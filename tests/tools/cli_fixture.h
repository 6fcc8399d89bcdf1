/*
 * cli_fixture.h - the fixture of a test file that runs `stray` as a user
 * would: a scratch folder (cli_setup / cli_teardown), paths and files in
 * it, the last command's result in r, and the check every refusal must
 * pass (exit 2, one stderr line naming the file, field or value, nothing
 * on stdout).  Include after <cmocka.h>; define STRAY first to run the
 * commands another way (run_stray_limited).
 */
#ifndef STRAY_TESTS_CLI_FIXTURE_H
#define STRAY_TESTS_CLI_FIXTURE_H

#include <cJSON.h>
#include <sys/stat.h>

#include "../scratch.h"
#include "run_cli.h"

static struct cli_run r;	/* the last command's status and output */
static char dir[64];		/* the file's scratch folder */

#ifndef STRAY
#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })
#endif

/* dir/name, in one of 16 slots reused in turn. */
static inline char *in_dir(const char *name)
{
	static char paths[16][256];
	static int k;
	char *p = paths[k++ % 16];

	snprintf(p, 256, "%s/%s", dir, name);
	return p;
}

/* dir/name holding the len bytes given. */
static inline char *put_bytes(const char *name, const char *bytes,
			      size_t len)
{
	char *p = in_dir(name);
	FILE *f = fopen(p, "wb");

	assert_non_null(f);
	assert_int_equal(fwrite(bytes, 1, len, f), len);
	fclose(f);
	return p;
}

static inline char *put_text(const char *name, const char *text)
{
	return put_bytes(name, text, strlen(text));
}

/* A file's first 64 KiB, as a string (overwritten by the next call). */
static inline char *slurp_file(const char *path)
{
	static char buf[1 << 16];

	slurp(path, buf, sizeof(buf));
	return buf;
}

/* Anything at path, a dangling link too. */
static inline int exists(const char *path)
{
	struct stat st;

	return lstat(path, &st) == 0;
}

/* Bad input: exit 2, nothing on stdout, one stderr line with needle. */
static inline void expect_bad(const char *needle)
{
	if (r.status != 2 || r.err_lines != 1 || !strstr(r.err, needle))
		fail_msg("status %d, stderr (%d lines): %s; wanted '%s'",
			 r.status, r.err_lines, r.err, needle);
	assert_string_equal(r.out, "");
}

static inline void expect_ok(void)
{
	if (r.status != 0)
		fail_msg("status %d, stderr: %s", r.status, r.err);
}

/* The last command's stdout as JSON (the caller deletes it). */
static inline cJSON *json_out(void)
{
	cJSON *j = cJSON_Parse(r.out);

	if (!j)
		fail_msg("not JSON: %s\n%s", r.out, r.err);
	return j;
}

static inline double num(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);

	if (!cJSON_IsNumber(v))
		fail_msg("no number '%s'", key);
	return v->valuedouble;
}

static inline const char *str(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);

	if (!cJSON_IsString(v))
		fail_msg("no string '%s'", key);
	return v->valuestring;
}

/* A fresh scratch folder /tmp/stray_TAG_XXXXXX for the group. */
static inline int cli_setup(const char *tag)
{
	snprintf(dir, sizeof(dir), "/tmp/stray_%s_XXXXXX", tag);
	return mkdtemp(dir) ? 0 : -1;
}

static inline int cli_teardown(void)
{
	return scratch_remove(dir);
}

#endif /* STRAY_TESTS_CLI_FIXTURE_H */
