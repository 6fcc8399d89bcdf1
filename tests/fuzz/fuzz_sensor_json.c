/*
 * fuzz_sensor_json.c - libFuzzer target for sensor files: cJSON parsing,
 * key mapping and range checks on arbitrary bytes (NUL-terminated copy).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sensor_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_sensor s;
	struct stray_error err;
	char *text = malloc(size + 1), line[1024];

	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = '\0';
	stray_error_clear(&err);
	if (stray_sensor_parse("fuzz.json", text, "/tmp", &s, &err) != STRAY_OK)
		stray_error_format(&err, line, sizeof(line));
	free(text);
	return 0;
}
