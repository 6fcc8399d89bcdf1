/*
 * model_map.c - the flight table <-> FDR model mapping of model_map.h,
 * both directions expanded from FDRFW_MODEL_FIELDS.  The module uses the
 * first, the ground's table builder the second (the target image's
 * --gc-sections drops it).
 */
#include <stddef.h>

#include "fdrfw/model_map.h"
#include "fdrfw/table.h"
#include "stray/fdr.h"

void fdrfw_model_from_table(const struct fdrfw_table *t,
			    struct stray_fdr_model *m)
{
#define FDRFW_TO_MODEL(tf, mf, lo, hi) m->mf = (stray_real)t->tf;
	FDRFW_MODEL_FIELDS(FDRFW_TO_MODEL)
	/* The thesis model: a source sets its own flux. */
	m->f_src_ph_s_m2 = 0;
	m->read_noise_e = 0;
	m->dark_current_e_s = 0;
	m->noise = STRAY_NOISE_GAUSS;
	m->map = NULL;
}

void fdrfw_table_from_model(const struct stray_fdr_model *m,
			    struct fdrfw_table *t)
{
#define FDRFW_TO_TABLE(tf, mf, lo, hi) t->tf = (float)m->mf;
	FDRFW_MODEL_FIELDS(FDRFW_TO_TABLE)
}
