/*
 * test_sweep.c - the sweep engine end to end against the simulators:
 * the real drivers speak APT, HID, GPIO and the frame link to the device
 * models; faults are injected and the folder is checked independently
 * (rig_test_util.h) after each run.  A small reduction by eq. 3.4-3.7 of
 * the frames written must give back the virtual lab's lens curve.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig/lab.h"
#include "rig/sim.h"
#include "rig/sweep.h"
#include "rig_test_util.h"

struct run {
	struct rig_config cfg;
	struct rig_sim sim;
	struct rig_hal hal;
	struct rig_lab lab;
	struct rig_sweep sw;
	struct rig_error err;
	char *dir;
	int rc;
};

/* Run a whole sweep into a fresh folder; r->rc is its status. */
static void run_sweep(struct run *r)
{
	rig_error_clear(&r->err);
	r->dir = temp_dir();
	assert_non_null(r->dir);
	rig_sim_init(&r->sim, &r->cfg, &r->hal);
	assert_int_equal(rig_lab_open(&r->lab, &r->cfg, &r->hal, &r->err),
			 RIG_OK);
	assert_int_equal(rig_sweep_open(&r->sw, &r->lab, r->dir, 0, &r->err),
			 RIG_OK);
	r->rc = rig_sweep_run(&r->sw, NULL, &r->err);
}

static void end_run(struct run *r)
{
	rig_sweep_close(&r->sw);
	rig_lab_close(&r->lab);
	rig_sim_fini(&r->sim);
	remove_tree(r->dir);
	free(r->dir);
}

static void assert_lab_safe(const struct run *r)
{
	assert_false(rig_sim_lamp_on(&r->sim));
	assert_true(rig_sim_beam_blocked(&r->sim));
	assert_false(rig_sim_shutter_open(&r->sim));
}

static void assert_complete(struct run *r)
{
	struct sweep_check c;

	if (r->rc != RIG_OK)
		fprintf(stderr, "sweep: %s\n", r->err.msg);
	assert_int_equal(r->rc, RIG_OK);
	assert_true(r->sw.finished);
	c = check_sweep(r->dir, &r->cfg);
	assert_int_equal(c.bad, 0);
	assert_true(c.rows >= 4 * 3 * 2);
	assert_lab_safe(r);
}

static void test_sweep_complete_and_safe(void **state)
{
	struct run r;

	(void)state;
	small_config(&r.cfg);
	run_sweep(&r);
	assert_complete(&r);
	assert_int_equal(rig_sim_faults_fired(&r.sim), 0);
	end_run(&r);
}

/* Mean of one FITS frame's pixels after subtracting another's: the
 * light-only signal L = I - D of eq. 3.4-3.5, summed over pixels. */
static double frame_sum(const char *dir, const char *file)
{
	char path[1024];
	fitsfile *f;
	long n, i;
	int st = 0, nul;
	double sum = 0, *px;
	long naxes[2];

	snprintf(path, sizeof(path), "%s/%s", dir, file);
	fits_open_file(&f, path, READONLY, &st);
	fits_get_img_size(f, 2, naxes, &st);
	n = naxes[0] * naxes[1];
	px = malloc((size_t)n * sizeof(*px));
	fits_read_img(f, TDOUBLE, 1, n, NULL, px, &nul, &st);
	fits_close_file(f, &st);
	assert_int_equal(st, 0);
	for (i = 0; i < n; i++)
		sum += px[i];
	free(px);
	return sum;
}

/* Mean over the group's repeats of the summed frame, and its t, nd. */
static double group_sum(const struct stray_sweep_manifest *mf, double a,
			int type,
			double t_exp_s, double *t_out, double *nd_out)
{
	size_t i;
	double s = 0;
	int n = 0;

	for (i = 0; i < mf->n; i++) {
		const struct stray_sweep_entry *row = &mf->e[i];

		if (row->type != type ||
		    fabs(row->angle_deg - a) > 1e-6 ||
		    (t_exp_s > 0 && fabs(row->exptime_s - t_exp_s) > 1e-9))
			continue;
		s += frame_sum(mf->dir, row->file);
		*t_out = row->exptime_s;
		*nd_out = row->ndtrans;
		n++;
	}
	assert_true(n > 0);
	return s / n;
}

