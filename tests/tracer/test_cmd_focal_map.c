/*
 * test_cmd_focal_map.c - `stray trace --focal-map` as a user runs it: the
 * FITS map and its keywords (tracer/README.md), mean = KPX * ALPHA,
 * SPREAD uniform or lensmap, the PNG, the --json block, the curve's bytes
 * unchanged by the map, and one-line errors with exit 2.
 */
#include <cJSON.h>
#include <fitsio.h>

#include "frames/focal_map_io.h"
#include "tracer_cli.h"

static void read_map(const char *path, long *nx, long *ny, double *mean,
		     double *key_mean, double *k_px, double *alpha,
		     char *spread)
{
	fitsfile *f = NULL;
	long naxes[2] = { 0, 0 }, i;
	float *img;
	int st = 0, nax = 0;

	assert_int_equal(fits_open_file(&f, path, READONLY, &st), 0);
	fits_get_img_dim(f, &nax, &st);
	fits_get_img_size(f, 2, naxes, &st);
	assert_int_equal(nax, 2);
	fits_read_key(f, TDOUBLE, "MEAN", key_mean, NULL, &st);
	fits_read_key(f, TDOUBLE, "KPX", k_px, NULL, &st);
	fits_read_key(f, TDOUBLE, "ALPHA", alpha, NULL, &st);
	fits_read_key(f, TSTRING, "SPREAD", spread, NULL, &st);
	img = malloc((size_t)(naxes[0] * naxes[1]) * sizeof(float));
	assert_non_null(img);
	fits_read_img(f, TFLOAT, 1, naxes[0] * naxes[1], NULL, img, NULL,
		      &st);
	fits_close_file(f, &st);
	assert_int_equal(st, 0);
	for (*mean = 0.0, i = 0; i < naxes[0] * naxes[1]; i++)
		*mean += img[i];
	*mean /= (double)(naxes[0] * naxes[1]);
	*nx = naxes[0];
	*ny = naxes[1];
	free(img);
}

static void test_cmd_focal_map_fits_and_json(void **state)
{
	char fits[] = "/tmp/focal_fXXXXXX", png[] = "/tmp/focal_pXXXXXX.png";
	char lmap[] = "/tmp/focal_lXXXXXX";
	char *a1[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--rays", "20000", "--set", "segments=64",
		       "--focal-map", fits, "--focal-map-png", png,
		       "--map-angle", "40", "--json", NULL };
	char *a2[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--rays", "20000", "--set", "segments=64",
		       "--focal-map", fits, "--map-angle", "40", "--map-cell",
		       "72", "--lens-map", lmap, NULL };
	char spread[FLEN_VALUE];
	double mean, kmean, k_px, alpha;
	struct cli_run r;
	cJSON *j, *m;
	long nx, ny;
	int fd;

	(void)state;
	close(mkstemp(fits));
	close(mkstemps(png, 4));
	assert_int_equal(run_stray(&r, a1), 0);
	read_map(fits, &nx, &ny, &mean, &kmean, &k_px, &alpha, spread);
	assert_int_equal(nx, 72);	/* 2592 / 36 */
	assert_int_equal(ny, 54);
	assert_near(k_px, M_PI * 6.5 * 6.5 / (2592 * 1944 * 2.2e-3 * 2.2e-3),
		    1e-9);
	assert_true(alpha > 0.0);
	assert_near(mean, k_px * alpha, 1e-5 * mean);	/* float cells */
	assert_near(kmean, k_px * alpha, 1e-9 * kmean);
	assert_string_equal(spread, "uniform");
	{	/* the reader `stray frames --map` uses */
		struct focal_map_file fm;
		double sum = 0.0;
		long px;

		assert_int_equal(focal_map_load(fits, &fm, NULL), 0);
		assert_int_equal(fm.nx, 72);
		assert_int_equal(fm.cell_px, 36);
		assert_near(fm.theta_deg, 40.0, 0.0);
		assert_near(fm.mean, kmean, 0.0);
		assert_string_equal(fm.spread, "uniform");
		/* row of cells 10: the 2 x 2 pixels around each cell's
		 * centre average, bilinearly, to the cell's value */
		for (px = 0; px < fm.npix_x; px += 36) {
			float w[4];

			focal_map_resample(&fm, 2592, 1944, (int)px + 17,
					   10 * 36 + 17, 2, 2, 1.0, w);
			sum += 0.25 * ((double)w[0] + w[1] + w[2] + w[3]);
			assert_near(0.25 * ((double)w[0] + w[1] + w[2] + w[3]),
				    fm.cell[10 * 72 + px / 36],
				    1e-6 * fm.cell[10 * 72 + px / 36] + 1e-30);
		}
		assert_near(sum / 72.0, k_px * alpha, 1e-5 * k_px * alpha);
		assert_near(fm.cell_mean, kmean, 1e-5 * kmean);
		focal_map_file_free(&fm);
		assert_int_not_equal(focal_map_load(png, &fm, NULL), 0);
	}
	j = cJSON_Parse(r.out);
	m = cJSON_GetObjectItem(j, "focal_map");
	assert_non_null(m);
	assert_string_equal(cJSON_GetObjectItem(m, "spread")->valuestring,
			    "uniform");
	assert_near(cJSON_GetObjectItem(m, "k_px")->valuedouble, k_px, 1e-9);
	cJSON_Delete(j);
	{
		FILE *f = fopen(png, "rb");
		char sig[4];

		assert_non_null(f);
		assert_int_equal(fread(sig, 1, 4, f), 4);
		fclose(f);
		assert_memory_equal(sig, "\x89PNG", 4);
	}
	fd = mkstemp(lmap);
	assert_true(write(fd, "fraction,rel_alpha\n0.5,0.5\n0.5,1.5\n", 35) ==
		    35);
	close(fd);
	assert_int_equal(run_stray(&r, a2), 0);
	read_map(fits, &nx, &ny, &mean, &kmean, &k_px, &alpha, spread);
	assert_int_equal(nx, 36);
	assert_string_equal(spread, "lensmap");
	assert_near(mean, k_px * alpha, 1e-5 * mean);
	unlink(fits);
	unlink(png);
	unlink(lmap);
}

