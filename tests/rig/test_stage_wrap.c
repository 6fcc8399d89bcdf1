/*
 * test_stage_wrap.c - the stage driver (stage.c over ftdi.c) with the HAL
 * wrapped at link time (-Wl,--wrap=rig_hal_usb_*, rig_hal_now/sleep):
 * the test plays the APT controller byte by byte, so the bytes the driver
 * sends and its reaction to replies, silence, errors, garbage and a
 * failing bus are checked without the simulator.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "rig/apt.h"
#include "rig/bytes.h"
#include "rig/devices.h"

/* ---- the scripted controller behind the wrapped HAL ---- */
static struct {
	uint8_t rx[2048];	/* bytes the "controller" will send */
	size_t rx_len, rx_off;
	uint8_t tx[1024];	/* bytes the driver wrote */
	size_t tx_len;
	int controls;
	uint16_t baud_index;	/* wIndex of SET_BAUD_RATE */
	int rts, latency_ms;
	uint16_t baud_value;
	double t_s;
	int fail_at, calls;	/* fail the fail_at-th transfer (0 = never) */
	int fake_dev;
} ctl;

static int fail_now(void)
{
	return ctl.fail_at && ++ctl.calls == ctl.fail_at;
}

int __wrap_rig_hal_usb_open(const struct rig_hal *hal,
			    const struct rig_usb_id *id, struct rig_hal_dev *d)
{
	(void)id;
	d->hal = hal;
	d->dev = &ctl.fake_dev;
	return fail_now() ? RIG_EDISCONNECT : RIG_OK;
}

int __wrap_rig_hal_usb_control(struct rig_hal_dev *d, uint8_t type,
			       uint8_t req, uint16_t value, uint16_t index,
			       unsigned timeout_ms)
{
	(void)d, (void)type, (void)timeout_ms;
	ctl.controls++;
	if (req == 3) {	/* FTDI_SIO_SET_BAUD_RATE */
		ctl.baud_value = value;
		ctl.baud_index = index;
	}
	if (req == 1 && (value & 0x0200))	/* SIO_MODEM_CTRL, RTS */
		ctl.rts = value & 0x02;
	if (req == 9)	/* SIO_SET_LATENCY_TIMER */
		ctl.latency_ms = value;
	return fail_now() ? RIG_EDISCONNECT : RIG_OK;
}

int __wrap_rig_hal_usb_write(struct rig_hal_dev *d, uint8_t ep,
			     const uint8_t *buf, size_t len,
			     unsigned timeout_ms)
{
	(void)d, (void)timeout_ms;
	assert_int_equal(ep, 0x02);
	if (fail_now())
		return RIG_EDISCONNECT;
	memcpy(ctl.tx + ctl.tx_len, buf, len);
	ctl.tx_len += len;
	return RIG_OK;
}

/* Deliver queued bytes as FTDI packets: 2 status bytes + up to 62. */
int __wrap_rig_hal_usb_read(struct rig_hal_dev *d, uint8_t ep, uint8_t *buf,
			    size_t cap, size_t *got, unsigned timeout_ms)
{
	size_t n = 0;

	(void)d;
	assert_int_equal(ep, 0x81);
	*got = 0;
	if (fail_now())
		return RIG_EDISCONNECT;
	ctl.t_s += timeout_ms * 1e-3 / 4;
	while (ctl.rx_off < ctl.rx_len && cap - n > 2) {
		size_t take = ctl.rx_len - ctl.rx_off;

		if (take > 62)
			take = 62;
		if (take > cap - n - 2)
			take = cap - n - 2;
		buf[n] = 0x01;
		buf[n + 1] = 0x60;
		memcpy(buf + n + 2, ctl.rx + ctl.rx_off, take);
		ctl.rx_off += take;
		n += take + 2;
	}
	if (n == 0) {
		buf[0] = 0x01;
		buf[1] = 0x60;
		n = 2;
	}
	*got = n;
	return RIG_OK;
}

void __wrap_rig_hal_usb_close(struct rig_hal_dev *d)
{
	d->dev = NULL;
}

double __wrap_rig_hal_now(const struct rig_hal *hal)
{
	(void)hal;
	return ctl.t_s;
}

void __wrap_rig_hal_sleep(const struct rig_hal *hal, double s)
{
	(void)hal;
	ctl.t_s += s;
}