/* eq. 3.6: J = L_ful/(t1 nd1) - L_amb/(t2 nd2); the darks matched on t. */
static double true_response(const struct stray_sweep_manifest *mf, double a)
{
	double t1, nd1, t2, nd2, d, dummy, ful, amb;

	ful = group_sum(mf, a, STRAY_SWEEP_FULL, -1, &t1, &nd1);
	amb = group_sum(mf, a, STRAY_SWEEP_AMBIENT, -1, &t2, &nd2);
	d = group_sum(mf, a, STRAY_SWEEP_DARK, t1, &dummy, &dummy);
	ful -= d;
	d = group_sum(mf, a, STRAY_SWEEP_DARK, t2, &dummy, &dummy);
	amb -= d;
	return ful / (t1 * nd1) - amb / (t2 * nd2);
}

static void test_sweep_recovers_lens_curve(void **state)
{
	struct stray_sweep_manifest mf;
	struct run r;
	double j0, a;

	(void)state;
	small_config(&r.cfg);
	/* A plain sum keeps hot pixels in. */
	r.cfg.sim.vlab.hot_frac = 0;
	run_sweep(&r);
	assert_complete(&r);
	assert_int_equal(stray_sweep_manifest_load(r.dir, &mf, NULL),
			 STRAY_OK);
	j0 = true_response(&mf, 0);
	for (a = 10; a <= 30; a += 10) {
		const struct rig_camera_cfg *c = &r.cfg.camera;
		double truth = rig_vlab_lens_alpha(&r.cfg.sim.vlab, a, c->rows,
						   c->n_rows, c->col0,
						   c->n_cols);
		double got = true_response(&mf, a) / j0;	/* eq. 3.7 */

		/* Shot noise over 512 px x 2 frames: well under 1%. */
		print_message("alpha(%g): reduced %.5f, truth %.5f\n", a, got,
			      truth);
		assert_float_equal(got / truth, 1.0, 0.02);
	}
	stray_sweep_manifest_free(&mf);
	end_run(&r);
}

/* MONITOR of a frame, 1 when absent. */
static double frame_monitor(const char *dir, const char *file)
{
	char path[1024];
	fitsfile *f;
	double m = 1;
	int st = 0;

	snprintf(path, sizeof(path), "%s/%s", dir, file);
	fits_open_file(&f, path, READONLY, &st);
	fits_read_key(f, TDOUBLE, "MONITOR", &m, NULL, &st);
	st = 0;
	fits_close_file(f, &st);
	return m;
}

/* eq. 3.6 with each lit frame's light divided by its lamp level. */
static double j_monitored(const struct stray_sweep_manifest *mf, double a,
			  int norm)
{
	double j = 0, t, nd, dummy, dark[2];
	int type, k;
	size_t i;

	for (k = 0, type = STRAY_SWEEP_FULL; k < 2; k++,
	     type = STRAY_SWEEP_AMBIENT) {
		double sum = 0;
		int n = 0;

		group_sum(mf, a, type, -1, &t, &nd);
		dark[k] = group_sum(mf, a, STRAY_SWEEP_DARK, t, &dummy, &dummy);
		for (i = 0; i < mf->n; i++) {
			const struct stray_sweep_entry *r = &mf->e[i];

			if (r->type != type ||
			    fabs(r->angle_deg - a) > 1e-6)
				continue;
			sum += (frame_sum(mf->dir, r->file) - dark[k]) /
			       (norm ? frame_monitor(mf->dir, r->file) : 1);
			n++;
		}
		j += (k == 0 ? 1 : -1) * sum / n / (t * nd);
	}
	return j;
}

/* A lamp drifting 1 %/s (hidden from the analysis) biases the curve;
 * the monitor photodiode's MONITOR keyword takes it out again. */
