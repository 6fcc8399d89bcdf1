/*
 * merge.c - several sweep folders of one lens reduced together
 * (stray_reduce_sweeps, reduce_sweep.h).  A lab measures the field edge
 * again next day, or finer, in a second folder; alone it has no on-axis
 * visit to normalise by.  Each folder is reduced on its own (its darks,
 * its masks) to its visits; the visits go on one time line, UTC of each
 * folder's frames, and one curve is fitted through all of them, P(0)
 * and its drift from every on-axis visit.  Row order means nothing
 * across folders, so every folder must carry date_obs.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/reduce_sweep.h"
#include "stray/sweep_store.h"

/* Whether a folder's manifest lists an on-axis frame. */
static int has_on_axis(const char *dir, struct stray_error *err, int *rc)
{
	struct stray_sweep_manifest m;
	size_t i;
	int yes = 0;

	*rc = stray_sweep_manifest_load(dir, &m, err);
	if (*rc != STRAY_OK)
		return 0;
	for (i = 0; i < m.n; i++)
		yes |= m.e[i].type == STRAY_SWEEP_FULL &&
		       fabs(m.e[i].angle_deg) <= STRAY_THETA_TOL_DEG;
	stray_sweep_manifest_free(&m);
	return yes;
}

static int same_window(const struct stray_reduce_sweep_result *a,
		       const struct stray_reduce_sweep_result *b)
{
	return a->n_rows == b->n_rows && a->n_cols == b->n_cols &&
	       a->col0 == b->col0;
}

/* The parts' visits (and profiles) on one time line, in time order. */
static int join(struct stray_reduce_sweep_result *parts, size_t n,
		struct stray_reduce_sweep_result *ref, struct stray_error *err)
{
	size_t total = 0, k = 0, i, v, nc = ref->n_cols;
	double t0 = HUGE_VAL;
	struct stray_visit *vis;
	double *prof;

	for (i = 0; i < n; i++) {
		total += parts[i].n_visits;
		t0 = fmin(t0, parts[i].t0_utc);
	}
	vis = malloc(total * sizeof(*vis));
	prof = malloc(total * nc * sizeof(*prof));
	if (!vis || !prof) {
		free(vis);
		free(prof);
		return stray_error_set(err, STRAY_ENOMEM, "sweep", "no memory");
	}
	for (i = 0; i < n; i++)
		for (v = 0; v < parts[i].n_visits; v++) {
			size_t j = k++;

			vis[j] = parts[i].visits[v];
			vis[j].order += parts[i].t0_utc - t0;
			/* insertion into time order, profile alongside */
			memcpy(prof + j * nc, parts[i].profiles + v * nc,
			       nc * sizeof(*prof));
			while (j > 0 && vis[j - 1].order > vis[j].order) {
				struct stray_visit tv = vis[j];
				double *a = prof + (j - 1) * nc, tp;
				size_t c;

				vis[j] = vis[j - 1];
				vis[j - 1] = tv;
				for (c = 0; c < nc; c++) {
					tp = a[c];
					a[c] = a[c + nc];
					a[c + nc] = tp;
				}
				j--;
			}
		}
	free(ref->visits);
	free(ref->profiles);
	ref->visits = vis;
	ref->profiles = prof;
	ref->n_visits = total;
	ref->t0_utc = t0;
	return STRAY_OK;
}

int stray_reduce_sweeps(const char *const *dirs, size_t n_dirs,
			const struct stray_reduce_sweep_opts *o,
			struct stray_reduce_sweep_result *res,
			struct stray_error *err)
{
	struct stray_reduce_sweep_result *parts = calloc(n_dirs,
							 sizeof(*parts));
	struct stray_reduce_sweep_opts oi;
	size_t i, ref = n_dirs;
	double lo = HUGE_VAL, hi = -HUGE_VAL;
	int rc = parts ? STRAY_OK : stray_error_set(err, STRAY_ENOMEM,
						     "sweep", "no memory");

	memset(res, 0, sizeof(*res));
	for (i = 0; rc == STRAY_OK && i < n_dirs; i++) {
		oi = *o;
		oi.visits_only = !has_on_axis(dirs[i], err, &rc);
		if (rc != STRAY_OK)
			break;
		if (!oi.visits_only && ref == n_dirs)
			ref = i;
		else
			oi.keep_image = 0;
		rc = stray_reduce_sweep(dirs[i], &oi, &parts[i], err);
		if (rc == STRAY_OK && !parts[i].drift_in_time)
			rc = stray_error_at(err, STRAY_EINVAL, dirs[i], 0,
				STRAY_SWEEP_COL_DATE_OBS, "not in every "
				"manifest row: folders are merged on their "
				"frames' times; reduce this folder alone");
		if (rc == STRAY_OK && i > 0 && !same_window(&parts[0],
							    &parts[i]))
			rc = stray_error_at(err, STRAY_EINVAL, dirs[i], 0,
				"NAXIS1", "another window (rows, columns) "
				"than the first folder's: not one curve");
	}
	if (rc == STRAY_OK && ref == n_dirs)
		rc = stray_error_at(err, STRAY_ENOTFOUND, dirs[0], 0, "ANGLE",
			"no on-axis (0 deg) visit in any of the folders to "
			"normalise by; add the folder that has one");
	if (rc == STRAY_OK)
		rc = join(parts, n_dirs, &parts[ref], err);
	if (rc == STRAY_OK) {
		struct stray_reduce_sweep_result *r = &parts[ref];

		for (i = 0; i < n_dirs; i++) {
			if (i != ref) {
				r->n_frames += parts[i].n_frames;
				r->n_darks += parts[i].n_darks;
				r->n_sat_samples += parts[i].n_sat_samples;
				r->n_sat_pixels += parts[i].n_sat_pixels;
			}
			lo = fmin(lo, parts[i].t0_utc);
			hi = fmax(hi, parts[i].t0_utc + parts[i].span_s);
		}
		free(r->points);
		r->points = calloc(r->n_visits, sizeof(*r->points));
		rc = r->points ? stray_reduce_curve(r->visits, r->n_visits,
				r->points, &r->n_points, &r->drift, err)
			       : stray_error_set(err, STRAY_ENOMEM, "curve",
						 "no memory");
		r->p0 = r->drift.p0;
		r->span_s = hi - lo;
		r->n_folders = n_dirs;
	}
	for (i = 0; parts && i < n_dirs; i++)
		if (rc != STRAY_OK || i != ref)
			stray_reduce_sweep_result_free(&parts[i]);
	if (rc == STRAY_OK)
		*res = parts[ref];
	free(parts);
	return rc;
}
