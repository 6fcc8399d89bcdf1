/*
 * sweep_manifest.h - the manifest.csv of a lab sweep folder
 * (docs/formats.md: file,frametyp,angle_deg,exptime_s,ndtrans,seqnum,
 * sha256), read with libcsv, and the SHA-256 check of each frame file
 * (OpenSSL libcrypto).
 */
#ifndef STRAY_TOOLS_SWEEP_MANIFEST_H
#define STRAY_TOOLS_SWEEP_MANIFEST_H

#include <stddef.h>

#include "stray/error.h"

enum sweep_frametyp { SWEEP_DARK, SWEEP_AMBIENT, SWEEP_FULL };

#define SWEEP_FILE_MAX 256

struct sweep_entry {
	char file[SWEEP_FILE_MAX];	/* relative to the sweep folder */
	int type;			/* enum sweep_frametyp */
	double angle_deg, exptime_s, ndtrans;
	long seqnum;
	char sha256[65];		/* lower-case hex */
	long line;			/* line in manifest.csv */
};

struct sweep_manifest {
	size_t n;
	struct sweep_entry *e;
};

/* FRAMETYP text to enum; -1 when unknown. */
int sweep_frametyp_parse(const char *text);
const char *sweep_frametyp_name(int type);

/*
 * Parse manifest text; name is used in messages.  Lines starting with '#'
 * and blank lines are skipped; the header names the columns (any order,
 * extra columns ignored); every error names the line and the column.
 */
int sweep_manifest_parse(const char *name, const char *text, size_t len,
			 struct sweep_manifest *m, struct stray_error *err);

/* Read DIR/manifest.csv. */
int sweep_manifest_load(const char *dir, struct sweep_manifest *m,
			struct stray_error *err);

void sweep_manifest_free(struct sweep_manifest *m);

/* Compare the SHA-256 of the file at path with hex (64 digits). */
int sweep_sha256_check(const char *path, const char *hex,
		       struct stray_error *err);

#endif /* STRAY_TOOLS_SWEEP_MANIFEST_H */