/* ---- helpers ---- */
static const struct rig_stage_cfg cfg = {
	{ 0x0403, 0xfaf0, NULL, 0 }, "", 49152000.0 / 360.0, 0.01, 5.0,
	-5.0, 90.0
};

static void reply(const struct rig_apt_msg *m)
{
	ctl.rx_len += rig_apt_encode(m, ctl.rx + ctl.rx_len,
				     sizeof(ctl.rx) - ctl.rx_len);
}

static void reply_pos(uint16_t id, double deg)
{
	struct rig_apt_msg m;

	memset(&m, 0, sizeof(m));
	m.id = id;
	m.dest = RIG_APT_HOST;
	m.source = RIG_APT_USB_UNIT;
	m.data_len = id == RIG_APT_MOT_GET_POSCOUNTER ? 6 : 14;
	rig_put_u16(m.data, 1);
	rig_put_u32(m.data + 2, (uint32_t)lround(deg * cfg.counts_per_deg));
	reply(&m);
}

static void reply_short(uint16_t id)
{
	struct rig_apt_msg m;

	rig_apt_short(&m, id, 1, 0);
	m.dest = RIG_APT_HOST;
	m.source = RIG_APT_USB_UNIT;
	reply(&m);
}

static int setup(void **state)
{
	(void)state;
	memset(&ctl, 0, sizeof(ctl));
	return 0;
}

static void open_homed(struct rig_stage *s, struct rig_error *err)
{
	static const struct rig_hal hal;

	rig_error_clear(err);
	assert_int_equal(rig_stage_open(s, &hal, &cfg, err), RIG_OK);
	reply_short(RIG_APT_MOT_MOVE_HOMED);
	assert_int_equal(rig_stage_home(s, err), RIG_OK);
	ctl.tx_len = 0;
}

/* ---- tests ---- */
static void test_stage_open_sets_up_ftdi(void **state)
{
	struct rig_stage s;
	struct rig_error err;

	(void)state;
	open_homed(&s, &err);
	/* APT protocol §2.1: reset, baud, 8N1, purge x2, RTS/CTS, RTS on,
	 * and the latency timer. */
	assert_int_equal(ctl.controls, 8);
	assert_int_equal(ctl.baud_value, 0x001A);	/* 115200 baud */
	/* On an FT232, wIndex bit 0 is divisor bit 16: 1 would be 113744
	 * baud (the umockdev test bed found it). */
	assert_int_equal(ctl.baud_index, 0);
	assert_true(ctl.rts);
	assert_int_equal(ctl.latency_ms, 16);
}

static void test_stage_move_sends_absolute_counts(void **state)
{
	struct rig_stage s;
	struct rig_error err;
	int32_t counts = (int32_t)lround(12.5 * cfg.counts_per_deg);

	(void)state;
	open_homed(&s, &err);
	reply_pos(RIG_APT_MOT_MOVE_COMPLETED, 12.5);
	reply_pos(RIG_APT_MOT_GET_POSCOUNTER, 12.5);
	assert_int_equal(rig_stage_move(&s, 12.5, &err), RIG_OK);
	/* 0x0453, 6 data bytes, dest 0x50|0x80, source 0x01, chan 1, pos. */
	assert_true(ctl.tx_len >= 12);
	assert_int_equal(rig_get_u16(ctl.tx), 0x0453);
	assert_int_equal(rig_get_u16(ctl.tx + 2), 6);
	assert_int_equal(ctl.tx[4], 0xD0);
	assert_int_equal(ctl.tx[5], 0x01);
	assert_int_equal(rig_get_u16(ctl.tx + 6), 1);
	assert_int_equal((int32_t)rig_get_u32(ctl.tx + 8), counts);
	/* then REQ_POSCOUNTER to verify. */
	assert_int_equal(rig_get_u16(ctl.tx + 12), 0x0411);
}

static void test_stage_move_detects_missed_target(void **state)
{
	struct rig_stage s;
	struct rig_error err;

	(void)state;
	open_homed(&s, &err);
	reply_pos(RIG_APT_MOT_MOVE_COMPLETED, 19.5);
	reply_pos(RIG_APT_MOT_GET_POSCOUNTER, 19.5);
	assert_int_equal(rig_stage_move(&s, 20.0, &err), RIG_ETARGET);
	assert_non_null(strstr(err.msg, "19.5000"));
}

