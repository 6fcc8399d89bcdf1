/*
 * api_args.h - a library call's options object as an argument list
 * (api_args.c).
 */
#ifndef STRAY_TOOLS_API_ARGS_H
#define STRAY_TOOLS_API_ARGS_H

#include <stddef.h>

/* The argument list being built: strings owned by the list, v[n] NULL. */
struct api_args {
	char **v;
	int n, cap;
};

/*
 * cmd, then opts_json (a JSON object, or NULL/"" for none) onto a.
 * CLI_OK; CLI_USAGE with err set (not an object, a value that is not an
 * option's); CLI_FAIL out of memory.  a is freed by api_args_free.
 */
int api_build_args(const char *cmd, const char *opts_json,
		   struct api_args *a, char *err, size_t err_size);

void api_args_free(struct api_args *a);

#endif /* STRAY_TOOLS_API_ARGS_H */
