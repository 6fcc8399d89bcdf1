/*
 * flightcheck_run.c - read a folder of flight frames and run the
 * per-frame step (flightcheck_run.h).  Frames are analysed in parallel
 * (OpenMP), each thread with its own buffers.
 */
#include <errno.h>
#include <fitsio.h>
#include <sys/stat.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mission/flightcheck_run.h"
#include "fdrfw/ephem.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/sweep_store.h"

#define PATH_LEN (STRAY_SWEEP_DIR_MAX + STRAY_SWEEP_FILE_MAX + 2)

/* A string keyword; 0 when present. */
static int key_str(struct stray_sweep_fits *f, const char *key, char *v)
{
	int status = 0;

	return fits_read_key((fitsfile *)f->fptr, TSTRING, key, v, NULL,
			     &status) ? -1 : 0;
}

/*
 * The attitude time of an open frame, TT seconds since J2000: its
 * mid-exposure, DATE-AVG, else the middle of DATE-BEG and DATE-END, else
 * DATE-BEG + EXPTIME/2, else DATE-OBS (taken as mid-exposure: the
 * standard fixes no meaning for it), in the frame's TIMESYS (UTC when
 * absent; UTC, TAI, TT, GPS).
 */
static int frame_time(struct stray_sweep_fits *f, double *t_tt,
		      struct stray_error *err)
{
	char v[FLEN_VALUE], w[FLEN_VALUE];
	const char *key = "DATE-AVG";
	int ts = stray_ccsds_time_system("UTC");
	double t2;

	if (key_str(f, "TIMESYS", v) == 0 &&
	    (ts = stray_ccsds_time_system(v)) < 0)
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, "TIMESYS",
				      "not UTC, TAI, TT or GPS");
	if (key_str(f, key, v) != 0) {
		key = "DATE-BEG";
		if (key_str(f, key, v) != 0) {
			key = "DATE-OBS";
			if (key_str(f, key, v) != 0)
				return stray_error_at(err, STRAY_EPARSE, f->path, 0,
					"DATE-OBS", "missing (and no DATE-AVG or DATE-BEG)");
		}
	}
	if (stray_ccsds_epoch(v, ts, t_tt))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, key,
				      "not an ISO 8601 epoch");
	if (strcmp(key, "DATE-BEG") == 0) {
		if (key_str(f, "DATE-END", w) == 0) {
			if (stray_ccsds_epoch(w, ts, &t2) || t2 < *t_tt)
				return stray_error_at(err, STRAY_EPARSE, f->path, 0,
					"DATE-END", "not an epoch at or after DATE-BEG");
			*t_tt = 0.5 * (*t_tt + t2);
		} else {
			*t_tt += 0.5 * f->h.exptime_s;
		}
	}
	return STRAY_OK;
}

/* A numeric keyword; 1 when absent, 0 with *v, or an error. */
static int key_num(struct stray_sweep_fits *f, const char *key, double *v,
		   double lo, double hi, struct stray_error *err)
{
	int status = 0;

	if (fits_read_key((fitsfile *)f->fptr, TDOUBLE, key, v, NULL, &status)) {
		if (status == KEY_NO_EXIST)
			return 1;
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, key,
				      "not a number");
	}
	if (!(*v >= lo && *v <= hi))
		return stray_error_at(err, STRAY_EINVAL, f->path, 0, key,
				      "out of range (docs/limits.md)");
	return 0;
}

/*
 * The camera of the frame, from its keywords: BIAS (or PEDESTAL, DN)
 * and GAIN (e- per DN) are required, nothing is assumed for them;
 * SATURATE (DN) when present, else SATLEVEL.
 */
static int frame_camera(struct stray_sweep_fits *f, struct fc_cfg *at,
			struct fc_frame *out, struct stray_error *err)
{
	double v;
	int rc;

	if ((rc = key_num(f, "BIAS", &v, 0.0, 65535.0, err)) == 1)
		rc = key_num(f, "PEDESTAL", &v, 0.0, 65535.0, err);
	if (rc == 1)
		return stray_error_at(err, STRAY_EINVAL, f->path, 0, "BIAS",
			"missing: the frame's bias level (DN, or PEDESTAL) is not assumed");
	if (rc)
		return rc;
	at->bias_dn = out->bias_dn = v;
	if ((rc = key_num(f, "GAIN", &v, 1e-3, 1e4, err)) == 1)
		return stray_error_at(err, STRAY_EINVAL, f->path, 0, "GAIN",
			"missing: the frame's gain (e- per DN) is not assumed");
	if (rc)
		return rc;
	at->gain_e_per_dn = out->gain_e_per_dn = v;
	if ((rc = key_num(f, "SATURATE", &v, 1.0, 65535.0, err)) == 1)
		v = (double)f->h.satlevel;
	else if (rc)
		return rc;
	at->sat_dn = v;
	return STRAY_OK;
}

/*
 * Open one listed frame as reduce does: read once by the toolkit (no
 * symlink, FIFO or device; cfitsio never sees the name), its bytes held
 * to the manifest's SHA-256 and its EXPTIME to the manifest's when there
 * is a manifest, decoded from memory, no lab keyword required.  f is
 * open on success only.
 */
static int open_frame(const struct stray_sweep_manifest *m,
		      const struct stray_sweep_entry *e,
		      struct stray_sweep_buf *b, char *path,
		      struct stray_sweep_fits *f, struct stray_error *err)
{
	int rc;

