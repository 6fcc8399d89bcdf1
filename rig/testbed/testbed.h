/*
 * testbed.h - what the test bed (rig-testbed) and its preload shim
 * (rig-testbed-shim.so) share: the clock node and its ioctls.
 *
 * The shim turns the host's nanosleep into RIGTB_SLEEP on /dev/rigtb-clock,
 * so the device side's virtual clock moves exactly as under the simulated
 * HAL (where rig_hal_sleep advances it), and hands the kernel's job of
 * creating a GPIO line-handle fd to RIGTB_BIND_HANDLE (umockdev cannot
 * create a file descriptor in the client).
 */
#ifndef RIG_TESTBED_H
#define RIG_TESTBED_H

#include <linux/ioctl.h>
#include <stdint.h>

#define RIGTB_CLOCK_NODE "/dev/rigtb-clock"
#define RIGTB_SLEEP _IOW('R', 0x71, uint64_t)	/* nanoseconds */
#define RIGTB_BIND_HANDLE _IOW('R', 0x72, int32_t)	/* handle token */
#define RIGTB_TOKEN_BASE 0x40000000	/* tokens the chip hands back */

#endif /* RIG_TESTBED_H */
