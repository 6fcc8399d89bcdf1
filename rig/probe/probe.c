/*
 * probe.c - strayrig-probe (`stray rig probe --config RIG.json`): the
 * lab's first-day check.  Lists what the real backend finds on the buses
 * (USB devices by the config's vid:pid, hidraw nodes, GPIO chips and the
 * named lines) and talks to each device once through the same drivers
 * the daemon uses, without moving anything:
 *   gpio     lines requested at their safe levels and read back
 *   stage    FTDI set-up, one position read (MOT_REQ_POSCOUNTER)
 *   wheel    one QUERY report round trip
 *   monitor  one photocurrent reading (when enabled)
 *   camera   window set, one 10 ms frame, CRC checked (shutter closed)
 * A lab on INDI ("backend": "indi") is probed through the daemon's INDI
 * lab instead (probe_indi.c).  One line per device, "ok" or the driver's
 * error; exit 0 when every device answered, 1 otherwise, 2 for a bad
 * config.
 */
#include <gpiod.h>
#include <hidapi.h>
#include <libusb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "probe.h"
#include "rig/config.h"
#include "rig/devices.h"
#include "rig/wheel_report.h"

static int failures;

void probe_result(const char *dev, int rc, const struct rig_error *err,
		  const char *what)
{
	if (rc == RIG_OK) {
		printf("%-8s ok: %s\n", dev, what);
	} else {
		printf("%-8s FAILED: %s\n", dev, err->msg);
		failures++;
	}
}

/* ---- what is on the buses ---- */
static void list_usb(const struct rig_config *c)
{
	libusb_context *ctx;
	libusb_device **list;
	ssize_t n, i;

	if (libusb_init(&ctx) != 0) {
		printf("usb      cannot initialise libusb\n");
		return;
	}
	n = libusb_get_device_list(ctx, &list);
	for (i = 0; i < n; i++) {
		struct libusb_device_descriptor dd;
		const char *role = NULL;

		if (libusb_get_device_descriptor(list[i], &dd) != 0)
			continue;
		if (dd.idVendor == c->stage.usb.vid &&
		    dd.idProduct == c->stage.usb.pid)
			role = "stage (APT over FTDI)";
		else if (dd.idVendor == c->camera.usb.vid &&
			 dd.idProduct == c->camera.usb.pid)
			role = "camera";
		if (role)
			printf("found    usb %04x:%04x bus %03u device %03u: "
			       "%s\n", dd.idVendor, dd.idProduct,
			       libusb_get_bus_number(list[i]),
			       libusb_get_device_address(list[i]), role);
	}
	if (n >= 0)
		libusb_free_device_list(list, 1);
	libusb_exit(ctx);
}

static void list_hid(uint16_t vid, uint16_t pid, const char *role)
{
	struct hid_device_info *all = hid_enumerate(vid, pid), *d;

	for (d = all; d; d = d->next)
		printf("found    hid %04x:%04x %s serial '%ls': %s\n",
		       d->vendor_id, d->product_id, d->path,
		       d->serial_number ? d->serial_number : L"", role);
	if (!all)
		printf("missing  hid %04x:%04x: %s\n", vid, pid, role);
	hid_free_enumeration(all);
}

static void list_gpio(const struct rig_config *c)
{
	int i;

	for (i = 0; i < RIG_LINE_COUNT; i++) {
		const struct rig_line_cfg *l = &c->lines[i];
		struct gpiod_chip *chip = gpiod_chip_open_lookup(l->chip);
		struct gpiod_line *line = chip ? gpiod_chip_find_line(chip,
							l->line) : NULL;

		if (line)
			printf("found    gpio %s line %u '%s': %s%s\n", l->chip,
			       gpiod_line_offset(line), l->line,
			       rig_line_name((enum rig_line)i),
			       gpiod_line_is_used(line) ? " (in use!)" : "");
		else
			printf("missing  gpio %s line '%s': %s\n", l->chip,
			       l->line, rig_line_name((enum rig_line)i));
		if (chip)
			gpiod_chip_close(chip);
	}
}

/* ---- one exchange with each ---- */
static void talk_gpio(const struct rig_hal *hal, const struct rig_config *c)
{
	struct rig_lines l;
	struct rig_error err;
	int rc;

	rig_error_clear(&err);
	rc = rig_lines_open(&l, hal, c->lines, &err);
	if (rc == RIG_OK) {
		rc = rig_lines_safe(&l, &err);
		rig_lines_close(&l);
	}
	probe_result("gpio", rc, &err, "lamp off, beam blocked, shutter closed, "
	       "each read back");
}

static void talk_stage(const struct rig_hal *hal, const struct rig_config *c)
{
	struct rig_stage s;
	struct rig_error err;
	char what[64];
	double theta = 0;
	int rc;

	rig_error_clear(&err);
	rc = rig_stage_open(&s, hal, &c->stage, &err);
	if (rc == RIG_OK) {
		rc = rig_stage_position(&s, &theta, &err);
		rig_stage_close(&s);
	}
	snprintf(what, sizeof(what), "position counter reads %.3f deg",
		 theta);
	probe_result("stage", rc, &err, what);
}

