/*
 * fuzz_api_options.c - libFuzzer target for the options object of a
 * library call (tools/api_args.c, what Python's keyword arguments become):
 * arbitrary bytes as the JSON, the argument list checked whole.  A list
 * that is built starts with the command, is NULL-terminated, and each
 * option word after the operands starts with "--"; a refusal says why.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "api_args.h"
#include "cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct api_args a = { NULL, 0, 0 };
	char *json = malloc(size + 1), err[512] = "";
	int rc, i;

	if (!json)
		return 0;
	memcpy(json, data, size);
	json[size] = '\0';
	rc = api_build_args("trace", json, &a, err, sizeof(err));
	if (rc == CLI_OK) {
		if (a.n < 1 || strcmp(a.v[0], "trace") != 0 || a.v[a.n])
			abort();
		for (i = 1; i < a.n; i++)
			if (!a.v[i])
				abort();
	} else if (rc == CLI_USAGE && !err[0]) {
		abort();	/* a refusal names its reason */
	}
	api_args_free(&a);
	free(json);
	return 0;
}
