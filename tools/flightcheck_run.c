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

int fc_run_dir(const char *dir, const struct stray_aem *aem,
	       const struct stray_sensor *s, const struct stray_fluxes *fl,
	       struct fc_cfg *cfg, struct fc_frame **frames, size_t *n,
	       struct stray_error *err)
{
	struct stray_sweep_manifest m;
	struct stray_sweep_fits f;
	size_t i, nf = 0, *which;
	char path[4096];
	int rc, fail = 0;

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
	snprintf(path, sizeof(path), "%s/%s", dir, m.e[which[0]].file);
	if ((rc = stray_sweep_fits_open(path, &f, err)) != STRAY_OK)
		goto out;
	fc_cfg_init(cfg, s, fl, (int)f.h.n_cols, (int)f.h.n_rows,
		    (int)f.h.col0, (int)f.h.row0);
	cfg->t_exp_s = f.h.exptime_s;
	stray_sweep_fits_close(&f);
	*frames = calloc(nf, sizeof(**frames));
	if (!*frames) {
		rc = stray_error_set(err, STRAY_ENOMEM, "flightcheck", "out of memory");
		goto out;
	}
#pragma omp parallel reduction(|:fail)
	{
		struct fc_work w;
		uint16_t *px = malloc((size_t)cfg->cols * cfg->rows * sizeof(*px));
		long k;

		if (!px || fc_work_alloc(&w, cfg))
			fail = 1;
#pragma omp for schedule(dynamic)
		for (k = 0; k < (long)nf; k++) {
			struct stray_sweep_fits ff;
			struct stray_error e;
			char p[4096];
			double t, q[4];

			if (fail)
				continue;
			snprintf(p, sizeof(p), "%s/%s", dir, m.e[which[k]].file);
			if (stray_sweep_fits_open(p, &ff, &e) != STRAY_OK) {
				fail = 2;
				continue;
			}
			if ((int)ff.h.n_cols != cfg->cols ||
			    (int)ff.h.n_rows != cfg->rows ||
			    frame_time(&ff, &t, &e) != STRAY_OK ||
			    stray_sweep_fits_read(&ff, px, &e) != STRAY_OK ||
			    stray_aem_attitude(aem, t, q) != STRAY_OK) {
				stray_sweep_fits_close(&ff);
				fail = 2;
				(*frames)[k].t_tt = NAN;
				continue;
			}
			stray_sweep_fits_close(&ff);
			fc_frame_analyse(cfg, &w, px, q, t, &(*frames)[k]);
		}
		free(px);
		if (px)
			fc_work_free(&w);
	}
	if (fail) {
		/* find the first bad frame again, serially, for its message */
		for (i = 0; i < nf; i++) {
			double t, q[4];

			snprintf(path, sizeof(path), "%s/%s", dir, m.e[which[i]].file);
			if ((rc = stray_sweep_fits_open(path, &f, err)) != STRAY_OK)
				break;
			rc = frame_time(&f, &t, err);
			if (rc == STRAY_OK && ((int)f.h.n_cols != cfg->cols ||
					       (int)f.h.n_rows != cfg->rows))
				rc = stray_error_at(err, STRAY_EINVAL, path, 0, 0,
					"NAXIS: not the size of the first frame");
			if (rc == STRAY_OK && stray_aem_attitude(aem, t, q) != STRAY_OK)
				/* bad input (the frame or the AEM), exit 2 */
				rc = stray_error_at(err, STRAY_EINVAL, path, 0, 0,
					"DATE-OBS: outside the AEM's span or in a gap of it");
			stray_sweep_fits_close(&f);
			if (rc != STRAY_OK)
				break;
		}
		if (rc == STRAY_OK)
			rc = stray_error_set(err, STRAY_ENOMEM, "flightcheck",
					     "out of memory");
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
