/*
 * diag_surfaces.h - the surface at fault (issue 17 item 4): per-surface-
 * group reflectance (Lambertian groups) or ABg-scale (ABg groups) factors
 * fitted to the measured curve by re-weighting one recorded path table
 * (no re-trace), few groups at a time (greedy forward selection, each
 * added group must lower BIC by DIAG_BIC_MARGIN), profile-chi2 intervals,
 * confirmed by a re-trace of the extended model written as a scene file.
 */
#ifndef DIAGNOSE_DIAG_SURFACES_H
#define DIAGNOSE_DIAG_SURFACES_H

#include <stddef.h>

#include "diagnose/diag_data.h"
#include "diagnose/diag_eval.h"
#include "stray/error.h"

#define DIAG_SURF_MAX 64	/* candidate groups (TRACER_GROUP_MAX) */
#define DIAG_SURF_NAMED_MAX 4	/* groups named together at most */
#define DIAG_SURF_LOG_BOUND 1.5	/* |log10 factor| <= this */

struct diag_surf_table;	/* the path table as re-weightable rows */

struct diag_surfaces {
	int n_cand;		/* interior groups seen in the path table */
	char name[DIAG_SURF_MAX][32];
	int group[DIAG_SURF_MAX];	/* scene group index */
	int abg[DIAG_SURF_MAX];		/* 1: the factor scales ABg's A */
	double rho[DIAG_SURF_MAX];	/* the scene's reflectance */
	int n_named;
	int named[DIAG_SURF_NAMED_MAX];	/* indices into the candidates */
	double log10_f[DIAG_SURF_NAMED_MAX];
	double ci_lo[DIAG_SURF_NAMED_MAX], ci_hi[DIAG_SURF_NAMED_MAX];
	int n_fit;		/* measured points fitted (theta != 0) */
	double chi2_before, chi2_after, bic_before, bic_after;
	double rms_before, rms_after;	/* rms of log10 residuals */
	double chi2_retrace, rms_retrace;	/* NaN: not confirmed */
	size_t n_rows;		/* path-table rows re-weighted */
	size_t n_evals;		/* model evaluations of the fit */
	double fit_seconds;	/* the localisation alone (no trace) */
	const double *base;	/* the registry's model over the nominal, per
				 * measured point, applied on top (NULL: none;
				 * the caller's array) */
	double trace_seconds;
};

/* Build the re-weightable table from one trace of the scene as e
 * describes it (its lens, sets, paths, seed). */
int diag_surf_table_trace(struct diag_eval *e, struct diag_surf_table **t,
			  struct stray_error *err);
void diag_surf_table_free(struct diag_surf_table *t);

/* The localisation by re-weighting t against d; fills s (not the
 * re-trace). */
int diag_surfaces_fit(const struct diag_surf_table *t,
		      const struct diag_data *d, struct diag_surfaces *s,
		      struct stray_error *err);

/* The same on top of the registry's model: base[i] = its alpha over the
 * nominal alpha at measured point i (the causes it named, or its
 * tentative model), so that the groups explain what it leaves. */
int diag_surfaces_fit_on(const struct diag_surf_table *t,
			 const struct diag_data *d, const double *base,
			 struct diag_surfaces *s, struct stray_error *err);

/* Write the extended model: path (JSON scene file) and its mesh beside it
 * (path with .obj for .json; through the atomic writer: in place when
 * the run's outputs are, stray_file_finish), every group's material as the scene's, the
 * named groups' factors applied. */
int diag_surfaces_write_model(const struct diag_eval *e,
			      const struct diag_surfaces *s, const char *path,
			      struct stray_error *err);

/* Confirm: write the model (a private copy, in a temporary directory),
 * trace it at the measured angles (through e's runner, same paths and
 * seed), times s->base when set, and fill chi2_retrace, rms_retrace. */
int diag_surfaces_confirm(struct diag_eval *e, const struct diag_data *d,
			  struct diag_surfaces *s, struct stray_error *err);

#endif /* DIAGNOSE_DIAG_SURFACES_H */
