/*
 * devices.c - the names of enum rig_device, as the config file spells
 * them.
 */
#include "rig/devices.h"

const char *const rig_device_names[RIG_DEV_COUNT] = {
	[RIG_DEV_STAGE] = "stage",
	[RIG_DEV_WHEEL] = "wheel",
	[RIG_DEV_CAMERA] = "camera",
	[RIG_DEV_MONITOR] = "monitor",
	[RIG_DEV_GPIO] = "gpio",
};
