/*
 * test_frames_cli.c - `stray frames` as a user runs it: the JSON keys of
 * issue 13, the thesis normalisation (k_px = 1) against the consistent
 * one, the sweep folder of --out-dir (read back through the store), all
 * or nothing on failure and SIGINT, and bad input (one stderr line naming the value,
 * exit 2).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cJSON.h>
#include <cmocka.h>
#include <dirent.h>
#include <fitsio.h>
#include <math.h>
#include <signal.h>
#include <time.h>

#include "stray/sweep_store.h"
#include "tools/run_cli.h"

#define STRAY(r, ...) run_stray(r, (char *[]){ "stray", __VA_ARGS__, NULL })

static struct cli_run r;
static void expect_bad(const char *needle);

static double key(const cJSON *o, const char *k)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);

	if (!cJSON_IsNumber(v))
		fail_msg("JSON key '%s' missing or not a number", k);
	return v->valuedouble;
}

static void test_frames_json_keys(void **state)
{
	static const char *const keys[] = { "theta_deg", "frames",
		"false_stars_per_image", "false_stars_sigma", "model_fdr",
		"model_fdr_extended", "k_px" };
	cJSON *o;
	size_t i;

	(void)state;
	assert_int_equal(STRAY(&r, "frames", "--alpha", "3e-7", "--window",
			       "128", "--frames", "2", "--json"), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	for (i = 1; i < sizeof(keys) / sizeof(keys[0]); i++)
		(void)key(o, keys[i]);
	assert_string_equal(cJSON_GetObjectItem(o, "normalisation")->valuestring,
			    "consistent");
	assert_string_equal(cJSON_GetObjectItem(o, "detector")->valuestring,
			    "thesis");
	/* k_px = A_cs / (n_px A_px) = 132.7 mm^2 / 24.4 mm^2 (issue 13) */
	assert_true(fabs(key(o, "k_px") - 5.44) < 0.01);
	assert_true(key(o, "model_fdr_extended") > key(o, "model_fdr"));
	{	/* the real detector needs less light than eq. 2.18 says,
		 * which needs less than the thesis's k_px = 1 */
		const cJSON *a = cJSON_GetObjectItem(o, "alpha_required");

		assert_non_null(a);
		assert_true(key(a, "extended") < key(a, "model"));
		assert_true(key(a, "model") < key(a, "thesis_k1"));
		assert_true(fabs(key(a, "thesis_k1") / 1.92e-6 - 1) < 0.01);
	}
	cJSON_Delete(o);
}

/* alpha from the curve at theta (log-linear, as `stray exclusion`). */
static void test_frames_curve_theta(void **state)
{
	cJSON *o;

	(void)state;
	/* the system curve: the baffle alone (examples/ref4_baffle_mitsuba.csv,
	 * 2.3e-5 at 40 deg) fills the ADC and is refused (test_det_frames.c) */
	assert_int_equal(STRAY(&r, "frames", "--curve",
			       "tests/vectors/fdrfw_curve.csv", "--theta", "40",
			       "--window", "64", "--json"), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	assert_true(key(o, "theta_deg") == 40.0);
	assert_true(key(o, "alpha") > 0.0 && key(o, "alpha") < 1.0);
	cJSON_Delete(o);
}

/* The same pixel level under both normalisations: alpha x k_px. */
static void test_frames_normalisations_agree(void **state)
{
	cJSON *a, *b;

	(void)state;
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
			       "--json"), 0);
	a = cJSON_Parse(r.out);
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
			       "--normalisation", "thesis", "--json"), 0);
	b = cJSON_Parse(r.out);
	assert_non_null(a);
	assert_non_null(b);
	assert_true(key(b, "k_px") == 1.0);
	assert_true(fabs(key(a, "stray_e_per_px") /
			 key(b, "stray_e_per_px") - key(a, "k_px")) < 1e-9);
	cJSON_Delete(a);
	cJSON_Delete(b);
}

/* Remove a flat folder (a sweep folder holds only files). */
static void remove_dir(const char *dir)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	char path[1024];

	while (d && (e = readdir(d)) != NULL)
		if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
			snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
			unlink(path);
		}
	if (d)
		closedir(d);
	rmdir(dir);
}

static void sleep_ms(long ms)
{
	struct timespec t = { ms / 1000, (ms % 1000) * 1000000L };

	nanosleep(&t, NULL);
}

/* Entries of a folder other than . and .. */
static int dir_entries(const char *dir)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	int n = 0;

	while (d && (e = readdir(d)) != NULL)
		n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
	if (d)
		closedir(d);
	return n;
}

/* --out-dir is a sweep folder: the store's reader loads the manifest,
 * checks the hash and reads the keywords back, the renderer's too. */
