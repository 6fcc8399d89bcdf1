/*
 * test_sweep_errors.c - corrupt sweeps given to `stray reduce`: each gives
 * exit status 2 and one stderr line naming the file and the keyword
 * (truncated FITS, missing keyword, no dark for an exposure time, ROWS
 * that disagree, manifest hash mismatch, a malformed manifest cell).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <fitsio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "synth_sweep.h"
#include "tools/run_cli.h"

struct bad_case {
	char root[64], dir[128], out[128];
	struct synth_config cfg;
	struct synth_truth truth;
	struct cli_run run;
};

static int setup(void **state)
{
	struct bad_case *k = calloc(1, sizeof(*k));

	if (!k)
		return -1;
	strcpy(k->root, "/tmp/stray_bad_XXXXXX");
	if (!mkdtemp(k->root))
		return -1;
	snprintf(k->dir, sizeof(k->dir), "%s/sweep", k->root);
	snprintf(k->out, sizeof(k->out), "%s/c.csv", k->root);
	synth_default(&k->cfg);
	k->cfg.n_angles = 3;
	k->cfg.theta_step_deg = 5.0;	/* three exposure times */
	k->cfg.repeats = 2;
	k->cfg.darks_per_exp = 2;
	k->cfg.ghosts = 0;
	k->cfg.n_hot = k->cfg.n_dead = 0;
	k->cfg.sat_spots = 0;
	k->cfg.sampled = 1;
	k->cfg.n_rows = 6;
	if (synth_write_sweep(k->dir, &k->cfg, &k->truth) != 0)
		return -1;
	*state = k;
	return 0;
}

static int teardown(void **state)
{
	struct bad_case *k = *state;
	char cmd[128];

	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", k->root);
	if (system(cmd) != 0)
		return -1;
	free(k);
	return 0;
}

/* The first entry of a type (FULL frames are what a visit needs). */
static const struct synth_entry *first(const struct bad_case *k,
				       const char *type)
{
	size_t i;

	for (i = 0; i < k->truth.n_entries; i++)
		if (strcmp(k->truth.entry[i].type, type) == 0)
			return &k->truth.entry[i];
	fail_msg("no %s entry", type);
	return NULL;
}

static void path_of(const struct bad_case *k, const struct synth_entry *e,
		    char *p, size_t n)
{
	snprintf(p, n, "%s/%s", k->dir, e->file);
}

/* Exit 2, one line, naming what and where. */
static void expect_bad(struct bad_case *k, const char *file,
		       const char *keyword)
{
	char *argv[] = { "stray", "reduce", k->dir, "--out", k->out, NULL };

	run_stray(&k->run, argv);
	print_message("stderr: %s", k->run.err);
	assert_int_equal(k->run.status, 2);
	assert_int_equal(k->run.err_lines, 1);
	assert_non_null(strstr(k->run.err, file));
	assert_non_null(strstr(k->run.err, keyword));
	assert_int_equal(access(k->out, F_OK), -1);	/* no curve written */
}

static void test_errors_truncated_fits(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = first(k, "FULL");
	char p[256];

	path_of(k, e, p, sizeof(p));
	assert_int_equal(truncate(p, 2880 + 200), 0);	/* header + a bit */
	assert_int_equal(synth_write_manifest(k->dir, &k->truth, NULL, NULL), 0);
	expect_bad(k, e->file, "truncated");
}

static void test_errors_missing_keyword(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = first(k, "AMBIENT");
	fitsfile *f;
	char p[256];
	int status = 0;

	path_of(k, e, p, sizeof(p));
	fits_open_file(&f, p, READWRITE, &status);
	fits_delete_key(f, "EXPTIME", &status);
	fits_close_file(f, &status);
	assert_int_equal(status, 0);
	assert_int_equal(synth_write_manifest(k->dir, &k->truth, NULL, NULL), 0);
	expect_bad(k, e->file, "EXPTIME");
}

static int skip_darks_at(const struct synth_entry *e, void *ctx)
{
	return strcmp(e->type, "DARK") == 0 &&
	       e->exptime_s == *(const double *)ctx;
}

static void test_errors_no_dark_for_exposure(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = &k->truth.entry[k->truth.n_entries - 2];
	double t = e->exptime_s;

	/* The last angle's exposure is not the shortest dark's. */
	assert_string_equal(e->type, "FULL");
	assert_true(t != first(k, "DARK")->exptime_s);

	assert_int_equal(synth_write_manifest(k->dir, &k->truth, skip_darks_at,
					      &t), 0);
	/* Named: the first frame that needs that dark. */
	for (e = k->truth.entry; e->exptime_s != t || !strcmp(e->type, "DARK");)
		e++;
	expect_bad(k, e->file, "EXPTIME");
	assert_non_null(strstr(k->run.err, "no dark"));
}

