/*
 * tracer_cli.h - the CLI tests' check of bad input (`stray trace`, its
 * focal map): exit 2 and one stderr line that names the culprit.
 */
#ifndef TRACER_CLI_H
#define TRACER_CLI_H

#include "tracer_test.h"
#include "../tools/run_cli.h"

static inline void expect_bad(char *const argv[], const char *needle)
{
	struct cli_run r;

	assert_int_equal(run_stray(&r, argv), 2);
	assert_int_equal(r.err_lines, 1);
	if (!strstr(r.err, needle))
		fail_msg("stderr '%s' lacks '%s'", r.err, needle);
}

#endif /* TRACER_CLI_H */