static void test_frames_writes_fits(void **state)
{
	char dir[] = "/tmp/stray_frames_XXXXXX", path[600], text[FLEN_VALUE];
	struct stray_sweep_manifest m;
	struct stray_sweep_fits f;
	struct stray_error err;
	double alpha = 0.0;
	long nstars = -1;
	int st = 0;

	(void)state;
	stray_error_clear(&err);
	assert_non_null(mkdtemp(dir));	/* an empty folder may be given */
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
			       "--theta", "12", "--frames", "2", "--save", "1",
			       "--out-dir", dir), 0);
	assert_int_equal(stray_sweep_manifest_load(dir, &m, &err), STRAY_OK);
	assert_int_equal(m.n, 1);			/* --save 1 */
	assert_int_equal(m.e[0].type, STRAY_SWEEP_FULL);
	assert_true(m.e[0].angle_deg == 12.0);
	assert_int_equal(m.e[0].seqnum, 0);
	snprintf(path, sizeof(path), "%s/%s", dir, m.e[0].file);
	assert_int_equal(stray_sweep_sha256_check(path, m.e[0].sha256, &err),
			 STRAY_OK);
	assert_int_equal(stray_sweep_fits_open(path, &f, &err), STRAY_OK);
	assert_int_equal(f.h.n_cols, 64);
	assert_int_equal(f.h.n_rows, 64);
	assert_int_equal(f.h.type, STRAY_SWEEP_FULL);
	assert_true(f.h.angle_deg == 12.0 && f.h.ndtrans == 1.0);
	fits_read_key(f.fptr, TDOUBLE, "ALPHA", &alpha, NULL, &st);
	fits_read_key(f.fptr, TLONG, "NSTARS", &nstars, NULL, &st);
	fits_read_key(f.fptr, TSTRING, "INSTRUME", text, NULL, &st);
	assert_int_equal(st, 0);
	assert_true(fabs(alpha - 1e-6) < 1e-15);
	assert_true(nstars >= 0);
	assert_string_equal(text, "stray frames");
	fits_read_key(f.fptr, TSTRING, "NORM", text, NULL, &st);
	assert_int_equal(st, 0);
	assert_string_equal(text, "consistent");
	stray_sweep_fits_close(&f);
	stray_sweep_manifest_free(&m);
	/* a folder that holds something is never written into */
	STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
	      "--out-dir", dir);
	expect_bad("not empty");
	remove_dir(dir);
}

/* All or nothing: a run that fails after frames were rendered and saved
 * (here the PNG of frame 0 cannot be written) leaves no folder and no
 * temporary. */
static void test_frames_failed_run_leaves_nothing(void **state)
{
	char base[] = "/tmp/stray_frames_XXXXXX", dir[256];

	(void)state;
	assert_non_null(mkdtemp(base));
	snprintf(dir, sizeof(dir), "%s/out", base);
	STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64", "--frames",
	      "3", "--save", "3", "--out-dir", dir, "--png",
	      "/nonexistent/frame.png");
	assert_int_not_equal(r.status, 0);
	assert_int_equal(dir_entries(base), 0);
	/* the same run with a good PNG leaves both */
	snprintf(dir, sizeof(dir), "%s/png.png", base);
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window",
			       "64", "--png", dir), 0);
	assert_int_equal(dir_entries(base), 1);
	unlink(dir);
	rmdir(base);
}

/* SIGINT while frames are being saved: no folder, no temporary. */
static void test_frames_sigint_leaves_nothing(void **state)
{
	char base[] = "/tmp/stray_frames_XXXXXX", dir[256];
	const char *bin = getenv("STRAY_BIN") ? getenv("STRAY_BIN")
					      : "build/bin/stray";
	pid_t pid;
	int i, status = 0;

	(void)state;
	assert_non_null(mkdtemp(base));
	snprintf(dir, sizeof(dir), "%s/out", base);
	pid = fork();
	assert_true(pid >= 0);
	if (pid == 0) {
		int fd = open("/dev/null", O_WRONLY);

		dup2(fd, 1);
		dup2(fd, 2);
		/* as from a terminal: started under a non-interactive shell's
		 * `&` the test inherits SIGINT ignored, stray rightly leaves
		 * an ignored signal alone, and the kill below did nothing */
		signal(SIGINT, SIG_DFL);
		execl(bin, "stray", "frames", "--alpha", "1e-6", "--window",
		      "512", "--frames", "1000", "--save", "1000", "--out-dir",
		      dir, (char *)NULL);
		_exit(127);
	}
	for (i = 0; i < 3000 && dir_entries(base) == 0; i++)
		sleep_ms(10);		/* until the temporary folder exists */
	assert_int_equal(dir_entries(base), 1);
	sleep_ms(200);			/* some frames in it */
	kill(pid, SIGINT);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
	assert_int_equal(dir_entries(base), 0);
	rmdir(base);
}

