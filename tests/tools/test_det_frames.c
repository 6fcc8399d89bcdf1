/*
 * test_det_frames.c - `stray frames` on frames the models cannot speak
 * for (issue 28): stray light that fills the 12-bit ADC.  White frames
 * have no noise tail and no room for stars, so "0 false stars measured"
 * is no agreement with any model: every pixel clipping is refused (one
 * line, exit 2), some pixels clipping give no verdict.
 *
 * STRAY_BIN=/path/to/old/stray runs the same probes against another build
 * (the old one said "model and frames agree" on white frames).
 */
#include <cJSON.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "run_cli.h"

static struct cli_run r;

#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })

/* A float FITS map (BITPIX -32, big-endian) of nx x ny cells, a ramp
 * along columns from lo to hi (as test_frames_cli.c writes one). */
static void write_ramp(const char *path, int nx, int ny, double lo, double hi)
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

/* alpha 1e-3: 2.4e6 stray e-/px against a 7990 e- full scale.  The old
 * build rendered white frames, measured 0 false stars for the threshold
 * detector and called that agreement with its model's 7 (exit 0). */
static void test_white_frames_refused(void **state)
{
	(void)state;
	assert_int_equal(STRAY("frames", "--alpha", "1e-3", "--window", "64",
			       "--frames", "2"), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "alpha 0.001"));
	assert_non_null(strstr(r.err, "full scale"));
	assert_null(strstr(r.out, "agree"));
	/* --json: the refusal alone, nothing on stdout */
	assert_int_equal(STRAY("frames", "--alpha", "3e-5", "--window", "64",
			       "--json"), 2);
	assert_int_equal(r.err_lines, 1);
	assert_string_equal(r.out, "");
}

/* Just below the clipping level the run goes on as before. */
static void test_bright_not_clipped(void **state)
{
	cJSON *o;

	(void)state;
	assert_int_equal(STRAY("frames", "--alpha", "2e-6", "--window", "64",
			       "--json"), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	assert_true(cJSON_IsNumber(cJSON_GetObjectItem(o, "clipped_fraction")));
	assert_true(cJSON_GetObjectItem(o, "clipped_fraction")->valuedouble == 0);
	cJSON_Delete(o);
}

/* A ramp map 0.1-1.9 at a mean of ~7000 e-/px: the bright columns clip,
 * the dim ones do not.  No verdict, with the clipped fraction.  A 512 px
 * window at the centre sees the ramp from ~0.75 to ~1.25 of its mean
 * (clipped fraction 0.33, the full 2592 x 1944 frame 0.47): partly
 * clipped as well, in 1 CPU second instead of 34 (92 under ASan). */
static void test_partly_clipped_no_verdict(void **state)
{
	char path[] = "/tmp/stray_ramp_XXXXXX";
	const cJSON *d;
	cJSON *o;
	double f;
	int fd = mkstemp(path);

	(void)state;
	assert_true(fd >= 0);
	close(fd);
	write_ramp(path, 72, 54, 0.1, 1.9);
	assert_int_equal(STRAY("frames", "--alpha", "3e-6", "--map", path,
			       "--window", "512", "--json"), 0);
	unlink(path);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	assert_true(cJSON_IsNumber(cJSON_GetObjectItem(o, "clipped_fraction")));
	f = cJSON_GetObjectItem(o, "clipped_fraction")->valuedouble;
	assert_true(f > 0.05 && f < 0.6);
	d = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "detectors"), "threshold");
	assert_non_null(d);
	assert_non_null(strstr(cJSON_GetObjectItem(d, "verdict")->valuestring,
			       "no verdict"));
	assert_null(strstr(cJSON_GetObjectItem(d, "verdict")->valuestring,
			   "agree"));
	cJSON_Delete(o);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_white_frames_refused),
		cmocka_unit_test(test_bright_not_clipped),
		cmocka_unit_test(test_partly_clipped_no_verdict),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
