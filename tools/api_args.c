/*
 * api_args.c - the options object of a library call (tools/api.h) as the
 * command line `stray <cmd> ...`: operands ("args") first, then --key
 * value pairs; true is a bare flag, false and null leave the option out,
 * an array repeats it.  Separate from api.c so it is fuzzed alone
 * (tests/fuzz/fuzz_api_options.c).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "api_args.h"
#include "cli.h"

static int push(struct api_args *a, const char *s)
{
	if (a->n + 2 > a->cap) {
		int cap = a->cap ? 2 * a->cap : 32;
		char **v = realloc(a->v, (size_t)cap * sizeof(char *));

		if (!v)
			return -1;
		a->v = v;
		a->cap = cap;
	}
	if (!(a->v[a->n] = strdup(s)))
		return -1;
	a->v[++a->n] = NULL;
	return 0;
}

void api_args_free(struct api_args *a)
{
	int i;

	for (i = 0; i < a->n; i++)
		free(a->v[i]);
	free(a->v);
}

/* One JSON value as option text: a string as is, a number %.17g (reads
 * back to the same double). 1: not a scalar. */
static int scalar_text(const cJSON *v, char *buf, size_t size)
{
	if (cJSON_IsString(v)) {
		snprintf(buf, size, "%s", v->valuestring);
		return 0;
	}
	if (cJSON_IsNumber(v)) {
		double d = v->valuedouble;

		if (d == floor(d) && fabs(d) < 1e15)
			snprintf(buf, size, "%.0f", d);
		else
			snprintf(buf, size, "%.17g", d);
		return 0;
	}
	return 1;
}

/* A value that is not an option's: the caller's mistake, bad input. */
static int bad_option(char *err, size_t err_size, const char *cmd,
		      const char *key, const char *why)
{
	snprintf(err, err_size, "stray %s: option '--%s': %s", cmd, key, why);
	return CLI_USAGE;
}

/* opts (a JSON object) onto a: operands first, then --key value pairs. */
int api_build_args(const char *cmd, const char *opts_json,
		   struct api_args *a, char *err, size_t err_size)
{
	char text[4096], opt[256];
	const cJSON *o, *it, *e;
	cJSON *root = NULL;
	int rc = CLI_OK;

	if (push(a, cmd))
		return CLI_FAIL;
	if (!opts_json || !*opts_json)
		return CLI_OK;
	root = cJSON_Parse(opts_json);
	if (!cJSON_IsObject(root)) {
		cJSON_Delete(root);
		snprintf(err, err_size, "stray %s: options are not a JSON object",
			 cmd);
		return CLI_USAGE;
	}
	o = root;
	if ((it = cJSON_GetObjectItemCaseSensitive(o, "args"))) {
		cJSON_ArrayForEach(e, it) {
			if (scalar_text(e, text, sizeof(text))) {
				rc = bad_option(err, err_size, cmd, "args", "not text");
				goto out;
			}
			if (push(a, text)) {
				rc = CLI_FAIL;
				goto out;
			}
		}
	}
	cJSON_ArrayForEach(it, o) {
		const cJSON *one = it;
		int many = cJSON_IsArray(it);

		if (strcmp(it->string, "args") == 0 || cJSON_IsFalse(it) ||
		    cJSON_IsNull(it))
			continue;
		snprintf(opt, sizeof(opt), "--%s", it->string);
		if (cJSON_IsTrue(it)) {
			if (push(a, opt))
				rc = CLI_FAIL;
			if (rc)
				goto out;
			continue;
		}
		for (e = many ? it->child : one; e; e = many ? e->next : NULL) {
			if (scalar_text(e, text, sizeof(text))) {
				rc = bad_option(err, err_size, cmd, it->string,
						"not a string or a number");
				goto out;
			}
			if (push(a, opt) || push(a, text)) {
				rc = CLI_FAIL;
				goto out;
			}
		}
	}
out:
	cJSON_Delete(root);
	return rc;
}