static void test_sweep_monitor_corrects_lamp_drift(void **state)
{
	struct stray_sweep_manifest mf;
	struct run r;
	double worst_raw = 0, worst_norm = 0, a;

	(void)state;
	small_config(&r.cfg);
	r.cfg.sim.vlab.hot_frac = 0;
	r.cfg.sim.vlab.lamp_drift_per_h = 36;
	r.cfg.monitor.enabled = 1;
	run_sweep(&r);
	assert_complete(&r);
	assert_int_equal(stray_sweep_manifest_load(r.dir, &mf, NULL),
			 STRAY_OK);
	for (a = 10; a <= 30; a += 10) {
		const struct rig_camera_cfg *c = &r.cfg.camera;
		double truth = rig_vlab_lens_alpha(&r.cfg.sim.vlab, a, c->rows,
						   c->n_rows, c->col0,
						   c->n_cols);
		double raw = j_monitored(&mf, a, 0) / j_monitored(&mf, 0, 0);
		double norm = j_monitored(&mf, a, 1) / j_monitored(&mf, 0, 1);

		print_message("alpha(%g): raw %.5f, monitored %.5f, truth "
			      "%.5f\n", a, raw, norm, truth);
		worst_raw = fmax(worst_raw, fabs(raw / truth - 1));
		worst_norm = fmax(worst_norm, fabs(norm / truth - 1));
	}
	assert_true(worst_raw > 0.05);		/* the drift is visible */
	assert_true(worst_norm < 0.01);		/* and removed */
	stray_sweep_manifest_free(&mf);
	end_run(&r);
}

static void test_sweep_exposure_below_saturation(void **state)
{
	struct stray_sweep_manifest mf;
	struct run r;
	size_t i;

	(void)state;
	small_config(&r.cfg);
	run_sweep(&r);
	assert_complete(&r);
	assert_int_equal(stray_sweep_manifest_load(r.dir, &mf, NULL),
			 STRAY_OK);
	for (i = 0; i < mf.n; i++) {
		const struct stray_sweep_entry *m = &mf.e[i];

		assert_true(m->exptime_s >= r.cfg.sweep.t_min_s - 1e-9);
		assert_true(m->exptime_s <= r.cfg.sweep.t_max_s + 1e-9);
	}
	/* On axis the bright beam needs an ND filter (lamp 4e5 DN/s). */
	assert_true(mf.e[0].type == STRAY_SWEEP_FULL &&
		    mf.e[0].ndtrans < 1);
	stray_sweep_manifest_free(&mf);
	end_run(&r);
}

static void add_fault(struct rig_config *cfg, int dev, int kind,
		      unsigned at, unsigned count, double value)
{
	struct rig_fault *f = &cfg->sim.faults[cfg->sim.n_faults++];

	f->device = dev;
	f->kind = kind;
	f->at = at;
	f->count = count;
	f->value = value;
}

static void test_sweep_survives_transient_faults(void **state)
{
	struct run r;

	(void)state;
	small_config(&r.cfg);
	add_fault(&r.cfg, RIG_DEV_CAMERA, RIG_FAULT_CRC, 5, 1, 0);
	add_fault(&r.cfg, RIG_DEV_CAMERA, RIG_FAULT_TIMEOUT, 12, 1, 0);
	add_fault(&r.cfg, RIG_DEV_CAMERA, RIG_FAULT_DISCONNECT, 20, 2, 0);
	add_fault(&r.cfg, RIG_DEV_STAGE, RIG_FAULT_MISS, 2, 1, 0.5);
	add_fault(&r.cfg, RIG_DEV_STAGE, RIG_FAULT_STALL, 4, 1, 0);
	add_fault(&r.cfg, RIG_DEV_WHEEL, RIG_FAULT_STALL, 2, 1, 0);
	run_sweep(&r);
	assert_complete(&r);
	assert_int_equal(rig_sim_faults_fired(&r.sim), 6);
	assert_int_equal(r.lab.crc_rereads + r.lab.camera.crc_rereads, 1);
	assert_true(r.lab.recoveries >= 4);
	end_run(&r);
}

static void test_sweep_stops_safe_on_lasting_disconnect(void **state)
{
	struct run r;

	(void)state;
	small_config(&r.cfg);
	add_fault(&r.cfg, RIG_DEV_CAMERA, RIG_FAULT_DISCONNECT, 9, 100, 0);
	run_sweep(&r);
	assert_int_equal(r.rc, RIG_EDISCONNECT);
	assert_non_null(strstr(r.err.msg, "camera"));
	assert_null(strchr(r.err.msg, '\n'));
	assert_lab_safe(&r);
	assert_int_equal(check_sweep(r.dir, &r.cfg).bad > 0,
			 1);	/* partial */
	end_run(&r);
}

