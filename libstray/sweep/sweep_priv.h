/*
 * sweep_priv.h - what the files of libstray/sweep share and no caller
 * sees.
 */
#ifndef STRAY_SWEEP_PRIV_H
#define STRAY_SWEEP_PRIV_H

#include <stddef.h>

#include "stray/sweep_store.h"

/* stray_sweep_manifest_parse; allow_empty accepts a header alone. */
int stray_sweep_manifest_parse_text(const char *name, const char *text,
				    size_t len, int allow_empty,
				    struct stray_sweep_manifest *m,
				    struct stray_error *err);

/* Every row's file, where it exists, a regular file of the folder
 * m->dir (no symlink, FIFO or device): refused at path's row line. */
int stray_sweep_manifest_check_files(const char *path,
				     const struct stray_sweep_manifest *m,
				     struct stray_error *err);

/*
 * Write img as dir/name: to name.tmp, fsync, rename, fsync the folder;
 * the SHA-256 of the final bytes goes to sha_hex.
 */
int stray_sweep_fits_write(const char *dir, const char *name,
			   const struct stray_sweep_image *img,
			   const struct stray_sweep_frame *m,
			   char sha_hex[STRAY_SWEEP_SHA256_HEX],
			   struct stray_error *err);

#endif /* STRAY_SWEEP_PRIV_H */
