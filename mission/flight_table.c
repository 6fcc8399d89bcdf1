/*
 * flight_table.c - a flight table read from a file and checked.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "mission/flight_table.h"
#include "stray/errfmt.h"
#include "stray/file.h"

int flight_table_load(const char *path, struct fdrfw_table *t,
		      struct stray_error *err)
{
	char *buf;
	size_t len;
	int rc = stray_file_read(path, &buf, &len, err);

	if (rc != STRAY_OK)
		return rc;
	rc = fdrfw_table_parse((const uint8_t *)buf, len, t);
	if (rc == FDRFW_EMAGIC) {	/* the magic, another version */
		char v[16];

		snprintf(v, sizeof(v), "%u", (unsigned)buf[4]);
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "version",
			"a flight table of an older or newer version (this "
			"build reads version 3, issue 28's detectors): rebuild "
			"it with stray firmware-table");
		stray_error_text(err, v);
	} else if (rc != FDRFW_OK || fdrfw_table_check(t) != FDRFW_OK)
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "table",
			"not a valid flight table (size, magic, CRC or range)");
	free(buf);
	return rc;
}
