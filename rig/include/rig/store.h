/*
 * store.h - a sweep folder on disk (docs/formats.md, "Lab frames"):
 * one FITS file per frame and manifest.csv with one row per frame,
 *   file,frametyp,angle_deg,exptime_s,ndtrans,seqnum,sha256
 * appended only after the frame file is complete, fsynced and renamed
 * into place, so after a crash every manifest row names a whole file and
 * a file without a row is an orphan to be retaken.
 */
#ifndef RIG_STORE_H
#define RIG_STORE_H

#include <stddef.h>

#include "rig/devices.h"
#include "rig/status.h"

enum rig_frametyp { RIG_DARK, RIG_AMBIENT, RIG_FULL, RIG_FRAMETYP_COUNT };

#define RIG_FILE_MAX 64
#define RIG_SHA256_HEX 65

struct rig_frame_meta {
	int type;		/* enum rig_frametyp */
	double angle_deg, exptime_s, ndtrans;
	int seqnum;
	int sat_dn;
	int full_frame;		/* 1: omit ROWS (all 1944 rows stored) */
	int has_monitor;
	double monitor;		/* lamp level, 1 = nominal (FITS MONITOR) */
};

struct rig_manifest_row {
	char file[RIG_FILE_MAX];
	struct rig_frame_meta meta;
	char sha256[RIG_SHA256_HEX];
};

struct rig_manifest {
	char dir[512];
	struct rig_manifest_row *rows;
	size_t n, cap;
};

const char *rig_frametyp_name(int type);

/* File name of a frame: a+12.000_FULL_000.fits. */
void rig_frame_filename(const struct rig_frame_meta *m, char *out,
			size_t size);

/*
 * Write img as dir/name with the formats.md keywords: to name.tmp,
 * fsync, rename, fsync the folder; the SHA-256 of the final bytes goes
 * to sha_hex.
 */
int rig_fits_write(const char *dir, const char *name,
		   const struct rig_image *img,
		   const struct rig_frame_meta *m,
		   char sha_hex[RIG_SHA256_HEX], struct rig_error *err);

/* SHA-256 of a file as lowercase hex (OpenSSL EVP). */
int rig_sha256_file(const char *path, char hex[RIG_SHA256_HEX],
		    struct rig_error *err);

/*
 * Open a sweep folder.  New (resume = 0): the folder must not hold a
 * manifest; it is created with its header.  Resume: a torn last line is
 * cut off, every row's file is checked against its sha256, and frame
 * files or temporaries with no row are removed.
 */
int rig_manifest_open(struct rig_manifest *mf, const char *dir, int resume,
		      struct rig_error *err);
/* Append one row and fsync. */
int rig_manifest_append(struct rig_manifest *mf,
			const struct rig_manifest_row *row,
			struct rig_error *err);
/* Count the rows of (angle, type); *first = the first such row or NULL. */
int rig_manifest_count(const struct rig_manifest *mf, double angle_deg,
		       int type, const struct rig_manifest_row **first);
void rig_manifest_close(struct rig_manifest *mf);

#endif /* RIG_STORE_H */