static void test_sweep_stops_safe_on_persistent_crc(void **state)
{
	struct run r;

	(void)state;
	small_config(&r.cfg);
	/* value >= 1: the re-sends are corrupt too; count covers retries. */
	add_fault(&r.cfg, RIG_DEV_CAMERA, RIG_FAULT_CRC, 3, 50, 1);
	run_sweep(&r);
	assert_int_equal(r.rc, RIG_ECRC);
	assert_non_null(strstr(r.err.msg, "CRC mismatch"));
	assert_lab_safe(&r);
	end_run(&r);
}

static void test_sweep_stops_on_stage_that_keeps_missing(void **state)
{
	struct run r;

	(void)state;
	small_config(&r.cfg);
	add_fault(&r.cfg, RIG_DEV_STAGE, RIG_FAULT_MISS, 2, 100, 0.3);
	run_sweep(&r);
	assert_int_equal(r.rc, RIG_ETARGET);
	assert_non_null(strstr(r.err.msg, "stage: stopped at"));
	assert_lab_safe(&r);
	end_run(&r);
}

/* Active-low wiring: the lines driver inverts, the lab still ends safe
 * (physically high lamp and shutter lines, low beam block). */
static void test_sweep_active_low_lines_end_safe(void **state)
{
	struct run r;
	int i;

	(void)state;
	small_config(&r.cfg);
	for (i = 0; i < RIG_LINE_COUNT; i++)
		r.cfg.lines[i].active_low = 1;
	run_sweep(&r);
	assert_complete(&r);
	assert_int_equal(r.sim.lines.level[RIG_LINE_LAMP], 1);
	assert_int_equal(r.sim.lines.level[RIG_LINE_SHUTTER], 1);
	assert_int_equal(r.sim.lines.level[RIG_LINE_BEAM_BLOCK], 0);
	end_run(&r);
}

/* A GPIO write that does not take (stuck driver) is caught by the
 * read-back and stops the sweep with the line named. */
static void test_sweep_stops_on_line_readback(void **state)
{
	struct run r;

	(void)state;
	small_config(&r.cfg);
	/* Writes 1-3 make the lab safe at open; 4-6 light it: 5 unblocks the
	 * beam, and is lost. */
	add_fault(&r.cfg, RIG_DEV_GPIO, RIG_FAULT_STALL, 5, 1, 0);
	run_sweep(&r);
	assert_int_equal(r.rc, RIG_EDEVICE);
	assert_non_null(strstr(r.err.msg, "beam_block: set 0 but read back 1"));
	assert_lab_safe(&r);
	end_run(&r);
}

static void test_sweep_refuses_existing_folder(void **state)
{
	struct run r;
	struct rig_sweep again;
	struct rig_error err;

	(void)state;
	small_config(&r.cfg);
	run_sweep(&r);
	rig_error_clear(&err);
	assert_int_equal(rig_sweep_open(&again, &r.lab, r.dir, 0, &err),
			 RIG_EIO);
	assert_non_null(strstr(err.msg, "resume"));
	end_run(&r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sweep_complete_and_safe),
		cmocka_unit_test(test_sweep_recovers_lens_curve),
		cmocka_unit_test(test_sweep_exposure_below_saturation),
		cmocka_unit_test(test_sweep_monitor_corrects_lamp_drift),
		cmocka_unit_test(test_sweep_survives_transient_faults),
		cmocka_unit_test(test_sweep_stops_safe_on_lasting_disconnect),
		cmocka_unit_test(test_sweep_stops_safe_on_persistent_crc),
		cmocka_unit_test(test_sweep_stops_on_stage_that_keeps_missing),
		cmocka_unit_test(test_sweep_active_low_lines_end_safe),
		cmocka_unit_test(test_sweep_stops_on_line_readback),
		cmocka_unit_test(test_sweep_refuses_existing_folder),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