/* The map is extra work only: the curve's bytes do not change. */
static void test_cmd_focal_map_curve_unchanged(void **state)
{
	char a[] = "/tmp/focal_aXXXXXX", b[] = "/tmp/focal_bXXXXXX";
	char fits[] = "/tmp/focal_gXXXXXX";
	char *a1[] = { "stray", "trace", "--scene", "ref4", "--angles",
		       "0,5,40", "--rays", "20000", "--set", "segments=64",
		       "--out", a, NULL };
	char *a2[] = { "stray", "trace", "--scene", "ref4", "--angles",
		       "0,5,40", "--rays", "20000", "--set", "segments=64",
		       "--out", b, "--focal-map", fits, "--map-angle", "5",
		       NULL };
	/* every byte but the command line, which differs */
	char *cmp[] = { "diff", "-q", "-I", "^# command: ", a, b, NULL };
	pid_t pid;
	int st;
	struct cli_run r;

	(void)state;
	close(mkstemp(a));
	close(mkstemp(b));
	close(mkstemp(fits));
	assert_int_equal(run_stray(&r, a1), 0);
	assert_int_equal(run_stray(&r, a2), 0);
	pid = fork();
	if (pid == 0) {
		execvp("diff", cmp);
		_exit(127);
	}
	waitpid(pid, &st, 0);
	assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
	unlink(a);
	unlink(b);
	unlink(fits);
}

static void test_cmd_focal_map_bad_input(void **state)
{
	char *a1[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--rays", "2000", "--focal-map", "/tmp/x.fits",
		       "--map-angle", "40", "--map-cell", "50", NULL };
	char *a2[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--rays", "2000", "--focal-map", "/tmp/x.fits",
		       "--map-angle", "30", NULL };
	char *a3[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--rays", "2000", "--focal-map", "/tmp/x.fits",
		       "--map-angle", "40", "--lens-map", "/nonexistent.csv",
		       NULL };
	char *a5[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--focal-map-png", "/tmp/x.jpg", "--map-angle", "40",
		       NULL };
	char *a4[] = { "stray", "trace", "--scene", "ref4", "--angles", "40",
		       "--rays", "2000", "--focal-map", "/tmp/x.fits",
		       "--map-angle", "40", "--sensor", "nosuch", NULL };

	(void)state;
	expect_bad(a1, "--map-cell");
	expect_bad(a2, "--map-angle");
	expect_bad(a3, "nonexistent");
	expect_bad(a4, "nosuch");
	expect_bad(a5, ".png");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cmd_focal_map_fits_and_json),
		cmocka_unit_test(test_cmd_focal_map_curve_unchanged),
		cmocka_unit_test(test_cmd_focal_map_bad_input),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
