/*
 * hal_usb.c - USB transfers through the backend's ops table.
 */
#include "rig/hal.h"
#include "rig/status.h"

int rig_hal_usb_open(const struct rig_hal *hal, const struct rig_usb_id *id,
		     struct rig_hal_dev *d)
{
	d->hal = hal;
	d->dev = NULL;
	return hal->ops->usb_open(hal->self, id, &d->dev);
}

int rig_hal_usb_control(struct rig_hal_dev *d, uint8_t type, uint8_t req,
			uint16_t value, uint16_t index, unsigned timeout_ms)
{
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->usb_control(d->hal->self, d->dev, type, req, value,
					index, timeout_ms);
}

int rig_hal_usb_write(struct rig_hal_dev *d, uint8_t ep, const uint8_t *buf,
		      size_t len, unsigned timeout_ms)
{
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->usb_write(d->hal->self, d->dev, ep, buf, len,
				      timeout_ms);
}

int rig_hal_usb_read(struct rig_hal_dev *d, uint8_t ep, uint8_t *buf,
		     size_t cap, size_t *got, unsigned timeout_ms)
{
	*got = 0;
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->usb_read(d->hal->self, d->dev, ep, buf, cap, got,
				     timeout_ms);
}

void rig_hal_usb_close(struct rig_hal_dev *d)
{
	if (d->dev)
		d->hal->ops->usb_close(d->hal->self, d->dev);
	d->dev = NULL;
}