static void test_errors_rows_disagree(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = first(k, "FULL");
	fitsfile *f;
	char p[256];
	int status = 0;

	path_of(k, e, p, sizeof(p));
	fits_open_file(&f, p, READWRITE, &status);
	fits_update_key_longstr(f, "ROWS", "0,1,200,201,400,401", NULL,
				&status);
	fits_close_file(f, &status);
	assert_int_equal(status, 0);
	assert_int_equal(synth_write_manifest(k->dir, &k->truth, NULL, NULL), 0);
	expect_bad(k, e->file, "ROWS");
}

static void test_errors_monitor_in_some_frames(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = &k->truth.entry[k->truth.n_entries - 1];
	double mon = 1.01;
	fitsfile *f;
	char p[256];
	int status = 0;

	path_of(k, e, p, sizeof(p));
	fits_open_file(&f, p, READWRITE, &status);
	fits_update_key(f, TDOUBLE, "MONITOR", &mon, NULL, &status);
	fits_close_file(f, &status);
	assert_int_equal(status, 0);
	assert_int_equal(synth_write_manifest(k->dir, &k->truth, NULL, NULL), 0);
	expect_bad(k, e->file, "MONITOR");
}

static void test_errors_hash_mismatch(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = first(k, "DARK");
	char p[256];
	FILE *f;

	path_of(k, e, p, sizeof(p));
	f = fopen(p, "r+b");
	assert_non_null(f);
	assert_int_equal(fseek(f, 2880 + 10, SEEK_SET), 0);
	assert_int_equal(fputc(0x5a, f), 0x5a);
	assert_int_equal(fclose(f), 0);
	expect_bad(k, e->file, "sha256");
}

static void test_errors_bad_manifest_cell(void **state)
{
	struct bad_case *k = *state;
	char p[256];
	FILE *f;

	snprintf(p, sizeof(p), "%s/manifest.csv", k->dir);
	f = fopen(p, "a");
	assert_non_null(f);
	fprintf(f, "x.fits,FULL,ten,0.1,1,0,%064d\n", 0);
	assert_int_equal(fclose(f), 0);
	expect_bad(k, "manifest.csv", "angle_deg");
}

/* A frame the manifest lists but the folder lacks: bad input, exit 2. */
static void test_errors_listed_frame_missing(void **state)
{
	struct bad_case *k = *state;
	const struct synth_entry *e = first(k, "AMBIENT");
	char p[256];

	path_of(k, e, p, sizeof(p));
	assert_int_equal(unlink(p), 0);
	expect_bad(k, e->file, "listed in manifest.csv but missing");
}

/* A row given twice is named as such (was "no FULL frame at this angle"). */
static void test_errors_duplicate_manifest_row(void **state)
{
	struct bad_case *k = *state;
	char p[256], line[1024];
	FILE *f;

	snprintf(p, sizeof(p), "%s/manifest.csv", k->dir);
	f = fopen(p, "r");
	assert_non_null(f);
	do		/* the first data line */
		assert_non_null(fgets(line, sizeof(line), f));
	while (line[0] == '#' || strncmp(line, "file", 4) == 0);
	assert_int_equal(fclose(f), 0);
	f = fopen(p, "a");
	assert_non_null(f);
	fputs(line, f);
	assert_int_equal(fclose(f), 0);
	expect_bad(k, "manifest.csv", "listed twice");
}

/* A run refused after the reduction writes nothing (r.csv was written
 * before --map-regions 65 was refused). */
static void test_errors_late_refusal_writes_nothing(void **state)
{
	struct bad_case *k = *state;
	char map[160];
	char *argv[] = { "stray", "reduce", k->dir, "--out", k->out, "--map",
			 map, "--map-regions", "65", NULL };

	snprintf(map, sizeof(map), "%s/m.csv", k->root);
	run_stray(&k->run, argv);
	assert_int_equal(k->run.status, 2);
	assert_int_equal(k->run.err_lines, 1);
	assert_int_equal(access(k->out, F_OK), -1);
	assert_int_equal(access(map, F_OK), -1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_errors_truncated_fits,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_errors_missing_keyword,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_errors_no_dark_for_exposure,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_errors_rows_disagree,
						setup, teardown),
		cmocka_unit_test_setup_teardown(
			test_errors_monitor_in_some_frames, setup, teardown),
		cmocka_unit_test_setup_teardown(test_errors_hash_mismatch,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_errors_bad_manifest_cell,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_errors_listed_frame_missing,
						setup, teardown),
		cmocka_unit_test_setup_teardown(
			test_errors_duplicate_manifest_row, setup, teardown),
		cmocka_unit_test_setup_teardown(
			test_errors_late_refusal_writes_nothing, setup, teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
