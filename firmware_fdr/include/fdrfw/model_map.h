/*
 * model_map.h - the one mapping between the flight table and libstray's
 * FDR model (struct fdrfw_table <-> struct stray_fdr_model, thesis
 * eq. 2.3-2.18).
 *
 * FDRFW_MODEL_FIELDS lists, in the table's order, every FDR model constant
 * the table carries, as X(table_field, model_field, domain).  From this
 * one list come the table's fields (table.h), the range check
 * (fdrfw_table_check), the ground's fill (fdrfw_table_from_model), the
 * module's model (fdrfw_model_from_table), the C source the ground writes
 * and the tests' float-core shim: a new constant is one line here.
 *
 * domain names one of table.c's predicates on the stored float:
 * positive (finite, > 0), at_least_one (finite, >= 1) or probability
 * (in [1e-6, 1 - 1e-6]).  Freestanding C99, no includes: table.h uses it.
 */
#ifndef FDRFW_MODEL_MAP_H
#define FDRFW_MODEL_MAP_H

#define FDRFW_MODEL_FIELDS(X) \
	X(t_exp_nominal_s, t_exp_s, positive)	/* I_sdt's exposure */ \
	X(a_px_m2, a_px_m2, positive)		/* A_px, eq. 2.3 */ \
	X(k_px, k_px, positive)			/* eq. 2.3's k_px */ \
	X(a_cs_m2, a_cs_m2, positive)		/* A_cs, eq. 2.12 */ \
	X(n_pps, n_pps, at_least_one)		/* window, eq. 2.7 */ \
	X(n_tot, n_tot, positive)		/* pixels, eq. 2.18 */ \
	X(pr_drs, pr_drs, probability)		/* eq. 2.16 */ \
	X(f_drs_ph_s_m2, f_drs_ph_s_m2, positive) /* F_drs, eq. 2.12 */

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
