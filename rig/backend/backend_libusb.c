/*
 * backend_libusb.c - USB ops of the real backend, on libusb-1.0.
 *
 * Opens the first device matching vid/pid (and serial, when given),
 * detaches a kernel driver (ftdi_sio would hold the APT controller) and
 * claims the interface.  LIBUSB_ERROR_NO_DEVICE maps to EDISCONNECT and
 * LIBUSB_ERROR_TIMEOUT to ETIMEOUT, the codes the simulator returns too.
 */
#include <libusb.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "rig/status.h"

struct usb_dev {
	libusb_device_handle *h;
	int interface;
};

static int map_usb_error(int rc)
{
	switch (rc) {
	case LIBUSB_SUCCESS:
		return RIG_OK;
	case LIBUSB_ERROR_TIMEOUT:
		return RIG_ETIMEOUT;
	case LIBUSB_ERROR_NO_DEVICE:
	case LIBUSB_ERROR_NOT_FOUND:
		return RIG_EDISCONNECT;
	case LIBUSB_ERROR_NO_MEM:
		return RIG_ENOMEM;
	default:
		return RIG_EIO;
	}
}

static int serial_matches(libusb_device_handle *h, uint8_t index,
			  const char *serial)
{
	unsigned char buf[128];
	int n;

	if (!serial)
		return 1;
	n = libusb_get_string_descriptor_ascii(h, index, buf, sizeof(buf) - 1);
	if (n < 0)
		return 0;
	buf[n] = '\0';
	return strcmp((const char *)buf, serial) == 0;
}

static libusb_device_handle *find_device(libusb_context *ctx,
					 const struct rig_usb_id *id)
{
	libusb_device **list;
	libusb_device_handle *found = NULL;
	ssize_t n, i;

	n = libusb_get_device_list(ctx, &list);
	for (i = 0; i < n && !found; i++) {
		struct libusb_device_descriptor dd;
		libusb_device_handle *h;

		if (libusb_get_device_descriptor(list[i], &dd) != 0 ||
		    dd.idVendor != id->vid || dd.idProduct != id->pid)
			continue;
		if (libusb_open(list[i], &h) != 0)
			continue;
		if (serial_matches(h, dd.iSerialNumber, id->serial))
			found = h;
		else
			libusb_close(h);
	}
	if (n >= 0)
		libusb_free_device_list(list, 1);
	return found;
}

int rig_real_usb_open(void *self, const struct rig_usb_id *id, void **dev)
{
	struct real_backend *rb = self;
	struct usb_dev *u;
	libusb_device_handle *h;
	int rc;

	h = find_device(rb->usb, id);
	if (!h)
		return RIG_EDISCONNECT;
	libusb_set_auto_detach_kernel_driver(h, 1);
	rc = libusb_claim_interface(h, id->interface);
	if (rc != 0) {
		libusb_close(h);
		return map_usb_error(rc);
	}
	u = calloc(1, sizeof(*u));
	if (!u) {
		libusb_release_interface(h, id->interface);
		libusb_close(h);
		return RIG_ENOMEM;
	}
	u->h = h;
	u->interface = id->interface;
	*dev = u;
	return RIG_OK;
}

int rig_real_usb_control(void *self, void *dev, uint8_t type, uint8_t req,
		     uint16_t value, uint16_t index, unsigned timeout_ms)
{
	struct usb_dev *u = dev;
	int rc;

	(void)self;
	rc = libusb_control_transfer(u->h, type, req, value, index, NULL, 0,
				     timeout_ms);
	return rc < 0 ? map_usb_error(rc) : RIG_OK;
}

int rig_real_usb_write(void *self, void *dev, uint8_t ep, const uint8_t *buf,
		   size_t len, unsigned timeout_ms)
{
	struct usb_dev *u = dev;
	int done = 0, rc;

	(void)self;
	rc = libusb_bulk_transfer(u->h, ep, (unsigned char *)buf, (int)len,
				  &done, timeout_ms);
	if (rc == 0 && (size_t)done != len)
		return RIG_ETIMEOUT;
	return map_usb_error(rc);
}

int rig_real_usb_read(void *self, void *dev, uint8_t ep, uint8_t *buf, size_t cap,
		  size_t *got, unsigned timeout_ms)
{
	struct usb_dev *u = dev;
	int done = 0, rc;

	(void)self;
	rc = libusb_bulk_transfer(u->h, ep, buf, (int)cap, &done, timeout_ms);
	*got = done > 0 ? (size_t)done : 0;
	if (rc == LIBUSB_ERROR_TIMEOUT && done > 0)
		return RIG_OK;
	return map_usb_error(rc);
}

void rig_real_usb_close(void *self, void *dev)
{
	struct usb_dev *u = dev;

	(void)self;
	libusb_release_interface(u->h, u->interface);
	libusb_close(u->h);
	free(u);
}
