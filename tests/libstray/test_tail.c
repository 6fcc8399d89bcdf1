/*
 * test_tail.c - Gaussian and Poisson tails (tail.c) against values computed
 * independently with mpmath at 60 digits (tests/vectors/make_tail_vectors.py).
 */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../test_util.h"

#include "stray/table.h"
#include "stray/tail.h"

static struct stray_table load(const char *path)
{
	struct stray_table t;
	struct stray_error err;

	stray_error_clear(&err);
	assert_int_equal(stray_table_read(path, &t, &err), STRAY_OK);
	assert_true(t.n_rows > 5);
	return t;
}

/* eq. 2.17 kernel: ln Q(z) to 1e-13 absolute (Q to 1e-13 relative) over
 * z in [-30, 1000], i.e. down to Q = 1e-217151, far below 1e-300. */
static void test_log_gauss_q_matches_mpmath(void **state)
{
	struct stray_table t = load("tests/vectors/gauss_tail.csv");
	size_t i;

	(void)state;
	for (i = 0; i < t.n_rows; i++) {
		double z = t.cell[3 * i], ref = t.cell[3 * i + 1];
		double got = stray_log_gauss_q(z);
		double tol = 1e-13 + 4.0 * DBL_EPSILON * fabs(ref);

		if (fabs(got - ref) > tol)
			fail_msg("z = %g: ln Q = %.17g, mpmath %.17g", z, got, ref);
	}
	stray_table_free(&t);
}

/* Where Q itself is representable (>= 1e-300) it must be there, to 1e-12. */
static void test_gauss_q_no_underflow_to_1e300(void **state)
{
	struct stray_table t = load("tests/vectors/gauss_tail.csv");
	size_t i;
	int checked = 0;

	(void)state;
	for (i = 0; i < t.n_rows; i++) {
		double z = t.cell[3 * i], q = t.cell[3 * i + 2];

		if (q < 1e-300)
			continue;
		assert_true(stray_gauss_q(z) > 0.0);
		assert_near(stray_gauss_q(z) / q, 1.0, 1e-12);
		checked++;
	}
	assert_true(checked >= 20);
	stray_table_free(&t);
}

/* The branch switch at z = 26 is continuous: the step over 2e-9 matches
 * d ln Q / dz = -phi/Q = -(z + 1/z - 2/z^3 + ...) (Mills ratio). */
static void test_log_gauss_q_continuous_at_switch(void **state)
{
	const double z = 26.0, h = 1e-9;
	double slope = z + 1.0 / z - 2.0 / (z * z * z);

	(void)state;
	assert_near(stray_log_gauss_q(z - h) - stray_log_gauss_q(z + h),
		    2.0 * h * slope, 1e-12);
}

/* Q^-1 inverts Q: Q^-1(0.05) = 1.6448536269514722 (tabulated quantile). */
static void test_gauss_q_inv_known_quantiles(void **state)
{
	struct stray_error err;
	double z;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_gauss_q_inv(0.05, &z, &err), STRAY_OK);
	assert_near(z, 1.6448536269514722, 1e-12);
	assert_int_equal(stray_gauss_q_inv(0.95, &z, &err), STRAY_OK);
	assert_near(z, -1.6448536269514722, 1e-12);
	assert_int_equal(stray_gauss_q_inv(1e-300, &z, &err), STRAY_OK);
	assert_near(stray_log_gauss_q(z), log(1e-300), 1e-10);
}

static void test_gauss_q_inv_rejects_bad_probability(void **state)
{
	struct stray_error err;
	double z;
	const double bad[] = { 0.0, 1.0, -0.1, 2.0, NAN };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		stray_error_clear(&err);
		assert_int_equal(stray_gauss_q_inv(bad[i], &z, &err), STRAY_EINVAL);
		assert_string_equal(err.field, "probability");
	}
}

/* Regularized incomplete gamma: ln P and ln Q to 1e-10 relative. */
static void test_log_gamma_matches_mpmath(void **state)
{
	struct stray_table t = load("tests/vectors/gamma_tail.csv");
	struct stray_error err;
	size_t i;

	(void)state;
	for (i = 0; i < t.n_rows; i++) {
		const double *r = t.cell + 4 * i;
		double lp, lq;

		stray_error_clear(&err);
		assert_int_equal(stray_log_gamma_p(r[0], r[1], &lp, &err), STRAY_OK);
		assert_int_equal(stray_log_gamma_q(r[0], r[1], &lq, &err), STRAY_OK);
		if (fabs(lp - r[2]) > 1e-10 * fmax(1.0, fabs(r[2])) + 1e-15)
			fail_msg("P(%g, %g): ln %.15g vs %.15g", r[0], r[1], lp, r[2]);
		if (fabs(lq - r[3]) > 1e-10 * fmax(1.0, fabs(r[3])) + 1e-15)
			fail_msg("Q(%g, %g): ln %.15g vs %.15g", r[0], r[1], lq, r[3]);
	}
	stray_table_free(&t);
}

/* For integer k, P(k, mu) = Pr(N >= k), N ~ Poisson(mu): the tail summed
 * term by term upward from k (no cancellation). */
static void test_gamma_p_is_poisson_tail(void **state)
{
	const double mu = 7.5;
	struct stray_error err;
	int k, j;

	(void)state;
	stray_error_clear(&err);
	for (k = 1; k < 60; k++) {
		double pmf = exp(-mu), tail = 0.0, lp;

		for (j = 1; j <= k; j++)
			pmf *= mu / j;
		for (j = k; j < k + 400; j++) {
			tail += pmf;
			pmf *= mu / (j + 1);
		}
		assert_int_equal(stray_log_gamma_p(k, mu, &lp, &err), STRAY_OK);
		assert_rel(exp(lp), tail, 1e-12);
	}
}

static void test_log_add(void **state)
{
	(void)state;
	assert_near(stray_log_add(log(2.0), log(3.0)), log(5.0), 1e-15);
	assert_near(stray_log_add(-INFINITY, 1.5), 1.5, 0.0);
	assert_near(stray_log_add(-1000.0, -1000.0),
			    -1000.0 + log(2.0), 1e-12);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_log_gauss_q_matches_mpmath),
		cmocka_unit_test(test_gauss_q_no_underflow_to_1e300),
		cmocka_unit_test(test_log_gauss_q_continuous_at_switch),
		cmocka_unit_test(test_gauss_q_inv_known_quantiles),
		cmocka_unit_test(test_gauss_q_inv_rejects_bad_probability),
		cmocka_unit_test(test_log_gamma_matches_mpmath),
		cmocka_unit_test(test_gamma_p_is_poisson_tail),
		cmocka_unit_test(test_log_add),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
