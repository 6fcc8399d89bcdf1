/*
 * float_core.h - libstray's FDR core built with STRAY_REAL_FLOAT (as on
 * the flight target), reached from a double test through this interface.
 *
 * float_core.c and the core's sources are compiled with -DSTRAY_REAL_FLOAT
 * and linked into one relocatable object whose only global symbols are
 * fcore_* (module.mk), so the float core sits beside the double libstray
 * in one test binary and the two are compared call for call.
 */
#ifndef FDRFW_TEST_FLOAT_CORE_H
#define FDRFW_TEST_FLOAT_CORE_H

#include "fdrfw/table.h"

/*
 * The thesis model (Gaussian, uniform light) of a flight table, through
 * the module's own mapping (fdrfw_model_from_table, built in float here),
 * at an exposure and a source flux of the test's choosing.
 */
struct fcore_model {
	const struct fdrfw_table *table;
	double t_exp_s, f_src_ph_s_m2;
};

/* Nonzero when the object was built with float as its real type. */
int fcore_real_is_float(void);

double fcore_log_gauss_q(double z);
int fcore_gauss_q_inv(double p, double *z);
int fcore_log_gamma_p(double a, double x, double *log_p);

/* Brent on x^3 - c over [0, c + 1] at the float tolerance. */
int fcore_root_cbrt(double c, double *x, int *iterations);

int fcore_fdr_threshold(const struct fcore_model *m, double *i_sdt);
double fcore_fdr_threshold_gauss(const struct fcore_model *m, double z);
int fcore_fdr_log_rate(const struct fcore_model *m, double alpha,
		       double i_sdt, double *log_fdr);
int fcore_fdr_alpha_required(const struct fcore_model *m, double rate,
			     double *alpha_req);

#endif /* FDRFW_TEST_FLOAT_CORE_H */
