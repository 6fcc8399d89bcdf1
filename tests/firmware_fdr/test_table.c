/*
 * test_table.c - the flight table: CRC, blob round trip, corruption and
 * range checks, and the curve lookup against libstray's (thesis §5.1).
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fdrfw/table.h"
#include "fixture.h"
#include "stray/curve.h"

/* The CRC-32 check value of "123456789" (Rocksoft catalogue). */
static void test_crc32_check_value(void **state)
{
	const uint8_t msg[] = "123456789";

	(void)state;
	assert_int_equal(fdrfw_crc32(0, msg, 9), 0xCBF43926u);
	/* Feeding in two pieces continues the same CRC. */
	assert_int_equal(fdrfw_crc32(fdrfw_crc32(0, msg, 4), msg + 4, 5),
			 0xCBF43926u);
}

static void test_table_built_is_valid(void **state)
{
	struct fdrfw_table t;

	(void)state;
	fixture_table(&t);
	assert_int_equal(fdrfw_table_check(&t), FDRFW_OK);
	assert_int_equal(t.n_curve, fixture_curve()->n);
}

static void test_blob_round_trip(void **state)
{
	static uint8_t blob[FDRFW_BLOB_SIZE];
	struct fdrfw_table t, u;

	(void)state;
	fixture_table(&t);
	fdrfw_table_serialize(&t, blob);
	/* The first word is the magic, little-endian. */
	assert_int_equal(blob[0], 0x46);
	assert_int_equal(blob[3], 0x52);
	memset(&u, 0xA5, sizeof(u));
	assert_int_equal(fdrfw_table_parse(blob, sizeof(blob), &u), FDRFW_OK);
	assert_memory_equal(&t, &u, sizeof(t));
	assert_int_equal(fdrfw_table_check(&u), FDRFW_OK);
}

/* Every single-bit flip anywhere in the blob is caught (CRC-32 detects
 * all 1-bit errors): by the CRC, or by the magic/version check first. */
static void test_every_bit_flip_rejected(void **state)
{
	static uint8_t blob[FDRFW_BLOB_SIZE];
	struct fdrfw_table t, u;
	size_t i;
	unsigned b;

	(void)state;
	fixture_table(&t);
	fdrfw_table_serialize(&t, blob);
	for (i = 0; i < sizeof(blob); i++) {
		for (b = 0; b < 8; b++) {
			int rc;

			blob[i] ^= (uint8_t)(1u << b);
			/* a flipped version word is refused by the parser
			 * already (issue 28: another version, another size) */
			rc = fdrfw_table_parse(blob, sizeof(blob), &u);
			if (rc == FDRFW_OK)
				rc = fdrfw_table_check(&u);
			if (i >= 8)
				assert_int_equal(rc, FDRFW_ECRC);
			else
				assert_int_equal(rc, FDRFW_EMAGIC);
			blob[i] ^= (uint8_t)(1u << b);
		}
	}
}

static void test_blob_wrong_size_rejected(void **state)
{
	static uint8_t blob[FDRFW_BLOB_SIZE + 1];
	struct fdrfw_table u;

	(void)state;
	assert_int_equal(fdrfw_table_parse(blob, FDRFW_BLOB_SIZE - 1, &u),
			 FDRFW_ESIZE);
	assert_int_equal(fdrfw_table_parse(blob, FDRFW_BLOB_SIZE + 1, &u),
			 FDRFW_ESIZE);
	assert_int_equal(fdrfw_table_parse(blob, 0, &u), FDRFW_ESIZE);
}

/* A resealed table with a value out of its domain fails the range check
 * with that field's code: a valid CRC does not make a bad table good
 * (every field: test_table_valid.c). */
static void test_out_of_range_rejected(void **state)
{
	struct fdrfw_table t;

	(void)state;
	fixture_table(&t);
	t.n_pps = NAN;
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t),
			 FDRFW_EFIELD_OF(n_pps));

	fixture_table(&t);
	t.theta_deg[5] = t.theta_deg[4];	/* not increasing */
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t),
			 FDRFW_EFIELD_OF(theta_deg));

	fixture_table(&t);
	t.log10_alpha_tail[3] -= 1.0f;		/* envelope inconsistent */
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t),
			 FDRFW_EFIELD_OF(log10_alpha_tail));

	fixture_table(&t);
	t.n_curve = FDRFW_CURVE_MAX + 1;
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t),
			 FDRFW_EFIELD_OF(n_curve));

	/* eq. 2.3's k_px: the thesis's 1 or A_cs / (n_tot A_px), nothing
	 * else (st16-like: 132.7 mm^2 / 24.39 mm^2 = 5.44). */
	fixture_table(&t);
	assert_near((double)t.k_px, 3.14159265358979 * 6.5 * 6.5 /
		    (2592.0 * 1944.0 * 2.2e-3 * 2.2e-3), 1e-5);
	assert_false(fdrfw_table_is_thesis(&t));
	t.k_px = 1.0f;
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t), FDRFW_OK);
	assert_true(fdrfw_table_is_thesis(&t));
	t.k_px = 2.0f;
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t),
			 FDRFW_EFIELD_OF(k_px));
	fixture_table(&t);
	t.k_px *= 1.001f;
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t),
			 FDRFW_EFIELD_OF(k_px));

	fixture_table(&t);
	t.version = FDRFW_TABLE_VERSION + 1;
	fdrfw_table_seal(&t);
	assert_int_equal(fdrfw_table_check(&t), FDRFW_EMAGIC);
}

/* The float lookup reproduces libstray's log-linear interpolation
 * (stray_curve_alpha_at) to single precision. */
static void test_alpha_matches_libstray(void **state)
{
	const struct stray_curve_view *c = fixture_curve();
	struct fdrfw_table t;
	double th;

	(void)state;
	fixture_table(&t);
	for (th = -2.0; th <= 90.0; th += 0.137) {
		double ref = stray_curve_alpha_at(c, th);
		double got = (double)fdrfw_alpha_at(&t, (float)th);

		assert_near(got, ref, 2e-5 * ref);
	}
}

/* fig. 5.1: envelope >= alpha_req exactly before the exclusion angle. */
static void test_envelope_gives_exclusion_angle(void **state)
{
	const struct stray_curve_view *c = fixture_curve();
	struct fdrfw_table t;
	double req, th, x;
	struct stray_error err;

	(void)state;
	fixture_table(&t);
	for (req = 1e-9; req < 0.5; req *= 1.7) {
		stray_error_clear(&err);
		if (stray_exclusion_angle(c, req, &x, &err) != 0)
			continue;
		for (th = 0.0; th < 85.0; th += 0.05) {
			double env = (double)fdrfw_envelope_at(&t, (float)th);

			if (fabs(th - x) < 1e-3)
				continue;	/* float rounding at the edge */
			assert_int_equal(env >= req, th < x);
		}
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_crc32_check_value),
		cmocka_unit_test(test_table_built_is_valid),
		cmocka_unit_test(test_blob_round_trip),
		cmocka_unit_test(test_every_bit_flip_rejected),
		cmocka_unit_test(test_blob_wrong_size_rejected),
		cmocka_unit_test(test_out_of_range_rejected),
		cmocka_unit_test(test_alpha_matches_libstray),
		cmocka_unit_test(test_envelope_gives_exclusion_angle),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
