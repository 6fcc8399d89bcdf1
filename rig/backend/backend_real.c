/*
 * backend_real.c - the real backend's ops table and its clock.
 */
#include <hidapi.h>
#include <stdlib.h>
#include <time.h>

#include "backend.h"
#include "rig/status.h"

static double real_now(void *self)
{
	struct timespec ts;

	(void)self;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void real_sleep(void *self, double s)
{
	struct timespec ts;

	(void)self;
	ts.tv_sec = (time_t)s;
	ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
	while (nanosleep(&ts, &ts) != 0)
		;
}

static const struct rig_hal_ops real_ops = {
	.name = "real",
	.usb_open = rig_real_usb_open,
	.usb_control = rig_real_usb_control,
	.usb_write = rig_real_usb_write,
	.usb_read = rig_real_usb_read,
	.usb_close = rig_real_usb_close,
	.hid_open = rig_real_hid_open,
	.hid_write = rig_real_hid_write,
	.hid_read = rig_real_hid_read,
	.hid_close = rig_real_hid_close,
	.gpio_open = rig_real_gpio_open,
	.gpio_set = rig_real_gpio_set,
	.gpio_get = rig_real_gpio_get,
	.gpio_close = rig_real_gpio_close,
	.clock_now = real_now,
	.clock_sleep = real_sleep,
};

int rig_hal_real_init(struct rig_hal *hal)
{
	struct real_backend *rb = calloc(1, sizeof(*rb));

	if (!rb)
		return RIG_ENOMEM;
	if (libusb_init(&rb->usb) != 0 || hid_init() != 0) {
		free(rb);
		return RIG_EIO;
	}
	hal->ops = &real_ops;
	hal->self = rb;
	return RIG_OK;
}

void rig_hal_real_fini(struct rig_hal *hal)
{
	struct real_backend *rb = hal->self;

	if (!rb)
		return;
	hid_exit();
	libusb_exit(rb->usb);
	free(rb);
	hal->self = NULL;
}
