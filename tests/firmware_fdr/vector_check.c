/*
 * vector_check.c - one comparison of a frame with its ground vector,
 * shared by the host test and the emulated target (freestanding).
 */
#include <math.h>
#include <string.h>

#include "vectors.h"

void fdrfw_vector_input(const struct fdrfw_vector *v, struct fdrfw_input *in)
{
	memset(in, 0, sizeof(*in));
	memcpy(in->q, v->q, sizeof(in->q));
	memcpy(in->pos_km, v->pos_km, sizeof(in->pos_km));
	memcpy(in->sun_dir, v->sun_dir, sizeof(in->sun_dir));
	memcpy(in->moon_dir, v->moon_dir, sizeof(in->moon_dir));
	in->t_exp_s = v->t_exp_s;
	in->use_given_dirs = 1;
}

int fdrfw_vector_check(const struct fdrfw_vector *v,
		       const struct fdrfw_output *out, double *worst)
{
	int b;

	for (b = 0; b < 2; b++) {
		double d_ln = fabs((double)out->ln_fdr[b] - v->ln_fdr[b]);

		if (!(fabs((double)out->theta_deg[b] - v->theta_deg[b]) <=
		      FDRFW_VECTOR_THETA_TOL_DEG))
			return 1 + b;
		if (v->ln_fdr[b] < FDRFW_VECTOR_LN_FLOOR) {
			if (!((double)out->ln_fdr[b] < FDRFW_VECTOR_LN_FLOOR +
			      FDRFW_VECTOR_LN_TOL))
				return 3 + b;
			continue;
		}
		if (!(d_ln <= FDRFW_VECTOR_LN_TOL))
			return 3 + b;
		if (d_ln > *worst)
			*worst = d_ln;
	}
	if ((out->flags & FDRFW_VECTOR_FLAGS) != v->flags)
		return 5;
	return 0;
}
