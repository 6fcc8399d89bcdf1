/*
 * hal_gpio.c - GPIO lines through the backend's ops table.
 */
#include "rig/hal.h"
#include "rig/status.h"

int rig_hal_gpio_open(const struct rig_hal *hal, const struct rig_gpio_id *id,
		      struct rig_hal_dev *d)
{
	d->hal = hal;
	d->dev = NULL;
	return hal->ops->gpio_open(hal->self, id, &d->dev);
}

int rig_hal_gpio_set(struct rig_hal_dev *d, int value)
{
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->gpio_set(d->hal->self, d->dev, value);
}

int rig_hal_gpio_get(struct rig_hal_dev *d, int *value)
{
	if (!d->dev)
		return RIG_EDISCONNECT;
	return d->hal->ops->gpio_get(d->hal->self, d->dev, value);
}

void rig_hal_gpio_close(struct rig_hal_dev *d)
{
	if (d->dev)
		d->hal->ops->gpio_close(d->hal->self, d->dev);
	d->dev = NULL;
}
