/*
 * hal_hid.c - HID reports through the backend's ops table.
 */
#include "rig/hal.h"
#include "rig/status.h"

int rig_hal_hid_open(const struct rig_hal *hal, uint16_t vid, uint16_t pid,
		     const char *serial, struct rig_hal_dev *d)
{
	d->hal = hal;
	d->dev = NULL;
	return hal->ops->hid_open(hal->self, vid, pid, serial, &d->dev);
}

int rig_hal_hid_write(struct rig_hal_dev *d, const uint8_t *buf, size_t len)
{
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->hid_write(d->hal->self, d->dev, buf, len);
}

int rig_hal_hid_read(struct rig_hal_dev *d, uint8_t *buf, size_t cap,
		     size_t *got, unsigned timeout_ms)
{
	*got = 0;
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->hid_read(d->hal->self, d->dev, buf, cap, got,
				     timeout_ms);
}

void rig_hal_hid_close(struct rig_hal_dev *d)
{
	if (d->dev)
		d->hal->ops->hid_close(d->hal->self, d->dev);
	d->dev = NULL;
}
