/*
 * test_starcat.c - the real catalogue readers and the colour term (issue
 * 24, stray/starcat.h, stray/colour.h): each format read to its numbers
 * (the fuzz seeds: three verbatim lines of the shipped I/311 extract,
 * I/239 records of Barnard's star and HIP 2, BSC5 records of Vega and
 * Sirius in the V/50 byte columns, a CSV), proper motion to an epoch
 * (Barnard's star), broken lines named by line and field, the colour
 * factor 1 at B-V = 0 and the blackbody's for a red star.  Run from the
 * repository's root.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/colour.h"
#include "stray/errfmt.h"
#include "stray/starcat.h"

#define PI 3.14159265358979323846
#define SEEDS "tests/fuzz/seeds/starcat/"

static int parse(const char *text, struct stray_starcat *c, char *msg,
		 size_t n)
{
	struct stray_error err = { 0 };
	int rc = stray_starcat_parse(text, strlen(text), "t.cat", c, &err);

	if (rc != STRAY_OK)
		stray_error_format(&err, msg, n);
	return rc;
}

static void load(const char *path, struct stray_starcat *c)
{
	struct stray_error err = { 0 };
	char msg[256];

	if (stray_starcat_load(path, c, &err) != STRAY_OK)
		fail_msg("%s", stray_error_format(&err, msg, sizeof(msg)));
}

static void test_formats(void **state)
{
	struct stray_starcat c;
	char msg[256];

	(void)state;
	load(SEEDS "hip2.dat", &c);
	assert_int_equal(c.kind, STRAY_STARCAT_HIP2);
	assert_int_equal((int)c.n, 3);
	assert_true(c.s[0].epoch_jyear == 1991.25);
	assert_true(fabs(c.s[0].v_mag - stray_hp_to_v(6.2609, c.s[0].b_v)) < 0.2);
	stray_starcat_free(&c);

	load(SEEDS "hip_main.dat", &c);
	assert_int_equal(c.kind, STRAY_STARCAT_HIP1);
	assert_int_equal((int)c.n, 2);
	assert_int_equal(c.s[0].id, 87937);
	assert_true(fabs(c.s[0].v_mag - 9.54) < 1e-9);
	assert_true(fabs(c.s[0].b_v - 1.57) < 1e-9);
	assert_true(fabs(c.s[0].pmdec_mas_yr - 10326.93) < 1e-9);
	stray_starcat_free(&c);

	load(SEEDS "bsc5.dat", &c);
	assert_int_equal(c.kind, STRAY_STARCAT_BSC5);
	assert_int_equal((int)c.n, 2);
	/* Vega: 18h36m56.3s +38d47'01" */
	assert_true(fabs(c.s[0].ra_deg - 279.234583) < 1e-5);
	assert_true(fabs(c.s[0].dec_deg - 38.783611) < 1e-5);
	assert_true(fabs(c.s[1].dec_deg + 16.716111) < 1e-5);	/* Sirius */
	assert_true(fabs(c.s[1].pmdec_mas_yr + 1205.0) < 1e-6);
	assert_true(c.s[1].epoch_jyear == 2000.0);
	stray_starcat_free(&c);

	assert_int_equal(parse("# comment\nv_mag,dec_deg,ra_deg,b_v,hp_mag\n"
			       ",20,10,0.5,6.1\n5,-3,350,1.5,\n", &c, msg,
			       sizeof(msg)), STRAY_OK);
	assert_int_equal(c.kind, STRAY_STARCAT_CSV);
	assert_true(fabs(c.s[0].v_mag - stray_hp_to_v(6.1, 0.5)) < 1e-12);
	assert_true(c.s[1].ra_deg == 350.0 && c.s[1].epoch_jyear == 2000.0);
	stray_starcat_free(&c);
}