/* A float FITS map (BITPIX -32, big-endian), nx x ny cells: a ramp along
 * columns from lo to hi, or a NaN in the first cell. */
static void write_map(const char *path, int nx, int ny, double lo, double hi,
		      int with_nan)
{
	char card[81], hdr[2880];
	unsigned char *data;
	size_t n = (size_t)nx * ny, pad = (n * 4 + 2879) / 2880 * 2880, i;
	const char *fmt[] = { "SIMPLE  =                    T",
			      "BITPIX  =                  -32",
			      "NAXIS   =                    2" };
	FILE *f = fopen(path, "wb");
	int k = 0;

	assert_non_null(f);
	memset(hdr, ' ', sizeof(hdr));
	for (i = 0; i < 3; i++, k++)
		memcpy(hdr + 80 * k, fmt[i], strlen(fmt[i]));
	snprintf(card, sizeof(card), "NAXIS1  = %20d", nx);
	memcpy(hdr + 80 * k++, card, strlen(card));
	snprintf(card, sizeof(card), "NAXIS2  = %20d", ny);
	memcpy(hdr + 80 * k++, card, strlen(card));
	memcpy(hdr + 80 * k, "END", 3);
	data = calloc(pad, 1);
	assert_non_null(data);
	for (i = 0; i < n; i++) {
		float v = (float)(lo + (hi - lo) * ((double)(i % nx) + 0.5) / nx);
		uint32_t u;

		if (with_nan && i == 0)
			v = NAN;
		memcpy(&u, &v, 4);
		data[4 * i] = (unsigned char)(u >> 24);
		data[4 * i + 1] = (unsigned char)(u >> 16);
		data[4 * i + 2] = (unsigned char)(u >> 8);
		data[4 * i + 3] = (unsigned char)u;
	}
	assert_int_equal(fwrite(hdr, 1, sizeof(hdr), f), sizeof(hdr));
	assert_int_equal(fwrite(data, 1, pad, f), pad);
	fclose(f);
	free(data);
}

/* A known map: the model sums over its levels; uneven light gives more
 * false stars than the same mean spread evenly (the tail is convex). */
static void test_frames_map(void **state)
{
	char path[] = "/tmp/stray_map_XXXXXX";
	int fd = mkstemp(path);
	cJSON *u, *m;

	(void)state;
	assert_true(fd >= 0);
	close(fd);
	write_map(path, 72, 54, 0.1, 1.9, 0);
	assert_int_equal(STRAY(&r, "frames", "--alpha", "3e-7", "--window",
			       "1024", "--json"), 0);
	u = cJSON_Parse(r.out);
	assert_int_equal(STRAY(&r, "frames", "--alpha", "3e-7", "--window",
			       "1024", "--map", path, "--json"), 0);
	m = cJSON_Parse(r.out);
	assert_non_null(u);
	assert_non_null(m);
	assert_string_equal(cJSON_GetObjectItem(m, "stray_light")->valuestring,
			    path);
	assert_true(key(m, "model_fdr") > 1.2 * key(u, "model_fdr"));
	cJSON_Delete(u);
	cJSON_Delete(m);
	write_map(path, 8, 6, 0.5, 1.5, 1);
	STRAY(&r, "frames", "--alpha", "3e-7", "--window", "64", "--map", path);
	unlink(path);
	expect_bad(path);
}

static void expect_bad(const char *needle)
{
	if (r.status != 2 || r.err_lines != 1 || !strstr(r.err, needle))
		fail_msg("exit %d, %d lines: '%s' (want 2, 1 line with '%s')",
			 r.status, r.err_lines, r.err, needle);
}

static void test_frames_bad_input(void **state)
{
	(void)state;
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv",
	      "--theta", "abc");
	expect_bad("theta");
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv",
	      "--theta", "nan");
	expect_bad("theta");
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv",
	      "--theta", "200");
	expect_bad("200");
	STRAY(&r, "frames", "--curve", "/nonexistent/curve.csv", "--theta", "30");
	expect_bad("/nonexistent/curve.csv");
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv");
	expect_bad("--theta");
	STRAY(&r, "frames", "--alpha", "1e-6", "--detector", "fancy");
	expect_bad("fancy");
	STRAY(&r, "frames", "--alpha", "1e-6", "--map", "/nonexistent/map.fits");
	expect_bad("/nonexistent/map.fits");
	STRAY(&r, "frames", "--alpha", "-1");
	expect_bad("alpha");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_frames_json_keys),
		cmocka_unit_test(test_frames_curve_theta),
		cmocka_unit_test(test_frames_normalisations_agree),
		cmocka_unit_test(test_frames_writes_fits),
		cmocka_unit_test(test_frames_failed_run_leaves_nothing),
		cmocka_unit_test(test_frames_sigint_leaves_nothing),
		cmocka_unit_test(test_frames_map),
		cmocka_unit_test(test_frames_bad_input),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
