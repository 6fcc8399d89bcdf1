/*
 * model_map.h - the one mapping between the flight table and libstray's
 * FDR model (struct fdrfw_table <-> struct stray_fdr_model, thesis
 * eq. 2.3-2.18).
 *
 * FDRFW_MODEL_FIELDS lists, in the table's order, every FDR model constant
 * the table carries, as X(table_field, model_field, min, max).  From this
 * one list come the table's fields (table.h), the range check
 * (fdrfw_table_check, on the ground and on board), the ground's fill
 * (fdrfw_table_from_model), the module's model (fdrfw_model_from_table),
 * the C source the ground writes and the tests' float-core shim: a new
 * constant is one line here.
 *
 * [min, max] is the field's physical domain, closed, on the stored float
 * (NaN and inf are outside every domain).  The bounds are deliberately
 * wide - any real star tracker lies well inside them - but they exclude
 * what no sensor can be: a zero or negative area, a pixel of 1e-38 m^2, an
 * exposure of a year.  Table fields that are not model constants have
 * their bounds in table.h (FDRFW_TABLE_SCALARS); together the two lists
 * are every scalar of the table.  Freestanding C99, no includes: table.h
 * uses it.
 */
#ifndef FDRFW_MODEL_MAP_H
#define FDRFW_MODEL_MAP_H

/* Exposure: frame.c's T_EXP_MAX_S is 100 s; a pixel 0.1 um .. 1 mm
 * square; k_px is 1 or A_cs / (n_tot A_px), also checked as such; an
 * aperture 0.1 mm^2 .. 10 m^2; a window of 1 .. 10^4 pixels (and <= n_tot);
 * 1 .. 10^9 pixels; Pr_drs strictly inside (0, 1); F_drs from a star far
 * fainter than any tracker sees (1 ph/s/m^2) to brighter than Sirius. */
#define FDRFW_MODEL_FIELDS(X) \
	X(t_exp_nominal_s, t_exp_s, 1e-6f, 100.0f)	/* I_sdt's exposure */ \
	X(a_px_m2, a_px_m2, 1e-14f, 1e-6f)	/* A_px, eq. 2.3 */ \
	X(k_px, k_px, 1e-6f, 1e6f)		/* eq. 2.3's k_px */ \
	X(a_cs_m2, a_cs_m2, 1e-8f, 10.0f)	/* A_cs, eq. 2.12 */ \
	X(n_pps, n_pps, 1.0f, 1e4f)		/* window, eq. 2.7 */ \
	X(n_tot, n_tot, 1.0f, 1e9f)		/* pixels, eq. 2.18 */ \
	X(pr_drs, pr_drs, 1e-6f, 0.999999f)	/* eq. 2.16 */ \
	X(f_drs_ph_s_m2, f_drs_ph_s_m2, 1.0f, 1e12f) /* F_drs, eq. 2.12 */

struct fdrfw_table;
struct stray_fdr_model;

/*
 * The thesis model (Gaussian, uniform light, no detector noise, no source
 * yet) from a table's listed fields; the exposure is the nominal one.
 */
void fdrfw_model_from_table(const struct fdrfw_table *t,
			    struct stray_fdr_model *m);

/* The listed fields of a table from a model (ground side), as floats. */
void fdrfw_table_from_model(const struct stray_fdr_model *m,
			    struct fdrfw_table *t);

#endif /* FDRFW_MODEL_MAP_H */
