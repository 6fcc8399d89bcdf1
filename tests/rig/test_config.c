/*
 * test_config.c - strayrigd's JSON config (config.c): values land in the
 * struct, and every kind of bad input is one line naming file and key.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>

#include "rig/config.h"

static int parse(struct rig_config *c, const char *text,
		 struct rig_error *err)
{
	rig_config_defaults(c);
	rig_error_clear(err);
	return rig_config_parse(c, "lab.json", text, err);
}

static void test_config_values_land(void **state)
{
	struct rig_config c;
	struct rig_error err;

	(void)state;
	assert_int_equal(parse(&c,
		"{\"stage\":{\"counts_per_deg\":1000,\"max_deg\":60},"
		"\"wheel\":{\"trans\":[1,0.5,0.25]},"
		"\"gpio\":{\"lamp\":{\"line\":\"LAMP\",\"active_low\":true}},"
		"\"camera\":{\"rows\":[1,2,3],\"n_cols\":64},"
		"\"sweep\":{\"repeats\":5},\"vlab\":{\"seed\":99,"
		"\"ghosts\":[{\"amp\":0.1}]},\"socket_mode\":432,"
		"\"sim\":{\"faults\":[{\"device\":\"camera\",\"kind\":\"crc\","
		"\"at\":3}]}}", &err), RIG_OK);
	assert_true(c.stage.counts_per_deg == 1000);
	assert_int_equal(c.wheel.n_slots, 3);
	assert_true(c.wheel.trans[2] == 0.25);
	assert_string_equal(c.lines[RIG_LINE_LAMP].line, "LAMP");
	assert_true(c.lines[RIG_LINE_LAMP].active_low);
	assert_int_equal(c.camera.n_rows, 3);
	assert_int_equal(c.sweep.repeats, 5);
	assert_int_equal(c.sim.vlab.seed, 99);
	assert_int_equal(c.sim.vlab.n_ghosts, 1);
	assert_int_equal(c.socket_mode, 0660);
	assert_int_equal(c.sim.n_faults, 1);
	assert_int_equal(c.sim.faults[0].kind, RIG_FAULT_CRC);
	assert_int_equal(c.sim.faults[0].at, 3);
}

static void expect_error(const char *text, const char *needle)
{
	struct rig_config c;
	struct rig_error err;

	assert_int_equal(parse(&c, text, &err), RIG_EPARSE);
	if (!strstr(err.msg, needle))
		fail_msg("'%s' lacks '%s'", err.msg, needle);
	assert_non_null(strstr(err.msg, "lab.json"));
	assert_null(strchr(err.msg, '\n'));
}

static void test_config_errors_name_the_key(void **state)
{
	(void)state;
	expect_error("{\"stage\":{\"counts_per_deg\":\"x\"}}",
		     "stage.counts_per_deg");
	expect_error("{\"stage\":{\"tol_deg\":-1}}", "value -1 outside");
	expect_error("{\"stage\":{\"speed\":1}}", "stage.speed: unknown key");
	expect_error("{\"sweep\":{\"repeats\":2.5}}", "expected an integer");
	expect_error("{\"wheel\":{\"trans\":[1,0]}}", "wheel.trans");
	expect_error("{\"camera\":{\"rows\":[5,4]}}", "camera.rows");
	expect_error("{\"backend\":\"usb\"}", "backend");
	expect_error("{\"sim\":{\"faults\":[{\"device\":\"toaster\"}]}}",
		     "sim.faults.device");
	expect_error("{\"sweep\":{\"theta_stop_deg\":120}}",
		     "stage limits");
	expect_error("{\"stage\":", "not valid JSON");
	expect_error("[1,2]", "expected a JSON object");
	expect_error("{\"vlab\":{\"bias_dn\":[1,2,3]}}", "vlab.bias_dn");
}

/* A socket anyone on the machine may write to would let anyone drive
 * the lab: socket_mode with o+w is refused (issue 14), 0660 is not. */
static void test_config_world_writable_socket_refused(void **state)
{
	struct rig_config c;
	struct rig_error err;

	(void)state;
	expect_error("{\"socket_mode\":511}", "socket_mode: world-writable");
	expect_error("{\"socket_mode\":438}", "socket_mode: world-writable");
	expect_error("{\"socket_mode\":2}", "socket_mode: world-writable");
	assert_int_equal(parse(&c, "{\"socket_mode\":432}", &err), RIG_OK);
	assert_int_equal(c.socket_mode, 0660);
}

/* The fault schedule names devices as enum rig_device does, in order. */
static void test_config_fault_devices_are_the_device_enum(void **state)
{
	static const char *const names[RIG_DEV_COUNT] = {
		[RIG_DEV_STAGE] = "stage", [RIG_DEV_WHEEL] = "wheel",
		[RIG_DEV_CAMERA] = "camera", [RIG_DEV_MONITOR] = "monitor",
		[RIG_DEV_GPIO] = "gpio",
	};
	struct rig_config c;
	struct rig_error err;
	char text[256];
	int d;

	(void)state;
	for (d = 0; d < RIG_DEV_COUNT; d++) {
		snprintf(text, sizeof(text), "{\"sim\":{\"real_delay_s\":0.5,"
			 "\"faults\":[{\"device\":\"%s\",\"kind\":\"stall\","
			 "\"at\":%d}]}}", names[d], d + 2);
		assert_int_equal(parse(&c, text, &err), RIG_OK);
		assert_string_equal(rig_device_names[d], names[d]);
		assert_int_equal(c.sim.n_faults, 1);
		assert_int_equal(c.sim.faults[0].device, d);
		assert_int_equal(c.sim.faults[0].kind, RIG_FAULT_STALL);
		assert_int_equal(c.sim.faults[0].at, d + 2);
		assert_true(c.sim.real_delay_s == 0.5);
	}
}

static void test_config_missing_file(void **state)
{
	struct rig_config c;
	struct rig_error err;

	(void)state;
	rig_config_defaults(&c);
	rig_error_clear(&err);
	assert_int_equal(rig_config_load(&c, "/nonexistent/rig.json", &err),
			 RIG_EIO);
	assert_non_null(strstr(err.msg, "/nonexistent/rig.json"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_config_values_land),
		cmocka_unit_test(test_config_errors_name_the_key),
		cmocka_unit_test(test_config_world_writable_socket_refused),
		cmocka_unit_test(test_config_fault_devices_are_the_device_enum),
		cmocka_unit_test(test_config_missing_file),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
