/*
 * flightcheck_run.c - read a folder of flight frames and run the
 * per-frame step (flightcheck_run.h).  Frames are analysed in parallel
 * (OpenMP), each thread with its own buffers.
 */
#include <fitsio.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flightcheck_run.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/sweep_store.h"

#define PATH_LEN (STRAY_SWEEP_DIR_MAX + STRAY_SWEEP_FILE_MAX + 2)

/* DATE-OBS (UTC) of an open frame, as TT seconds since J2000. */
static int frame_time(struct stray_sweep_fits *f, double *t_tt,
		      struct stray_error *err)
{
	char v[FLEN_VALUE];
	int status = 0;

	if (fits_read_key((fitsfile *)f->fptr, TSTRING, "DATE-OBS", v, NULL,
			  &status))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, 0,
				      "keyword DATE-OBS: missing");
	if (stray_ccsds_epoch(v, stray_ccsds_time_system("UTC"), t_tt))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, 0,
				      "keyword DATE-OBS: not a UTC epoch");
	return STRAY_OK;
}

/*
 * Open one listed frame as reduce does: read once by the toolkit (no
 * symlink, FIFO or device; cfitsio never sees the name), its bytes held
 * to the manifest's SHA-256, decoded from memory; its EXPTIME the
 * manifest's.  f is open on success only.
 */
static int open_frame(const struct stray_sweep_manifest *m,
		      const struct stray_sweep_entry *e,
		      struct stray_sweep_buf *b, char *path,
		      struct stray_sweep_fits *f, struct stray_error *err)
{
	int rc;

	snprintf(path, PATH_LEN, "%s/%s", m->dir, e->file);
	rc = stray_sweep_file_load(path, b, err);
	if (rc == STRAY_OK)
		rc = stray_sweep_sha256_check_mem(path, b->data, b->len,
						  e->sha256, err);
	if (rc == STRAY_OK)
		rc = stray_sweep_fits_open_buf(path, b, f, err);
	if (rc != STRAY_OK)
		return rc;
	/* manifest.csv keeps 6 decimals */
	if (fabs(f->h.exptime_s - e->exptime_s) > 5e-7 + 1e-6 * e->exptime_s) {
		stray_sweep_fits_close(f);
		return stray_error_at(err, STRAY_EINVAL, path, 0,
				      STRAY_SWEEP_KEY_EXPTIME,
				      "differs from manifest.csv's exptime_s");
	}
	return STRAY_OK;
}

/* Frame e (k-th FULL) into px and out; errors name the file. */
static int one_frame(const struct stray_sweep_manifest *m,
		     const struct stray_sweep_entry *e,
		     const struct stray_aem *aem, const struct fc_cfg *cfg,
		     struct stray_sweep_buf *b, uint16_t *px,
		     struct fc_work *w, struct fc_frame *out,
		     struct stray_error *err)
{
	struct stray_sweep_fits f;
	struct fc_cfg at;
	char path[PATH_LEN];
	double t, q[4];
	int rc;

	if ((rc = open_frame(m, e, b, path, &f, err)) != STRAY_OK)
		return rc;
	if ((int)f.h.n_cols != cfg->cols || (int)f.h.n_rows != cfg->rows)
		rc = stray_error_at(err, STRAY_EINVAL, path, 0, 0,
				    "NAXIS: not the size of the first frame");
	if (rc == STRAY_OK)
		rc = frame_time(&f, &t, err);
	if (rc == STRAY_OK && stray_aem_attitude(aem, t, q) != STRAY_OK)
		/* bad input (the frame or the AEM), exit 2 */
		rc = stray_error_at(err, STRAY_EINVAL, path, 0, 0,
			"DATE-OBS: outside the AEM's span or in a gap of it");
	if (rc == STRAY_OK)
		rc = stray_sweep_fits_read(&f, px, err);
	if (rc == STRAY_OK) {
		/* each frame's stars and dark counts with its own EXPTIME */
		fc_cfg_exposure(cfg, f.h.exptime_s, &at);
		fc_frame_analyse(&at, w, px, q, t, out);
		out->t_exp_s = f.h.exptime_s;
	}
	stray_sweep_fits_close(&f);
	return rc;
}

