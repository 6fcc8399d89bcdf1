/*
 * backend_hidapi.c - HID ops of the real backend, on hidapi (libusb
 * flavour).  Reports carry their report id in byte 0, as hid_write and
 * hid_read_timeout expect.
 */
#include <hidapi.h>
#include <stdlib.h>
#include <wchar.h>

#include "backend.h"
#include "rig/status.h"

int rig_real_hid_open(void *self, uint16_t vid, uint16_t pid, const char *serial,
		  void **dev)
{
	wchar_t wserial[64];
	hid_device *h;

	(void)self;
	if (serial && mbstowcs(wserial, serial, 63) == (size_t)-1)
		return RIG_EINVAL;
	wserial[63] = L'\0';
	h = hid_open(vid, pid, serial ? wserial : NULL);
	if (!h)
		return RIG_EDISCONNECT;
	*dev = h;
	return RIG_OK;
}

int rig_real_hid_write(void *self, void *dev, const uint8_t *buf, size_t len)
{
	(void)self;
	return hid_write(dev, buf, len) == (int)len ? RIG_OK
						     : RIG_EDISCONNECT;
}

int rig_real_hid_read(void *self, void *dev, uint8_t *buf, size_t cap,
		  size_t *got, unsigned timeout_ms)
{
	int n;

	(void)self;
	n = hid_read_timeout(dev, buf, cap, (int)timeout_ms);
	if (n < 0)
		return RIG_EDISCONNECT;
	*got = (size_t)n;
	return n == 0 ? RIG_ETIMEOUT : RIG_OK;
}

void rig_real_hid_close(void *self, void *dev)
{
	(void)self;
	hid_close(dev);
}
