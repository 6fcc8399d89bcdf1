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

/* The thesis model's fields (Gaussian, uniform light), as doubles. */
struct fcore_model {
	double f_src_ph_s_m2, f_drs_ph_s_m2, t_exp_s, a_px_m2, a_cs_m2;
	double n_pps, n_tot, pr_drs, read_noise_e, dark_current_e_s;
	int poisson;		/* 1: the exact-Poisson noise model */
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
