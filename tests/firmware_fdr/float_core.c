/*
 * float_core.c - the double-typed face of the float build of libstray's
 * core (see float_core.h).  Compiled with -DSTRAY_REAL_FLOAT
 * -Wdouble-promotion: every conversion here is explicit.
 */
#include <stddef.h>

#include "fdrfw/model_map.h"
#include "float_core.h"
#include "stray/fdr.h"
#include "stray/root.h"
#include "stray/tail.h"

static void model_of(const struct fcore_model *d, struct stray_fdr_model *m)
{
	fdrfw_model_from_table(d->table, m);
	m->t_exp_s = (stray_real)d->t_exp_s;
	m->f_src_ph_s_m2 = (stray_real)d->f_src_ph_s_m2;
}

int fcore_real_is_float(void)
{
	return sizeof(stray_real) == sizeof(float);
}

double fcore_log_gauss_q(double z)
{
	return (double)stray_log_gauss_q((stray_real)z);
}

int fcore_gauss_q_inv(double p, double *z)
{
	stray_real zf = 0;
	int rc = stray_gauss_q_inv((stray_real)p, &zf, NULL);

	*z = (double)zf;
	return rc;
}

int fcore_log_gamma_p(double a, double x, double *log_p)
{
	stray_real lp = 0;
	int rc = stray_log_gamma_p((stray_real)a, (stray_real)x, &lp, NULL);

	*log_p = (double)lp;
	return rc;
}

static int cube_minus(stray_real x, void *ctx, stray_real *y)
{
	*y = x * x * x - *(const stray_real *)ctx;
	return STRAY_OK;
}

int fcore_root_cbrt(double c, double *x, int *iterations)
{
	stray_real cf = (stray_real)c;
	struct stray_root_result res = { 0, 0 };
	int rc = stray_root_brent(cube_minus, &cf, 0, cf + 1,
				  STRAY_TOL(1e-14), &res, NULL);

	*x = (double)res.x;
	*iterations = res.iterations;
	return rc;
}

int fcore_fdr_threshold(const struct fcore_model *d, double *i_sdt)
{
	struct stray_fdr_model m;
	stray_real t = 0;
	int rc;

	model_of(d, &m);
	rc = stray_fdr_threshold(&m, &t, NULL);
	*i_sdt = (double)t;
	return rc;
}

double fcore_fdr_threshold_gauss(const struct fcore_model *d, double z)
{
	struct stray_fdr_model m;

	model_of(d, &m);
	return (double)stray_fdr_threshold_gauss(&m, (stray_real)z);
}

int fcore_fdr_log_rate(const struct fcore_model *d, double alpha,
		       double i_sdt, double *log_fdr)
{
	struct stray_fdr_model m;
	stray_real l = 0;
	int rc;

	model_of(d, &m);
	rc = stray_fdr_log_rate(&m, (stray_real)alpha, (stray_real)i_sdt, &l,
				NULL);
	*log_fdr = (double)l;
	return rc;
}

int fcore_fdr_alpha_required(const struct fcore_model *d, double rate,
			     double *alpha_req)
{
	struct stray_fdr_model m;
	stray_real a = 0;
	int rc;

	model_of(d, &m);
	rc = stray_fdr_alpha_required(&m, (stray_real)rate, &a, NULL);
	*alpha_req = (double)a;
	return rc;
}
