/*
 * indi_hal.c - the HAL of an INDI lab (indi.h): only a clock, the
 * monotonic one and the system's UTC; every device is behind indiserver.
 */
#include <time.h>

#include "rig/indi.h"

static double clk_now(void *self)
{
	struct timespec ts;

	(void)self;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void clk_sleep(void *self, double s)
{
	struct timespec ts;

	(void)self;
	ts.tv_sec = (time_t)s;
	ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
	while (nanosleep(&ts, &ts) != 0)
		;
}

static const struct rig_hal_ops clock_ops = {
	.name = "indi",
	.clock_now = clk_now,
	.clock_sleep = clk_sleep,
};

void rig_hal_indi_init(struct rig_hal *hal)
{
	hal->ops = &clock_ops;
	hal->self = NULL;
}
