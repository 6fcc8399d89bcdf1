/*
 * hal_clock.c - time through the backend, so simulators run on a virtual
 * clock and tests never really sleep.
 */
#include <time.h>

#include "rig/hal.h"
#include "stray/sweep_store.h"

static double wall_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_REALTIME, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

double rig_hal_utc(const struct rig_hal *hal)
{
	return hal->ops->clock_utc ? hal->ops->clock_utc(hal->self)
				   : wall_now();
}

void rig_utc_stamp(char *out, size_t size)
{
	stray_sweep_utc_format(wall_now(), out, size);
}

double rig_hal_now(const struct rig_hal *hal)
{
	return hal->ops->clock_now(hal->self);
}

void rig_hal_sleep(const struct rig_hal *hal, double s)
{
	if (s > 0)
		hal->ops->clock_sleep(hal->self, s);
}
