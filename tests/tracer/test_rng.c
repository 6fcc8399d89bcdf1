/*
 * test_rng.c - Philox4x32-10 against the known-answer vectors of the
 * Random123 distribution (kat_vectors, Salmon et al. 2011), and the
 * per-path stream properties the integrator relies on.
 */
#include <string.h>

#include "tracer_test.h"
#include "tracer/rng.h"

static void check_kat(const uint32_t ctr[4], const uint32_t key[2],
		      const uint32_t want[4])
{
	uint32_t out[4];

	tracer_philox4x32(ctr, key, out);
	assert_memory_equal(out, want, sizeof(out));
}

static void test_rng_philox_known_answers(void **state)
{
	const uint32_t c0[4] = { 0, 0, 0, 0 }, k0[2] = { 0, 0 };
	const uint32_t w0[4] = { 0x6627e8d5, 0xe169c58d, 0xbc57ac4c,
				 0x9b00dbd8 };
	const uint32_t c1[4] = { 0xffffffff, 0xffffffff, 0xffffffff,
				 0xffffffff };
	const uint32_t k1[2] = { 0xffffffff, 0xffffffff };
	const uint32_t w1[4] = { 0x408f276d, 0x41c83b0e, 0xa20bc7c6,
				 0x6d5451fd };
	const uint32_t c2[4] = { 0x243f6a88, 0x85a308d3, 0x13198a2e,
				 0x03707344 };
	const uint32_t k2[2] = { 0xa4093822, 0x299f31d0 };
	const uint32_t w2[4] = { 0xd16cfe09, 0x94fdcceb, 0x5001e420,
				 0x24126ea1 };

	(void)state;
	check_kat(c0, k0, w0);
	check_kat(c1, k1, w1);
	check_kat(c2, k2, w2);
}

/* A path's stream depends only on (seed, path): replayable anywhere. */
static void test_rng_streams_replay_and_differ(void **state)
{
	struct tracer_rng a, b, c;
	int i, same = 0;

	(void)state;
	tracer_rng_init(&a, 7, 123456789012ull);
	tracer_rng_init(&b, 7, 123456789012ull);
	tracer_rng_init(&c, 7, 123456789013ull);
	for (i = 0; i < 1000; i++) {
		double x = tracer_rng_uniform(&a);

		assert_true(x == tracer_rng_uniform(&b));
		assert_true(x >= 0.0 && x < 1.0);
		same += x == tracer_rng_uniform(&c);
	}
	assert_true(same < 3);
}

/* Mean and variance of U(0,1): 1/2 and 1/12, within 5 sigma. */
static void test_rng_uniform_moments(void **state)
{
	struct tracer_rng r;
	const int n = 200000;
	double m = 0, m2 = 0;
	int i;

	(void)state;
	tracer_rng_init(&r, 1, 0);
	for (i = 0; i < n; i++) {
		double x = tracer_rng_uniform(&r);

		m += x;
		m2 += x * x;
	}
	m /= n;
	m2 /= n;
	assert_near(m, 0.5, 5.0 * sqrt(1.0 / 12.0 / n));
	assert_near(m2 - m * m, 1.0 / 12.0, 5.0 * sqrt(1.0 / 180.0 / n));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_rng_philox_known_answers),
		cmocka_unit_test(test_rng_streams_replay_and_differ),
		cmocka_unit_test(test_rng_uniform_moments),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