/* The first FULL frame fixes the size and the window's place. */
static int first_frame(const struct stray_sweep_manifest *m,
		       const struct stray_sweep_entry *e,
		       const struct stray_sensor *s,
		       const struct stray_fluxes *fl, struct fc_cfg *cfg,
		       struct stray_error *err)
{
	struct stray_sweep_buf b = { NULL, 0, 0 };
	struct stray_sweep_fits f;
	char path[PATH_LEN];
	int rc = open_frame(m, e, &b, path, &f, err);

	if (rc == STRAY_OK) {
		fc_cfg_init(cfg, s, fl, (int)f.h.n_cols, (int)f.h.n_rows,
			    (int)f.h.col0, (int)f.h.row0);
		stray_sweep_fits_close(&f);
	}
	stray_sweep_buf_free(&b);
	return rc;
}

int fc_run_dir(const char *dir, const struct stray_aem *aem,
	       const struct stray_sensor *s, const struct stray_fluxes *fl,
	       struct fc_cfg *cfg, struct fc_frame **frames, size_t *n,
	       struct stray_error *err)
{
	struct stray_sweep_manifest m;
	struct stray_error bad_err;
	size_t i, nf = 0, *which;
	long bad = -1;
	int rc, nomem = 0;

	*frames = NULL;
	*n = 0;
	if ((rc = stray_sweep_manifest_load(dir, &m, err)) != STRAY_OK)
		return rc;
	which = malloc((m.n + 1) * sizeof(*which));
	for (i = 0; which && i < m.n; i++)
		if (m.e[i].type == STRAY_SWEEP_FULL)
			which[nf++] = i;
	if (!which || nf == 0) {
		free(which);
		stray_sweep_manifest_free(&m);
		return stray_error_at(err, STRAY_EINVAL, dir, 0, 0,
				      "manifest.csv: no FULL frames");
	}
	if ((rc = first_frame(&m, &m.e[which[0]], s, fl, cfg, err)))
		goto out;
	*frames = calloc(nf, sizeof(**frames));
	if (!*frames) {
		rc = stray_error_set(err, STRAY_ENOMEM, "flightcheck", "out of memory");
		goto out;
	}
#pragma omp parallel reduction(|:nomem)
	{
		struct stray_sweep_buf b = { NULL, 0, 0 };
		struct fc_work w;
		/* the size was held to the first file's bytes at its open */
		uint16_t *px = malloc((size_t)cfg->cols * cfg->rows * sizeof(*px));
		long k;

		if (!px || fc_work_alloc(&w, cfg))
			nomem = 1;
#pragma omp for schedule(dynamic)
		for (k = 0; k < (long)nf; k++) {
			struct stray_error e;

			stray_error_clear(&e);
			if (nomem || one_frame(&m, &m.e[which[k]], aem, cfg,
					       &b, px, &w, &(*frames)[k],
					       &e) == STRAY_OK)
				continue;
			/* the first bad frame in manifest order is named */
#pragma omp critical(fc_bad_frame)
			if (bad < 0 || k < bad) {
				bad = k;
				bad_err = e;
			}
		}
		free(px);
		if (px)
			fc_work_free(&w);
		stray_sweep_buf_free(&b);
	}
	if (bad >= 0 || nomem) {
		if (bad >= 0 && err)
			*err = bad_err;
		rc = bad >= 0 ? bad_err.code
			      : stray_error_set(err, STRAY_ENOMEM,
						"flightcheck", "out of memory");
		free(*frames);
		*frames = NULL;
		goto out;
	}
	*n = nf;
	rc = STRAY_OK;
out:
	free(which);
	stray_sweep_manifest_free(&m);
	return rc;
}
