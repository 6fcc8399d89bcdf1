/*
 * tail.c - Gaussian and Poisson tails in the log domain (freestanding).
 *
 * Thesis eq. 2.16-2.17 integrate Gaussian densities above a threshold;
 * at strong attenuation the result is far below the smallest double, so
 * everything here works with logarithms and never forms a tail that could
 * underflow before the logarithm is taken.  stray_real and the stray_*
 * math functions are double, or float in flight builds (config.h).
 */
#include "stray/config.h"
#include "stray/root.h"
#include "stray/tail.h"

#define LN_SQRT_2PI STRAY_R(0.918938533204672741780329736406)
#define SQRT1_2 STRAY_R(0.707106781186547524400844362105)

/* Below this z, erfc is used directly, beyond it Laplace's fraction: 26 in
 * double (Q(26) ~ 1e-149, far from underflow), 5 in float (config.h). */
#define GAUSS_CF_FROM_Z STRAY_GAUSS_CF_FROM_Z
/* Depth of Laplace's continued fraction; ample at z >= 26 (see tests), and
 * exact to double already from z = 3. */
#define GAUSS_CF_DEPTH 64

stray_real stray_log_add(stray_real a, stray_real b)
{
	stray_real hi = a > b ? a : b;
	stray_real lo = a > b ? b : a;

	if (lo == -STRAY_HUGE)
		return hi;
	return hi + stray_log1p(stray_exp(lo - hi));
}

/*
 * ln Q(z) for large z by Laplace's continued fraction (Abramowitz & Stegun
 * 26.2.14):  Q(z) = phi(z) / (z + 1/(z + 2/(z + 3/(z + ...)))),
 * evaluated from the bottom up at a fixed depth.
 */
static stray_real log_gauss_q_cf(stray_real z)
{
	stray_real d = z;
	int k;

	for (k = GAUSS_CF_DEPTH; k >= 1; k--)
		d = z + (stray_real)k / d;
	return -STRAY_R(0.5) * z * z - LN_SQRT_2PI - stray_log(d);
}

stray_real stray_log_gauss_q(stray_real z)
{
	if (isnan(z))
		return z;
	if (z >= GAUSS_CF_FROM_Z)
		return log_gauss_q_cf(z);
	if (z >= -GAUSS_CF_FROM_Z)
		return stray_log(STRAY_R(0.5) * stray_erfc(z * SQRT1_2));
	/* Q(z) = 1 - Q(-z), and Q(-z) is tiny here. */
	return stray_log1p(-stray_exp(log_gauss_q_cf(-z)));
}

stray_real stray_gauss_q(stray_real z)
{
	return stray_exp(stray_log_gauss_q(z));
}

struct q_inv_ctx {
	stray_real log_p;
};

static int q_inv_residual(stray_real z, void *ctx, stray_real *y)
{
	const struct q_inv_ctx *c = ctx;

	*y = stray_log_gauss_q(z) - c->log_p;
	return STRAY_OK;
}

int stray_gauss_q_inv(stray_real p, stray_real *z, struct stray_error *err)
{
	struct q_inv_ctx ctx;
	struct stray_root_result res;
	int rc;

	if (!(p > 0 && p < 1))
		return stray_error_set_value(err, STRAY_EINVAL, "probability",
			STRAY_MSG("must lie strictly between 0 and 1"), p);
	ctx.log_p = stray_log(p);
	/* ln Q spans [ln(1 - 1e-350), -800] over [-40, 40]: every double p
	 * (and every float).  1e-14 in z is 45 double epsilons; a float
	 * build scales it to its own epsilon (STRAY_TOL). */
	rc = stray_root_brent(q_inv_residual, &ctx, STRAY_R(-40.0),
			      STRAY_R(40.0), STRAY_TOL(1e-14), &res, err);
	if (rc == STRAY_OK)
		*z = res.x;
	return rc;
}

/* ln of the common prefactor x^a e^-x / Gamma(a + shift). */
static stray_real log_gamma_prefactor(stray_real a, stray_real x,
				      stray_real shift)
{
	return a * stray_log(x) - x - stray_lgamma(a + shift);
}

/*
 * P(a, x) by its power series (Numerical Recipes 3rd ed. §6.2, eq. 6.2.5):
 * P = x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)); for x < a + 1.
 */
static int log_gamma_p_series(stray_real a, stray_real x, stray_real *log_p,
			      struct stray_error *err)
{
	stray_real term = 1, sum = 1, ap = a;
	long n;

	for (n = 0; n < STRAY_SERIES_ITER_MAX; n++) {
		ap += 1;
		term *= x / ap;
		sum += term;
		if (term < sum * STRAY_EPSILON * STRAY_R(0.5)) {
			*log_p = log_gamma_prefactor(a, x, 1) + stray_log(sum);
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
static int log_gamma_q_cf(stray_real a, stray_real x, stray_real *log_q,
			  struct stray_error *err)
{
	const stray_real tiny = STRAY_REAL_MIN / STRAY_EPSILON;
	stray_real b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
	long i;

	for (i = 1; i < STRAY_SERIES_ITER_MAX; i++) {
		stray_real an = -(stray_real)i * ((stray_real)i - a), del;

		b += 2;
		d = an * d + b;
		if (stray_fabs(d) < tiny)
			d = tiny;
		c = b + an / c;
		if (stray_fabs(c) < tiny)
			c = tiny;
		d = 1 / d;
		del = d * c;
		h *= del;
		if (stray_fabs(del - 1) <= STRAY_EPSILON) {
			*log_q = log_gamma_prefactor(a, x, 0) + stray_log(h);
			return STRAY_OK;
		}
	}
	return stray_error_set_value(err, STRAY_ENOCONV, "poisson_mean",
		STRAY_MSG("incomplete-gamma fraction did not converge"), x);
}

static int gamma_args_check(stray_real a, stray_real x,
			    struct stray_error *err)
{
	if (!(a > 0) || !isfinite(a))
		return stray_error_set_value(err, STRAY_EINVAL, "gamma_a",
			STRAY_MSG("must be finite and > 0"), a);
	if (!(x >= 0) || !isfinite(x))
		return stray_error_set_value(err, STRAY_EINVAL, "gamma_x",
			STRAY_MSG("must be finite and >= 0"), x);
	return STRAY_OK;
}

int stray_log_gamma_p(stray_real a, stray_real x, stray_real *log_p,
		      struct stray_error *err)
{
	stray_real log_q;
	int rc = gamma_args_check(a, x, err);

	if (rc != STRAY_OK)
		return rc;
	if (x == 0) {
		*log_p = -STRAY_HUGE;
		return STRAY_OK;
	}
	if (x < a + 1)
		return log_gamma_p_series(a, x, log_p, err);
	rc = log_gamma_q_cf(a, x, &log_q, err);
	if (rc == STRAY_OK)
		*log_p = stray_log1p(-stray_exp(log_q));
	return rc;
}

int stray_log_gamma_q(stray_real a, stray_real x, stray_real *log_q,
		      struct stray_error *err)
{
	stray_real log_p;
	int rc = gamma_args_check(a, x, err);

	if (rc != STRAY_OK)
		return rc;
	if (x == 0) {
		*log_q = 0;
		return STRAY_OK;
	}
	if (x >= a + 1)
		return log_gamma_q_cf(a, x, log_q, err);
	rc = log_gamma_p_series(a, x, &log_p, err);
	if (rc == STRAY_OK)
		*log_q = stray_log1p(-stray_exp(log_p));
	return rc;
}
