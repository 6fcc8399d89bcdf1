/*
 * rig_test_util.h - shared helpers of the rig tests: a small simulated
 * lab config, temporary folders, and an independent check of a sweep
 * folder read through the sweep store's reader (every manifest row
 * against its FITS header and file and its SHA-256, groups complete,
 * darks matching the lit exposures, nothing extra on disk).
 */
#ifndef RIG_TEST_UTIL_H
#define RIG_TEST_UTIL_H

#include <dirent.h>
#include <fitsio.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rig/config.h"
#include "stray/errfmt.h"
#include "stray/sweep_store.h"
#include "rig/sweep.h"

/* A 4-row x 128-column window, angles 0..30 step 10, 2 repeats. */
static inline void small_config(struct rig_config *cfg)
{
	static const uint16_t rows[4] = { 960, 961, 1100, 1101 };

	rig_config_defaults(cfg);
	cfg->camera.n_rows = 4;
	memcpy(cfg->camera.rows, rows, sizeof(rows));
	cfg->camera.col0 = 960;
	cfg->camera.n_cols = 128;
	cfg->sweep.theta_start_deg = 0;
	cfg->sweep.theta_stop_deg = 30;
	cfg->sweep.theta_step_deg = 10;
	cfg->sweep.repeats = 2;
}

static inline char *temp_dir(void)
{
	char tmpl[] = "/tmp/rigtest-XXXXXX";
	char *d = mkdtemp(tmpl);

	return d ? strdup(d) : NULL;
}

static inline void remove_tree(const char *dir)
{
	char cmd[600];

	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	if (system(cmd) != 0)
		fprintf(stderr, "could not remove %s\n", dir);
}

struct sweep_check {
	int rows;		/* manifest rows */
	int bad;		/* problems found (printed) */
};

static inline int fits_key_mismatch(const char *path,
				    const struct stray_sweep_entry *r)
{
	fitsfile *f;
	char type[FLEN_VALUE];
	double angle, t, nd;
	int st = 0, seq, sat, bad = 0;

	if (fits_open_file(&f, path, READONLY, &st))
		return 1;
	fits_read_key(f, TSTRING, "FRAMETYP", type, NULL, &st);
	fits_read_key(f, TDOUBLE, "ANGLE", &angle, NULL, &st);
	fits_read_key(f, TDOUBLE, "EXPTIME", &t, NULL, &st);
	fits_read_key(f, TDOUBLE, "NDTRANS", &nd, NULL, &st);
	fits_read_key(f, TINT, "SEQNUM", &seq, NULL, &st);
	fits_read_key(f, TINT, "SATLEVEL", &sat, NULL, &st);
	bad = st != 0 || strcmp(type, stray_sweep_frametyp_name(r->type)) ||
	      fabs(angle - r->angle_deg) > 1e-4 ||
	      fabs(t - r->exptime_s) > 1e-7 ||
	      fabs(nd / r->ndtrans - 1) > 1e-5 || seq != r->seqnum ||
	      sat != 4095;
	st = 0;
	fits_close_file(f, &st);
	return bad;
}

/* Count how many rows of (angle, type) have seqnum k. */
static inline int n_with_seq(const struct stray_sweep_manifest *mf, double a,
			     int type,
			     int k)
{
	size_t i;
	int n = 0;

	for (i = 0; i < mf->n; i++)
		n += mf->e[i].type == type &&
		     fabs(mf->e[i].angle_deg - a) < 1e-6 &&
		     mf->e[i].seqnum == k;
	return n;
}

