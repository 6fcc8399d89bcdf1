/*
 * hal_clock.c - time through the backend, so simulators run on a virtual
 * clock and tests never really sleep.
 */
#include "rig/hal.h"

double rig_hal_now(const struct rig_hal *hal)
{
	return hal->ops->clock_now(hal->self);
}

void rig_hal_sleep(const struct rig_hal *hal, double s)
{
	if (s > 0)
		hal->ops->clock_sleep(hal->self, s);
}
