/*
 * avail_heads.h - the heads file of `stray availability` (JSON), read
 * from its text alone: names, the body -> head frame of each, and the
 * paths of their flight tables (resolved against the file's folder, not
 * opened here, so the fuzz target never touches the disk).
 */
#ifndef STRAY_MISSION_AVAIL_HEADS_H
#define STRAY_MISSION_AVAIL_HEADS_H

#include <stddef.h>

#include "stray/error.h"

#define AVAIL_HEADS_MAX 8

struct avail_head_spec {
	char name[32];
	double m_bs[3][3];	/* body -> head (rows: head axes) */
	char table[4096];	/* the flight table's path */
};

/*
 * Parse buf[0 .. len) as the heads file at `path` into spec[0 .. *n).
 * Every key is known ("heads"; per head "name", "boresight_body",
 * "up_body", "table"): anything else is refused with its name.
 * STRAY_EPARSE with one line in err.
 */
int avail_heads_parse(const char *buf, size_t len, const char *path,
		      struct avail_head_spec spec[AVAIL_HEADS_MAX], size_t *n,
		      struct stray_error *err);

#endif /* STRAY_MISSION_AVAIL_HEADS_H */