	if (m->dir[0])
		snprintf(path, PATH_LEN, "%s/%s", m->dir, e->file);
	else	/* a list of files */
		snprintf(path, PATH_LEN, "%s", e->file);
	rc = stray_sweep_file_load(path, b, err);
	if (rc == STRAY_OK && e->sha256[0])	/* no manifest: no hash */
		rc = stray_sweep_sha256_check_mem(path, b->data, b->len,
						  e->sha256, err);
	if (rc == STRAY_OK)	/* no lab keyword required */
		rc = stray_sweep_fits_open_flight_buf(path, b, f, err);
	if (rc != STRAY_OK || !e->sha256[0])
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

#define DEG_RAD (3.14159265358979323846 / 180.0)
#define EARTH_KM 6378.137

static double angle_deg(const double a[3], const double b[3])
{
	double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
	double n = sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) *
			(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));

	return acos(fmax(-1.0, fmin(1.0, d / n))) / DEG_RAD;
}

/*
 * The Moon's and the Earth limb's offset angles of the boresight at t
 * (issue 24): the Moon from the spacecraft (from the Earth's centre
 * without an orbit: up to ~1 deg off in LEO), the limb as the angle to
 * the Earth's centre less its angular radius.  Screened when either is
 * under its minimum.
 */
static int body_angles(const struct fc_sky *sky, const char *path,
		       const double q[4], double t, struct fc_frame *out,
		       struct stray_error *err)
{
	double m[3][3], z[3], r[3] = { 0, 0, 0 }, v[3], mo[3], down[3];
	float mk[3];
	int i;

	stray_q_dcm(q, m);
	for (i = 0; i < 3; i++)
		z[i] = m[2][i];
	if (sky && sky->oem && stray_oem_state(sky->oem, t, r, v) != STRAY_OK)
		return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
			"the frame's time: outside the OEM's span or in a gap of it");
	fdrfw_moon_pos_km((int32_t)lround(t), mk);
	for (i = 0; i < 3; i++) {
		mo[i] = mk[i] - r[i];
		down[i] = -r[i];
	}
	out->moon_deg = angle_deg(z, mo);
	out->limb_deg = NAN;
	if (sky && sky->oem) {
		double rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);

		out->limb_deg = angle_deg(z, down) -
				asin(fmin(1.0, EARTH_KM / rn)) / DEG_RAD;
	}
	out->screened = sky && (out->moon_deg < sky->moon_min_deg ||
				out->limb_deg < sky->limb_min_deg);
	return STRAY_OK;
}

/* Frame e (k-th FULL) into px and out; errors name the file. */
static int one_frame(const struct stray_sweep_manifest *m,
		     const struct stray_sweep_entry *e,
		     const struct stray_aem *aem, const struct fc_sky *sky,
		     const struct fc_cfg *cfg,
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
		/* each frame's stars and dark counts with its own EXPTIME,
		 * its camera with its own keywords */
		struct fc_frame cam;

		fc_cfg_exposure(cfg, f.h.exptime_s, &at);
		memset(&cam, 0, sizeof(cam));
		rc = frame_camera(&f, &at, &cam, err);
		if (rc == STRAY_OK) {
			fc_frame_analyse(&at, w, px, q, t, out);
			out->t_exp_s = f.h.exptime_s;
			out->gain_e_per_dn = cam.gain_e_per_dn;
			out->bias_dn = cam.bias_dn;
			rc = body_angles(sky, path, q, t, out, err);
		}
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
	return fc_run_dir_sky(dir, aem, s, fl, NULL, cfg, frames, n, err);
}

int fc_run_dir_sky(const char *dir, const struct stray_aem *aem,
		   const struct stray_sensor *s, const struct stray_fluxes *fl,
		   const struct fc_sky *sky, struct fc_cfg *cfg,
		   struct fc_frame **frames, size_t *n, struct stray_error *err)
{
	struct stray_sweep_manifest m;
	struct stray_error bad_err;
	size_t i, nf = 0, *which;
	long bad = -1;
	int rc, nomem = 0;
	char mpath[PATH_LEN];
	struct stat st;

	*frames = NULL;
	*n = 0;
	/* a manifest when there is one (its hashes checked), else the
	 * folder's FITS files as a camera wrote them */
	snprintf(mpath, sizeof(mpath), "%s/manifest.csv", dir);
	if (sky && sky->files)	/* a list of frame files */
		rc = stray_sweep_flight_files(sky->files, sky->n_files, &m, err);
	else if (lstat(mpath, &st) != 0 && errno == ENOENT)
		rc = stray_sweep_flight_list(dir, &m, err);
	else
		rc = stray_sweep_manifest_load(dir, &m, err);
	if (rc != STRAY_OK)
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
	cfg->starcat = sky ? sky->cat : NULL;
	cfg->colour = sky ? sky->colour : NULL;
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
			if (nomem || one_frame(&m, &m.e[which[k]], aem, sky, cfg,
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

int fc_verdict(const struct fc_summary *s, char *why, size_t n)
{
	if (s->n_cal < FC_MIN_CAL)
		snprintf(why, n, "%d calibration stars (at least %d needed)",
			 s->n_cal, FC_MIN_CAL);
	else if (!(s->match_frac >= FC_MIN_MATCH))
		snprintf(why, n, "%d of the %d predicted stars that cannot be missed found (%.2f; at least %.2f needed): the attitude, time or catalogue does not fit the frames",
			 s->n_sure_found, s->n_sure, s->match_frac, FC_MIN_MATCH);
	else if (s->n_screened >= s->n_frames)
		snprintf(why, n, "every frame has the Moon or the Earth limb within its minimum angle (--moon-min, --limb-min)");
	else if (!(s->resid_px <= FC_MAX_RESID_PX))
		snprintf(why, n, "plate residual %.2f px (at most %.1f allowed)",
			 s->resid_px, FC_MAX_RESID_PX);
	else
		return 0;
	return 1;
}
