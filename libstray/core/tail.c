/*
 * tail.c - Gaussian and Poisson tails in the log domain (freestanding).
 *
 * Thesis eq. 2.16-2.17 integrate Gaussian densities above a threshold;
 * at strong attenuation the result is far below the smallest double, so
 * everything here works with logarithms and never forms a tail that could
 * underflow before the logarithm is taken.
 */
#include <float.h>
#include <math.h>

#include "stray/config.h"
#include "stray/root.h"
#include "stray/tail.h"

#define LN_SQRT_2PI 0.918938533204672741780329736406
#define SQRT1_2 0.707106781186547524400844362105

/* Below this z, erfc is used directly: Q(26) ~ 1e-149, far from underflow. */
#define GAUSS_CF_FROM_Z 26.0
/* Depth of Laplace's continued fraction; ample at z >= 26 (see tests). */
#define GAUSS_CF_DEPTH 64

double stray_log_add(double a, double b)
{
	double hi = a > b ? a : b;
	double lo = a > b ? b : a;

	if (lo == -HUGE_VAL)
		return hi;
	return hi + log1p(exp(lo - hi));
}

/*
 * ln Q(z) for large z by Laplace's continued fraction (Abramowitz & Stegun
 * 26.2.14):  Q(z) = phi(z) / (z + 1/(z + 2/(z + 3/(z + ...)))),
 * evaluated from the bottom up at a fixed depth.
 */
static double log_gauss_q_cf(double z)
{
	double d = z;
	int k;

	for (k = GAUSS_CF_DEPTH; k >= 1; k--)
		d = z + (double)k / d;
	return -0.5 * z * z - LN_SQRT_2PI - log(d);
}

double stray_log_gauss_q(double z)
{
	if (isnan(z))
		return z;
	if (z >= GAUSS_CF_FROM_Z)
		return log_gauss_q_cf(z);
	if (z >= -GAUSS_CF_FROM_Z)
		return log(0.5 * erfc(z * SQRT1_2));
	/* Q(z) = 1 - Q(-z), and Q(-z) is tiny here. */
	return log1p(-exp(log_gauss_q_cf(-z)));
}

double stray_gauss_q(double z)
{
	return exp(stray_log_gauss_q(z));
}

struct q_inv_ctx {
	double log_p;
};

static int q_inv_residual(double z, void *ctx, double *y)
{
	const struct q_inv_ctx *c = ctx;

	*y = stray_log_gauss_q(z) - c->log_p;
	return STRAY_OK;
}

int stray_gauss_q_inv(double p, double *z, struct stray_error *err)
{
	struct q_inv_ctx ctx;
	struct stray_root_result res;
	int rc;

	if (!(p > 0.0 && p < 1.0))
		return stray_error_set_value(err, STRAY_EINVAL, "probability",
			STRAY_MSG("must lie strictly between 0 and 1"), p);
	ctx.log_p = log(p);
	/* ln Q spans [ln(1 - 1e-350), -800] over [-40, 40]: every double p. */
	rc = stray_root_brent(q_inv_residual, &ctx, -40.0, 40.0, 1e-14, &res,
			      err);
	if (rc == STRAY_OK)
		*z = res.x;
	return rc;
}

/* ln of the common prefactor x^a e^-x / Gamma(a + shift). */
static double log_gamma_prefactor(double a, double x, double shift)
{
	return a * log(x) - x - lgamma(a + shift);
}

/*
 * P(a, x) by its power series (Numerical Recipes 3rd ed. §6.2, eq. 6.2.5):
 * P = x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)); for x < a + 1.
 */
static int log_gamma_p_series(double a, double x, double *log_p,
			      struct stray_error *err)
{
	double term = 1.0, sum = 1.0, ap = a;
	long n;

	for (n = 0; n < STRAY_SERIES_ITER_MAX; n++) {
		ap += 1.0;
		term *= x / ap;
		sum += term;
		if (term < sum * DBL_EPSILON * 0.5) {
			*log_p = log_gamma_prefactor(a, x, 1.0) + log(sum);
			return STRAY_OK;
		}
	}
	return stray_error_set_value(err, STRAY_ENOCONV, "poisson_mean",
		STRAY_MSG("incomplete-gamma series did not converge"), x);
}

/*
 * Q(a, x) by its continued fraction, modified Lentz (Numerical Recipes
 * 3rd ed. §6.2, eq. 6.2.7); for x >= a + 1.
 */
static int log_gamma_q_cf(double a, double x, double *log_q,
			  struct stray_error *err)
{
	const double tiny = DBL_MIN / DBL_EPSILON;
	double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
	long i;

	for (i = 1; i < STRAY_SERIES_ITER_MAX; i++) {
		double an = -(double)i * ((double)i - a), del;

		b += 2.0;
		d = an * d + b;
		if (fabs(d) < tiny)
			d = tiny;
		c = b + an / c;
		if (fabs(c) < tiny)
			c = tiny;
		d = 1.0 / d;
		del = d * c;
		h *= del;
		if (fabs(del - 1.0) <= DBL_EPSILON) {
			*log_q = log_gamma_prefactor(a, x, 0.0) + log(h);
			return STRAY_OK;
		}
	}
	return stray_error_set_value(err, STRAY_ENOCONV, "poisson_mean",
		STRAY_MSG("incomplete-gamma fraction did not converge"), x);
}

static int gamma_args_check(double a, double x, struct stray_error *err)
{
	if (!(a > 0.0) || !isfinite(a))
		return stray_error_set_value(err, STRAY_EINVAL, "gamma_a",
			STRAY_MSG("must be finite and > 0"), a);
	if (!(x >= 0.0) || !isfinite(x))
		return stray_error_set_value(err, STRAY_EINVAL, "gamma_x",
			STRAY_MSG("must be finite and >= 0"), x);
	return STRAY_OK;
}

int stray_log_gamma_p(double a, double x, double *log_p,
		      struct stray_error *err)
{
	double log_q;
	int rc = gamma_args_check(a, x, err);

	if (rc != STRAY_OK)
		return rc;
	if (x == 0.0) {
		*log_p = -HUGE_VAL;
		return STRAY_OK;
	}
	if (x < a + 1.0)
		return log_gamma_p_series(a, x, log_p, err);
	rc = log_gamma_q_cf(a, x, &log_q, err);
	if (rc == STRAY_OK)
		*log_p = log1p(-exp(log_q));
	return rc;
}

int stray_log_gamma_q(double a, double x, double *log_q,
		      struct stray_error *err)
{
	double log_p;
	int rc = gamma_args_check(a, x, err);

	if (rc != STRAY_OK)
		return rc;
	if (x == 0.0) {
		*log_q = 0.0;
		return STRAY_OK;
	}
	if (x >= a + 1.0)
		return log_gamma_q_cf(a, x, log_q, err);
	rc = log_gamma_p_series(a, x, &log_p, err);
	if (rc == STRAY_OK)
		*log_q = log1p(-exp(log_p));
	return rc;
}
