/*
 * fuzz_tracer_args.c - libFuzzer target for the text the tracer parses
 * from its command line: the angle list (first line) and `--set
 * key=value` overrides (the following lines), checked afterwards.  No
 * input may crash, leak or accept a non-finite angle.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tracer/angles.h"
#include "tracer/baffle.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct tracer_baffle b;
	struct stray_error err;
	char *text = malloc(size + 1), *line, *save = NULL;
	double *a = NULL;
	size_t n, i;

	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = '\0';
	tracer_baffle_ref4(&b);
	line = strtok_r(text, "\n", &save);
	stray_error_clear(&err);
	if (line && tracer_angles_parse(line, &a, &n, &err) == 0) {
		for (i = 0; i < n; i++)
			if (!(a[i] >= 0.0 && a[i] <= 180.0) ||
			    (i && !(a[i] > a[i - 1])))
				abort();
		free(a);
	}
	while ((line = strtok_r(NULL, "\n", &save)) != NULL) {
		stray_error_clear(&err);
		tracer_baffle_set(&b, line, &err);
	}
	stray_error_clear(&err);
	if (tracer_baffle_check(&b, &err) == 0 &&
	    !(b.reflectance >= 0.0 && b.reflectance <= 1.0))
		abort();
	free(text);
	return 0;
}