static inline int check_angle(const struct stray_sweep_manifest *mf, double a,
			      int reps)
{
	const struct stray_sweep_entry *f, *am;
	int bad = 0, k, n_dark, t;

	for (t = STRAY_SWEEP_AMBIENT; t <= STRAY_SWEEP_FULL; t++)
		for (k = 0; k < reps; k++)
			bad += n_with_seq(mf, a, t, k) != 1;
	if (stray_sweep_manifest_count(mf, a, STRAY_SWEEP_FULL, &f) != reps ||
	    stray_sweep_manifest_count(mf, a, STRAY_SWEEP_AMBIENT, &am) != reps)
		return bad + 1;
	n_dark = fabs(f->exptime_s - am->exptime_s) < 1e-9 ? 1 : 2;
	bad += stray_sweep_manifest_count(mf, a, STRAY_SWEEP_DARK,
					  NULL) != reps * n_dark;
	for (k = 0; k < reps * n_dark; k++) {
		size_t i;
		double want = k < reps ? f->exptime_s : am->exptime_s;

		bad += n_with_seq(mf, a, STRAY_SWEEP_DARK, k) != 1;
		for (i = 0; i < mf->n; i++)
			if (mf->e[i].type == STRAY_SWEEP_DARK &&
			    fabs(mf->e[i].angle_deg - a) < 1e-6 &&
			    mf->e[i].seqnum == k)
				bad += fabs(mf->e[i].exptime_s -
					    want) > 1e-9;
	}
	/* Every lit frame of a group shares one exposure and ND. */
	for (k = 0; k < (int)mf->n; k++) {
		const struct stray_sweep_entry *r = &mf->e[k];
		const struct stray_sweep_entry *g = r->type == STRAY_SWEEP_FULL ? f
						   : am;

		if (r->type == STRAY_SWEEP_DARK ||
		    fabs(r->angle_deg - a) > 1e-6)
			continue;
		bad += r->exptime_s != g->exptime_s ||
		       r->ndtrans != g->ndtrans;
	}
	return bad;
}

static inline int count_fits_files(const char *dir)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	int n = 0;

	while (d && (e = readdir(d)) != NULL)
		n += e->d_name[0] != '.' &&
		     strcmp(e->d_name, "manifest.csv") != 0 &&
		     strcmp(e->d_name, "plan.json") != 0 &&
		     strcmp(e->d_name, "events.log") != 0;
	if (d)
		closedir(d);
	return n;
}

/* Full check of a finished sweep folder against cfg. */
static inline struct sweep_check check_sweep(const char *dir,
					     const struct rig_config *cfg)
{
	struct sweep_check c = { 0, 0 };
	struct stray_sweep_manifest mf;
	struct stray_error se;
	struct rig_error err;
	double *angles;
	int n_angles, k;
	size_t i;
	char path[1024];

	rig_error_clear(&err);
	stray_error_clear(&se);
	if (stray_sweep_manifest_load(dir, &mf, &se) != STRAY_OK) {
		fprintf(stderr, "check: %s\n",
			stray_error_format(&se, path, sizeof(path)));
		c.bad = 1;
		return c;
	}
	c.rows = (int)mf.n;
	for (i = 0; i < mf.n; i++) {
		snprintf(path, sizeof(path), "%s/%s", dir, mf.e[i].file);
		if (stray_sweep_sha256_check(path, mf.e[i].sha256, NULL) !=
		    STRAY_OK) {
			fprintf(stderr, "check: %s: sha256 differs\n", path);
			c.bad++;
		}
		if (fits_key_mismatch(path, &mf.e[i])) {
			fprintf(stderr, "check: %s: header disagrees\n", path);
			c.bad++;
		}
	}
	rig_sweep_angles(&cfg->sweep, &angles, &n_angles, &err);
	for (k = 0; k < n_angles; k++) {
		int b = check_angle(&mf, angles[k], cfg->sweep.repeats);

		if (b)
			fprintf(stderr, "check: angle %g: %d problems\n",
				angles[k], b);
		c.bad += b;
	}
	{
		long in_plan = 0;

		for (k = 0; k < n_angles; k++)
			for (i = 0; i < STRAY_SWEEP_FRAMETYP_COUNT; i++)
				in_plan += stray_sweep_manifest_count(&mf,
								      angles[k],
							      (int)i, NULL);
		if (in_plan != c.rows) {
			fprintf(stderr, "check: %d rows, %ld in plan\n",
				c.rows, in_plan);
			c.bad++;
		}
	}
	if (count_fits_files(dir) != c.rows) {
		fprintf(stderr, "check: %d files for %d rows\n",
			count_fits_files(dir), c.rows);
		c.bad++;
	}
	free(angles);
	stray_sweep_manifest_free(&mf);
	return c;
}

#endif /* RIG_TEST_UTIL_H */