/* Barnard's star: 10.33"/yr north; 1991.25 -> 2026.25 is 361.4". */
static void test_proper_motion(void **state)
{
	struct stray_starcat c;
	struct stray_cat_star out[4];
	double dir[3], ra = 269.45402 * PI / 180.0, de = 4.66828 * PI / 180.0;
	size_t n;

	(void)state;
	load(SEEDS "hip_main.dat", &c);
	dir[0] = cos(de) * cos(ra);
	dir[1] = cos(de) * sin(ra);
	dir[2] = sin(de);
	assert_int_equal((int)stray_starcat_cone(&c, 2026.25, dir, 1.0, 12.0,
						 out, 4, &n), 1);
	assert_true(fabs((out[0].dec_deg - 4.66828) * 3600.0 -
			 10.32693 * 35.0) < 0.05);
	assert_true(fabs((out[0].ra_deg - 269.45402) * 3600.0 * cos(de) +
			 0.79784 * 35.0) < 0.05);
	assert_true(fabs(out[0].b_v - 1.57) < 1e-12 && out[0].colour == 1.0);
	/* the magnitude limit */
	assert_int_equal((int)stray_starcat_cone(&c, 2026.25, dir, 1.0, 9.0,
						 out, 4, &n), 0);
	stray_starcat_free(&c);
}

static void test_errors(void **state)
{
	struct stray_starcat c;
	struct stray_error err = { 0 };
	char msg[256], *text, *nl;
	size_t len;

	(void)state;
	/* a broken Hp on line 2 of hip2.dat */
	load(SEEDS "hip2.dat", &c);
	stray_starcat_free(&c);
	{
		FILE *f = fopen(SEEDS "hip2.dat", "rb");

		assert_non_null(f);
		text = calloc(1, 4096);
		len = fread(text, 1, 4095, f);
		fclose(f);
	}
	nl = strchr(text, '\n');
	memcpy(nl + 130, "  x.xxx", 7);
	assert_int_equal(stray_starcat_parse(text, len, "t.cat", &c, &err),
			 STRAY_EPARSE);
	stray_error_format(&err, msg, sizeof(msg));
	free(text);
	assert_non_null(strstr(msg, "t.cat:2:"));
	assert_non_null(strstr(msg, "Hpmag"));
	assert_int_equal(parse("ra_deg,dec_deg,v_mag\n1,2,3\n", &c, msg,
			       sizeof(msg)), STRAY_EPARSE);
	assert_non_null(strstr(msg, "b_v"));
	assert_int_equal(parse("ra_deg,dec_deg,v_mag,b_v\n1,95,3,0\n", &c, msg,
			       sizeof(msg)), STRAY_EPARSE);
	assert_non_null(strstr(msg, "t.cat:2: dec"));
	assert_int_equal(parse("ra_deg,dec_deg,v_mag,b_v,hip\n1,5,3,0,1e26\n",
			       &c, msg, sizeof(msg)), STRAY_EPARSE);
	assert_non_null(strstr(msg, "id"));
	assert_int_equal(parse("hello\n", &c, msg, sizeof(msg)), STRAY_EPARSE);
	assert_int_equal(parse("ra_deg,dec_deg,v_mag,b_v\n", &c, msg,
			       sizeof(msg)), STRAY_EINVAL);
	assert_non_null(strstr(msg, "no usable star"));
}

static void test_colour(void **state)
{
	struct stray_colour col;
	struct stray_error err = { 0 };

	(void)state;
	assert_int_equal(stray_colour_for_qe(&col, "builtin:qe_mt9p031_approx",
					     &err), STRAY_OK);
	assert_true(fabs(stray_colour_factor(&col, 0.0) - 1.0) < 1e-12);
	/* the figure: a B-V = 1.5 star gives ~1.27x the photo-e- */
	assert_true(stray_colour_factor(&col, 1.5) > 1.2 &&
		    stray_colour_factor(&col, 1.5) < 1.32);
	assert_true(stray_colour_factor(&col, 1.0) > stray_colour_factor(&col, 0.5));
	/* Ballesteros: the Sun (B-V 0.65) near 5800 K */
	assert_true(fabs(stray_bv_temperature(0.65) - 5800.0) < 150.0);
	assert_true(isfinite(stray_colour_factor(&col, NAN)));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_formats),
		cmocka_unit_test(test_proper_motion),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_colour),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
