/*
 * hal.h - the hardware seam of the rig.
 *
 * Drivers call only the rig_hal_* functions below (defined in rig/hal/ files,
 * so a unit test can `-Wl,--wrap` them); each dispatches to a backend ops
 * table: the real one (libusb, hidapi, libgpiod, CLOCK_MONOTONIC) or the
 * simulator, which speaks the device side of the same byte protocols.
 * Everything above this seam is the code that runs in the lab (the Zephyr
 * emulator pattern: emul_bmi160.c behind the bus API).
 */
#ifndef RIG_HAL_H
#define RIG_HAL_H

#include <stddef.h>
#include <stdint.h>

/* A USB device: vendor/product id, optional serial, interface number. */
struct rig_usb_id {
	uint16_t vid, pid;
	const char *serial;	/* NULL = first match */
	int interface;
};

/* A GPIO line by chip and line name; values at the HAL are physical. */
struct rig_gpio_id {
	const char *chip;	/* e.g. "gpiochip0" */
	const char *line;	/* line name, e.g. "LAMP_EN" */
	int output;
	int initial;		/* physical level driven from the request on */
};

struct rig_hal_ops {
	const char *name;
	int (*usb_open)(void *self, const struct rig_usb_id *id, void **dev);
	int (*usb_control)(void *self, void *dev, uint8_t type, uint8_t req,
			   uint16_t value, uint16_t index,
			   unsigned timeout_ms);
	int (*usb_write)(void *self, void *dev, uint8_t ep,
			 const uint8_t *buf, size_t len, unsigned timeout_ms);
	int (*usb_read)(void *self, void *dev, uint8_t ep, uint8_t *buf,
			size_t cap, size_t *got, unsigned timeout_ms);
	void (*usb_close)(void *self, void *dev);
	int (*hid_open)(void *self, uint16_t vid, uint16_t pid,
			const char *serial, void **dev);
	int (*hid_write)(void *self, void *dev, const uint8_t *buf,
			 size_t len);
	int (*hid_read)(void *self, void *dev, uint8_t *buf, size_t cap,
			size_t *got, unsigned timeout_ms);
	void (*hid_close)(void *self, void *dev);
	int (*gpio_open)(void *self, const struct rig_gpio_id *id,
			 void **dev);
	int (*gpio_set)(void *self, void *dev, int value);
	int (*gpio_get)(void *self, void *dev, int *value);
	void (*gpio_close)(void *self, void *dev);
	double (*clock_now)(void *self);	/* seconds, monotonic */
	void (*clock_sleep)(void *self, double s);
	/* UTC, s since 1970 (NULL: the system's CLOCK_REALTIME); the
	 * simulator adds its virtual time to the wall clock */
	double (*clock_utc)(void *self);
};

/* A backend: its ops and its state. */
struct rig_hal {
	const struct rig_hal_ops *ops;
	void *self;
};

/* An open device on some backend. */
struct rig_hal_dev {
	const struct rig_hal *hal;
	void *dev;		/* NULL when closed */
};

/* All return enum rig_status; a read that times out returns ETIMEOUT. */
int rig_hal_usb_open(const struct rig_hal *hal, const struct rig_usb_id *id,
		     struct rig_hal_dev *d);
int rig_hal_usb_control(struct rig_hal_dev *d, uint8_t type, uint8_t req,
			uint16_t value, uint16_t index, unsigned timeout_ms);
int rig_hal_usb_write(struct rig_hal_dev *d, uint8_t ep, const uint8_t *buf,
		      size_t len, unsigned timeout_ms);
int rig_hal_usb_read(struct rig_hal_dev *d, uint8_t ep, uint8_t *buf,
		     size_t cap, size_t *got, unsigned timeout_ms);
void rig_hal_usb_close(struct rig_hal_dev *d);

int rig_hal_hid_open(const struct rig_hal *hal, uint16_t vid, uint16_t pid,
		     const char *serial, struct rig_hal_dev *d);
int rig_hal_hid_write(struct rig_hal_dev *d, const uint8_t *buf, size_t len);
int rig_hal_hid_read(struct rig_hal_dev *d, uint8_t *buf, size_t cap,
		     size_t *got, unsigned timeout_ms);
void rig_hal_hid_close(struct rig_hal_dev *d);

int rig_hal_gpio_open(const struct rig_hal *hal, const struct rig_gpio_id *id,
		      struct rig_hal_dev *d);
int rig_hal_gpio_set(struct rig_hal_dev *d, int value);
int rig_hal_gpio_get(struct rig_hal_dev *d, int *value);
void rig_hal_gpio_close(struct rig_hal_dev *d);

double rig_hal_now(const struct rig_hal *hal);
void rig_hal_sleep(const struct rig_hal *hal, double s);
/* UTC in s since 1970 through the backend (frames' DATE-OBS). */
double rig_hal_utc(const struct rig_hal *hal);
/* The system's UTC as 2026-12-02T04:50:00.123Z (the event log). */
#include <stddef.h>
void rig_utc_stamp(char *out, size_t size);

/* The real backend: libusb, hidapi, libgpiod and the monotonic clock. */
int rig_hal_real_init(struct rig_hal *hal);
void rig_hal_real_fini(struct rig_hal *hal);

#endif /* RIG_HAL_H */