static void test_stage_move_times_out_on_silence(void **state)
{
	struct rig_stage s;
	struct rig_error err;

	(void)state;
	open_homed(&s, &err);
	assert_int_equal(rig_stage_move(&s, 3.0, &err), RIG_ETIMEOUT);
	assert_non_null(strstr(err.msg, "0x0464"));
	assert_true(ctl.t_s >= cfg.move_timeout_s);
}

static void test_stage_reports_controller_error(void **state)
{
	struct rig_stage s;
	struct rig_error err;

	(void)state;
	open_homed(&s, &err);
	reply_short(RIG_APT_HW_RESPONSE);
	assert_int_equal(rig_stage_move(&s, 3.0, &err), RIG_EDEVICE);
	assert_non_null(strstr(err.msg, "controller reported error"));
}

static void test_stage_resyncs_past_garbage(void **state)
{
	static const uint8_t junk[] = { 0xff, 0x00, 0x13, 0x99, 0x42, 0x07,
					0x01 };
	struct rig_stage s;
	struct rig_error err;
	int i;

	(void)state;
	open_homed(&s, &err);
	memcpy(ctl.rx + ctl.rx_len, junk, sizeof(junk));
	ctl.rx_len += sizeof(junk);
	/* 40 status messages: spans many 64-byte FTDI packets. */
	for (i = 0; i < 40; i++)
		reply_pos(RIG_APT_MOT_MOVE_STOPPED, 1.0);
	reply_pos(RIG_APT_MOT_MOVE_COMPLETED, 7.0);
	reply_pos(RIG_APT_MOT_GET_POSCOUNTER, 7.0);
	assert_int_equal(rig_stage_move(&s, 7.0, &err), RIG_OK);
}

static void test_stage_refuses_out_of_limits(void **state)
{
	struct rig_stage s;
	struct rig_error err;

	(void)state;
	open_homed(&s, &err);
	assert_int_equal(rig_stage_move(&s, 95.0, &err), RIG_EINTERLOCK);
	assert_int_equal(ctl.tx_len, 0);	/* nothing was sent */
	rig_error_clear(&err);
	assert_int_equal(rig_stage_move(&s, NAN, &err), RIG_EINTERLOCK);
}

/* Fail the N-th bus call for every N of a home + move: each failure is
 * returned with a message, never a crash or a false OK. */
static void test_stage_fail_after_n(void **state)
{
	static const struct rig_hal hal;
	int n, ok_seen = 0;

	(void)state;
	for (n = 1; n <= 40; n++) {
		struct rig_stage s;
		struct rig_error err;
		int rc;

		memset(&ctl, 0, sizeof(ctl));
		ctl.fail_at = n;
		rig_error_clear(&err);
		reply_short(RIG_APT_MOT_MOVE_HOMED);
		reply_pos(RIG_APT_MOT_MOVE_COMPLETED, 5.0);
		reply_pos(RIG_APT_MOT_GET_POSCOUNTER, 5.0);
		rc = rig_stage_open(&s, &hal, &cfg, &err);
		if (rc == RIG_OK)
			rc = rig_stage_home(&s, &err);
		if (rc == RIG_OK)
			rc = rig_stage_move(&s, 5.0, &err);
		if (ctl.calls >= n) {
			assert_int_equal(rc, RIG_EDISCONNECT);
			assert_true(strlen(err.msg) > 0);
		} else {
			assert_int_equal(rc, RIG_OK);
			ok_seen = 1;
		}
	}
	assert_true(ok_seen);	/* the sequence has fewer than 40 calls */
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup(test_stage_open_sets_up_ftdi, setup),
		cmocka_unit_test_setup(test_stage_move_sends_absolute_counts,
				       setup),
		cmocka_unit_test_setup(test_stage_move_detects_missed_target,
				       setup),
		cmocka_unit_test_setup(test_stage_move_times_out_on_silence,
				       setup),
		cmocka_unit_test_setup(test_stage_reports_controller_error,
				       setup),
		cmocka_unit_test_setup(test_stage_resyncs_past_garbage, setup),
		cmocka_unit_test_setup(test_stage_refuses_out_of_limits, setup),
		cmocka_unit_test_setup(test_stage_fail_after_n, setup),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
