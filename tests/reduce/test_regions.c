/*
 * test_regions.c - a J image as the FDR's non-uniform region map: quantile
 * regions with their pixel fraction and level relative to Pbar (eq. 3.13).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "stray/reduce_map.h"
#include "test_util.h"

static void test_regions_quantiles(void **state)
{
	float j[16];
	double scratch[16];
	struct stray_region_map m;
	size_t i;

	(void)state;
	for (i = 0; i < 16; i++)	/* levels 1..4, 4 pixels each, shuffled */
		j[(i * 5) % 16] = (float)(1 + i / 4);
	assert_int_equal(stray_region_map_from_image(j, 16, 4, scratch, &m,
						     NULL), STRAY_OK);
	assert_int_equal(m.n, 4);
	for (i = 0; i < 4; i++) {
		assert_near(m.fraction[i], 0.25, 1e-15);
		assert_near(m.rel_alpha[i], (1.0 + i) / 2.5, 1e-12);
	}
	assert_int_equal(stray_region_map_from_image(j, 16, 65, scratch, &m,
						     NULL), STRAY_EINVAL);
	for (i = 0; i < 16; i++)
		j[i] = 0.0f;
	assert_int_equal(stray_region_map_from_image(j, 16, 2, scratch, &m,
						     NULL), STRAY_EINVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_regions_quantiles),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
