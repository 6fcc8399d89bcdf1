/*
 * space.c - room on the disk for the sweep, checked from the plan before
 * the first move (sweep.h): a full disk found at frame 4000 of 6000
 * costs the night; found at the start it costs a minute.
 */
#include <libgen.h>
#include <stdio.h>
#include <string.h>
#include <sys/statvfs.h>

#include "rig/sweep.h"

#define FITS_BLOCK 2880.0
#define HEADER_BLOCKS 2	/* the lab-frame keywords fit in two */
#define ROW_BYTES 160.0	/* a manifest row */
#define RESERVE_BYTES (16.0 * 1024 * 1024)	/* the log, the plan, slack */

double rig_sweep_bytes_per_frame(const struct rig_config *cfg)
{
	double data = 2.0 * cfg->camera.n_rows * cfg->camera.n_cols;

	return HEADER_BLOCKS * FITS_BLOCK +
	       FITS_BLOCK * (double)(long)((data + FITS_BLOCK - 1) /
					   FITS_BLOCK) + ROW_BYTES;
}

int rig_sweep_space_check(const char *dir, const struct rig_config *cfg,
			  long frames, struct rig_error *err)
{
	char where[RIG_PATH_MAX + 2], *at;
	struct statvfs vs;
	double need, have;

	snprintf(where, sizeof(where), "%s", dir);
	at = where;
	if (statvfs(where, &vs) != 0) {	/* not made yet: its parent */
		at = dirname(where);
		if (statvfs(at, &vs) != 0)
			return RIG_OK;	/* the store names the real problem */
	}
	need = (double)frames * rig_sweep_bytes_per_frame(cfg) * 1.1 +
	       RESERVE_BYTES;
	have = (double)vs.f_bavail * (double)vs.f_frsize;
	if (have >= need)
		return RIG_OK;
	return rig_error_set(err, RIG_EIO, "%s: not enough free space for "
		"the sweep: about %.0f MB needed for %ld frames, %.0f MB "
		"free on %s; free space or choose another folder", dir,
		need / 1e6, frames, have / 1e6, at);
}