static void talk_wheel(const struct rig_hal *hal, const struct rig_config *c)
{
	struct rig_wheel w;
	struct rig_wheel_out o = { RIG_WHEEL_QUERY, 0, 1 };
	struct rig_wheel_in in;
	struct rig_error err;
	uint8_t buf[RIG_WHEEL_REPORT_LEN];
	char what[64] = "";
	size_t got = 0;
	int rc;

	rig_error_clear(&err);
	rc = rig_wheel_open(&w, hal, &c->wheel, &err);
	if (rc != RIG_OK) {
		probe_result("wheel", rc, &err, "");
		return;
	}
	rig_wheel_out_encode(&o, buf);
	rc = rig_hal_hid_write(&w.hid, buf, sizeof(buf));
	if (rc == RIG_OK)
		rc = rig_hal_hid_read(&w.hid, buf, sizeof(buf), &got, 500);
	if (rc == RIG_OK && rig_wheel_in_decode(buf, got, &in) != RIG_OK)
		rc = RIG_EPROTO;
	if (rc != RIG_OK)
		rig_error_set(&err, rc, "wheel: QUERY: %s",
			      rig_status_text(rc));
	else
		snprintf(what, sizeof(what), "slot %u of %u, flags 0x%02x",
			 in.slot, in.n_slots, in.flags);
	rig_wheel_close(&w);
	probe_result("wheel", rc, &err, what);
}

static void talk_monitor(const struct rig_hal *hal,
			 const struct rig_config *c)
{
	struct rig_monitor m;
	struct rig_error err;
	char what[64];
	double level = 0;
	int rc;

	rig_error_clear(&err);
	rc = rig_monitor_open(&m, hal, &c->monitor, &err);
	if (rc == RIG_OK) {
		rc = rig_monitor_read(&m, &level, &err);
		rig_monitor_close(&m);
	}
	snprintf(what, sizeof(what), "lamp level %.4f of nominal", level);
	probe_result("monitor", rc, &err, what);
}

static void talk_camera(const struct rig_hal *hal,
			const struct rig_config *c)
{
	struct rig_camera cam;
	struct rig_image img;
	struct rig_error err;
	char what[80];
	int rc;

	rig_error_clear(&err);
	memset(&img, 0, sizeof(img));
	rc = rig_camera_open(&cam, hal, &c->camera, &err);
	if (rc != RIG_OK) {
		probe_result("camera", rc, &err, "");
		return;
	}
	img.px = calloc((size_t)c->camera.n_rows * (size_t)c->camera.n_cols,
			sizeof(*img.px));
	rc = img.px ? rig_camera_set_exposure(&cam, 0.01, &err) : RIG_ENOMEM;
	if (rc == RIG_OK)
		rc = rig_camera_capture(&cam, &img, &err);
	snprintf(what, sizeof(what), "one 10 ms frame, %d x %d px, CRC ok",
		 img.n_rows, img.n_cols);
	free(img.px);
	rig_camera_close(&cam);
	probe_result("camera", rc, &err, what);
}

int main(int argc, char **argv)
{
	struct rig_config cfg;
	struct rig_error err;
	struct rig_hal hal;

	if (argc != 3 || strcmp(argv[1], "--config")) {
		fprintf(stderr, "usage: strayrig-probe --config RIG.json\n");
		return 2;
	}
	rig_error_clear(&err);
	rig_config_defaults(&cfg);
	if (rig_config_load(&cfg, argv[2], &err) != RIG_OK ||
	    rig_config_env(&cfg, &err) != RIG_OK) {
		fprintf(stderr, "strayrig-probe: %s\n", err.msg);
		return 2;
	}
	if (strcmp(cfg.backend, "indi") == 0) {
		probe_indi(&cfg);
		goto done;
	}
	if (rig_hal_real_init(&hal) != RIG_OK) {
		fprintf(stderr, "strayrig-probe: cannot initialise libusb "
			"or hidapi\n");
		return 1;
	}
	list_usb(&cfg);
	list_hid(cfg.wheel.vid, cfg.wheel.pid, "ND wheel");
	if (cfg.monitor.enabled)
		list_hid(cfg.monitor.vid, cfg.monitor.pid, "lamp monitor");
	list_gpio(&cfg);
	talk_gpio(&hal, &cfg);
	talk_stage(&hal, &cfg);
	talk_wheel(&hal, &cfg);
	if (cfg.monitor.enabled)
		talk_monitor(&hal, &cfg);
	talk_camera(&hal, &cfg);
	rig_hal_real_fini(&hal);
done:
	printf("%s\n", failures ? "probe: some devices did not answer"
				: "probe: every device answered");
	return failures ? 1 : 0;
}
