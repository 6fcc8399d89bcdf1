/*
 * backend.h - private: the pieces of the real backend's ops table, one
 * file per device library.
 */
#ifndef RIG_BACKEND_H
#define RIG_BACKEND_H

#include <libusb.h>

#include "rig/hal.h"

struct real_backend {
	libusb_context *usb;
};

int rig_real_usb_open(void *self, const struct rig_usb_id *id, void **dev);
int rig_real_usb_control(void *self, void *dev, uint8_t type, uint8_t req,
		     uint16_t value, uint16_t index, unsigned timeout_ms);
int rig_real_usb_write(void *self, void *dev, uint8_t ep, const uint8_t *buf,
		   size_t len, unsigned timeout_ms);
int rig_real_usb_read(void *self, void *dev, uint8_t ep, uint8_t *buf, size_t cap,
		  size_t *got, unsigned timeout_ms);
void rig_real_usb_close(void *self, void *dev);

int rig_real_hid_open(void *self, uint16_t vid, uint16_t pid, const char *serial,
		  void **dev);
int rig_real_hid_write(void *self, void *dev, const uint8_t *buf, size_t len);
int rig_real_hid_read(void *self, void *dev, uint8_t *buf, size_t cap,
		  size_t *got, unsigned timeout_ms);
void rig_real_hid_close(void *self, void *dev);

int rig_real_gpio_open(void *self, const struct rig_gpio_id *id, void **dev);
int rig_real_gpio_set(void *self, void *dev, int value);
int rig_real_gpio_get(void *self, void *dev, int *value);
void rig_real_gpio_close(void *self, void *dev);

#endif /* RIG_BACKEND_H */
