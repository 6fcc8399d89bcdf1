/*
 * test_hal_fail_wrap.c - fail-after-N over every HAL path.  All rig_hal_*
 * transfer calls are wrapped at link time (-Wl,--wrap); the wrappers pass
 * through to the simulator except the N-th call, which fails with EIO
 * (not retried) or, for even N, EDISCONNECT (retried after a reconnect).
 * For N spread over a whole small sweep, each run must end either complete
 * or with one error line and the lab safe, and the folder left behind must
 * resume to a complete, consistent sweep.  SQLite's fault-injection
 * countdown (test_malloc.c), applied at the hardware seam.
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

static long calls, fail_at;
static int fail_code;	/* EIO: stops the sweep; EDISCONNECT: retried */

static int countdown(void)
{
	++calls;
	return fail_at > 0 && calls == fail_at;
}

#define WRAP(ret, name, params, args)					\
	ret __real_##name params;					\
	ret __wrap_##name params					\
	{								\
		if (countdown())					\
			return fail_code;				\
		return __real_##name args;				\
	}

WRAP(int, rig_hal_usb_open, (const struct rig_hal *hal,
	const struct rig_usb_id *id, struct rig_hal_dev *d), (hal, id, d))
WRAP(int, rig_hal_usb_control, (struct rig_hal_dev *d, uint8_t type,
	uint8_t req, uint16_t value, uint16_t index, unsigned timeout_ms),
	(d, type, req, value, index, timeout_ms))
WRAP(int, rig_hal_usb_write, (struct rig_hal_dev *d, uint8_t ep,
	const uint8_t *buf, size_t len, unsigned timeout_ms),
	(d, ep, buf, len, timeout_ms))
WRAP(int, rig_hal_usb_read, (struct rig_hal_dev *d, uint8_t ep, uint8_t *buf,
	size_t cap, size_t *got, unsigned timeout_ms),
	(d, ep, buf, cap, got, timeout_ms))
WRAP(int, rig_hal_hid_open, (const struct rig_hal *hal, uint16_t vid,
	uint16_t pid, const char *serial, struct rig_hal_dev *d),
	(hal, vid, pid, serial, d))
WRAP(int, rig_hal_hid_write, (struct rig_hal_dev *d, const uint8_t *buf,
	size_t len), (d, buf, len))
WRAP(int, rig_hal_hid_read, (struct rig_hal_dev *d, uint8_t *buf, size_t cap,
	size_t *got, unsigned timeout_ms), (d, buf, cap, got, timeout_ms))
WRAP(int, rig_hal_gpio_open, (const struct rig_hal *hal,
	const struct rig_gpio_id *id, struct rig_hal_dev *d), (hal, id, d))
WRAP(int, rig_hal_gpio_set, (struct rig_hal_dev *d, int value), (d, value))
WRAP(int, rig_hal_gpio_get, (struct rig_hal_dev *d, int *value), (d, value))

/* One sweep into dir with the countdown armed; returns its status. */
static int sweep_once(const struct rig_config *cfg, const char *dir,
		      int resume, long fail, struct rig_sim *sim,
		      struct rig_error *err)
{
	struct rig_hal hal;
	struct rig_lab lab;
	struct rig_sweep sw;
	int rc;

	calls = 0;
	fail_at = fail;
	rig_error_clear(err);
	rig_sim_init(sim, cfg, &hal);
	rc = rig_lab_open(&lab, cfg, &hal, err);
	if (rc != RIG_OK) {
		rig_sim_fini(sim);
		return rc;
	}
	rc = rig_sweep_open(&sw, &lab, dir, resume, err);
	if (rc == RIG_OK) {
		rc = rig_sweep_run(&sw, NULL, err);
		rig_sweep_close(&sw);
	}
	rig_lab_close(&lab);
	rig_sim_fini(sim);
	return rc;
}

static void test_hal_fail_after_n_everywhere(void **state)
{
	struct rig_config cfg;
	struct rig_sim sim;
	struct rig_error err;
	long total, n, step;
	int runs = 0, failed = 0;

	(void)state;
	small_config(&cfg);
	cfg.sweep.theta_stop_deg = 10;	/* 2 angles keep it quick */
	cfg.monitor.enabled = 1;
	{
		char *dir = temp_dir();

		assert_int_equal(sweep_once(&cfg, dir, 0, 0, &sim, &err),
				 RIG_OK);
		total = calls;
		remove_tree(dir);
		free(dir);
	}
	print_message("a clean sweep makes %ld HAL calls\n", total);
	step = total / 20 + 1;
	for (n = 1; n <= total; n += n < 20 ? 1 : step) {
		char *dir = temp_dir();
		int rc;

		fail_code = n % 2 ? RIG_EIO : RIG_EDISCONNECT;
		rc = sweep_once(&cfg, dir, 0, n, &sim, &err);

		runs++;
		if (rc != RIG_OK) {
			failed++;
			assert_true(strlen(err.msg) > 0);
			assert_null(strchr(err.msg, '\n'));
			assert_false(rig_sim_lamp_on(&sim));
			assert_false(rig_sim_shutter_open(&sim));
		}
		/* Whatever happened, resuming completes it consistently. */
		fail_code = RIG_OK;
		assert_int_equal(sweep_once(&cfg, dir, 1, 0, &sim, &err),
				 RIG_OK);
		assert_int_equal(check_sweep(dir, &cfg).bad, 0);
		remove_tree(dir);
		free(dir);
	}
	print_message("%d runs, %d stopped with an error, all resumed\n",
		      runs, failed);
	assert_true(failed > 0 && failed < runs);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hal_fail_after_n_everywhere),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
