/*
 * testbed.c - rig-testbed: runs a command with the lab's devices
 * emulated under umockdev, their far side being the simulators.
 *
 *   rig-testbed --config RIG.json [--log FILE] -- COMMAND [ARG...]
 *
 * The devices are the ones RIG.json names, presented as the kernel
 * presents them (sysfs, udev properties, device nodes):
 *   stage   USB device (FTDI FT232R bridge, ftdi_sio bound) on
 *           /dev/bus/usb/001/002: usbdevfs URBs, FTDI vendor requests;
 *   camera  USB device on /dev/bus/usb/001/003: usbdevfs bulk URBs;
 *   wheel   hidraw node under a USB HID interface, numbered reports;
 *   monitor hidraw node, likewise (when enabled);
 *   gpio    one gpiochip character device per chip named, GPIO uAPI v1
 *           (the ioctls libgpiod 1.6 issues).
 * Each ioctl, read and write is answered by handing the bytes to the
 * simulator backend's own ops table (rig/sim/sim.c), the code that
 * answers the simulated HAL: one device model serves both paths.
 *
 * RIGTB_SLEEP answers the number of devices plugged back, so the shim
 * gives the host's hotplug thread time to see them.
 *
 * Faults of the simulator's schedule become what the kernel shows: a
 * disconnect removes the device (sysfs, node, "remove" uevent; URBs
 * complete with -ESHUTDOWN, then -ENODEV) and it is plugged back ("add"
 * uevent) when the host next sleeps and the schedule lets it re-open; a
 * timeout is a URB that never completes (libusb discards it); a CRC
 * fault is a corrupted frame on the wire.
 *
 * The test bed also checks the host side against the protocols (FTDI
 * set-up per the APT documentation, endpoints, kernel driver detach and
 * re-attach, HID report ids, GPIO request flags and initial levels);
 * each violation is one line on stderr and the exit status is 3.
 * Otherwise it exits with the command's status.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <glib.h>
#include <linux/gpio.h>
#include <linux/hidraw.h>
#include <linux/usbdevice_fs.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <umockdev.h>
#include <unistd.h>

#include "rig/config.h"
#include "rig/framelink.h"
#include "rig/monitor_report.h"
#include "rig/sim.h"
#include "rig/status.h"
#include "rig/wheel_report.h"
#include "testbed.h"
#include "tb.h"

/* ---- setting up ---- */
static struct node *add_node(enum node_kind kind, int dev, const char *what)
{
	struct node *n = &tb_nodes[tb_n_nodes++];
	int i;

	memset(n, 0, sizeof(*n));
	n->kind = kind;
	n->dev = dev;
	n->what = what;
	for (i = 0; i < GPIO_LINES; i++)
		n->line_at[i] = -1;
	return n;
}

static void build_lab(void)
{
	struct node *n;
	int i, j;

	n = add_node(N_USB, RIG_DEV_STAGE, "stage");
	g_strlcpy(n->name, "1-2", sizeof(n->name));
	g_strlcpy(n->devnode, "/dev/bus/usb/001/002", sizeof(n->devnode));
	n->serial = tb_cfg.stage.serial[0] ? tb_cfg.stage.serial : "83000001";
	n->vid = tb_cfg.stage.usb.vid;
	n->pid = tb_cfg.stage.usb.pid;
	n->eps[0] = 0x81;
	n->eps[1] = 0x02;
	n->n_eps = 2;
	n->ep_max_packet = 64;
	n->driver0 = "ftdi_sio";
	n = add_node(N_USB, RIG_DEV_CAMERA, "camera");
	g_strlcpy(n->name, "1-3", sizeof(n->name));
	g_strlcpy(n->devnode, "/dev/bus/usb/001/003", sizeof(n->devnode));
	n->serial = tb_cfg.camera.serial[0] ? tb_cfg.camera.serial : "CAM0001";
	n->vid = tb_cfg.camera.usb.vid;
	n->pid = tb_cfg.camera.usb.pid;
	n->eps[0] = RIG_FL_EP_CMD;
	n->eps[1] = RIG_FL_EP_DATA;
	n->n_eps = 2;
	n->ep_max_packet = 512;
	n = add_node(N_HID, RIG_DEV_WHEEL, "wheel");
	g_strlcpy(n->name, "hidraw0", sizeof(n->name));
	g_strlcpy(n->devnode, "/dev/hidraw0", sizeof(n->devnode));
	n->serial = tb_cfg.wheel.serial[0] ? tb_cfg.wheel.serial : "ND0001";
	n->vid = tb_cfg.wheel.vid;
	n->pid = tb_cfg.wheel.pid;
	if (tb_cfg.monitor.enabled) {
		n = add_node(N_HID, RIG_DEV_MONITOR, "monitor");
		g_strlcpy(n->name, "hidraw1", sizeof(n->name));
		g_strlcpy(n->devnode, "/dev/hidraw1", sizeof(n->devnode));
		n->serial = tb_cfg.monitor.serial[0] ? tb_cfg.monitor.serial
						   : "MON0001";
		n->vid = tb_cfg.monitor.vid;
		n->pid = tb_cfg.monitor.pid;
	}
	/* One chip per chip name; lines at offsets 2, 3, 4, ... */
	for (i = 0; i < RIG_LINE_COUNT; i++) {
		struct node *chip = NULL;

		for (j = 0; j < tb_n_nodes; j++)
			if (tb_nodes[j].kind == N_GPIO &&
			    !strcmp(tb_nodes[j].chip, tb_cfg.lines[i].chip))
				chip = &tb_nodes[j];
		if (!chip) {
			chip = add_node(N_GPIO, RIG_DEV_GPIO, "gpio");
			g_strlcpy(chip->chip, tb_cfg.lines[i].chip,
				  sizeof(chip->chip));
			g_strlcpy(chip->name, tb_cfg.lines[i].chip,
				  sizeof(chip->name));
			snprintf(chip->devnode, sizeof(chip->devnode),
				 "/dev/%s", tb_cfg.lines[i].chip);
		}
		chip->line_at[2 + i] = i;
	}
	n = add_node(N_CLOCK, -1, "clock");
	g_strlcpy(n->devnode, RIGTB_CLOCK_NODE, sizeof(n->devnode));
	tb_put_file(n->devnode + 1, "", 0);
	for (i = 0; i < tb_n_nodes; i++)
		if (tb_nodes[i].kind != N_CLOCK)
			tb_plug(&tb_nodes[i]);
}

static void summary(int status)
{
	int i;

	for (i = 0; i < tb_n_nodes; i++)
		if (tb_nodes[i].driver0)
			tb_note("%s: kernel driver detached %d, re-attached %d",
				tb_nodes[i].what, tb_nodes[i].detached,
				tb_nodes[i].reattached);
	tb_note("command exit %d; %u protocol violations, %u disconnects, %u "
		"re-plugs, %u URBs never completed, %u faults fired", status,
		tb_violations, tb_n_disconnects, tb_n_replugs, tb_n_timeouts,
		rig_sim_faults_fired(&tb_sim));
}

int main(int argc, char **argv)
{
	const char *config = NULL, *logpath = NULL;
	struct rig_error err;
	char preload[4096];
	const char *shim, *old;
	int i, status;
	pid_t pid;

	for (i = 1; i < argc && strcmp(argv[i], "--"); i++) {
		if (!strcmp(argv[i], "--config") && i + 1 < argc)
			config = argv[++i];
		else if (!strcmp(argv[i], "--log") && i + 1 < argc)
			logpath = argv[++i];
		else
			break;
	}
	if (!config || i >= argc - 1 || strcmp(argv[i], "--")) {
		fprintf(stderr, "usage: rig-testbed --config RIG.json "
			"[--log FILE] -- COMMAND [ARG...]\n");
		return 2;
	}
	rig_error_clear(&err);
	rig_config_defaults(&tb_cfg);
	if (rig_config_load(&tb_cfg, config, &err) != RIG_OK) {
		fprintf(stderr, "rig-testbed: %s\n", err.msg);
		return 2;
	}
	for (i = 0; i < tb_cfg.sim.n_faults; i++)
		if (tb_cfg.sim.faults[i].kind == RIG_FAULT_KILL) {
			fprintf(stderr, "rig-testbed: %s: sim.faults[%d]: kind "
				"'kill' cannot run under the test bed (the "
				"device side would kill the test bed, not the "
				"daemon)\n", config, i);
			return 2;
		}
	tb_logf = logpath ? fopen(logpath, "w") : stderr;
	shim = getenv("RIG_TESTBED_SHIM");
	if (!shim) {
		fprintf(stderr, "rig-testbed: RIG_TESTBED_SHIM (the path of "
			"rig-testbed-shim.so) is not set\n");
		return 2;
	}
	rig_sim_init(&tb_sim, &tb_cfg, &tb_hal);
	tb_mock = umockdev_testbed_new();
	build_lab();
	for (i = 0; i < tb_n_nodes; i++)
		if (tb_attach(&tb_nodes[i]) != 0)
			return 2;
	old = getenv("LD_PRELOAD");
	if (old && strstr(old, "libumockdev-preload"))
		snprintf(preload, sizeof(preload), "%s:%s", shim, old);
	else
		snprintf(preload, sizeof(preload),
			 "%s:libumockdev-preload.so.0%s%s", shim,
			 old ? ":" : "", old ? old : "");
	pid = fork();
	if (pid == 0) {
		setenv("LD_PRELOAD", preload, 1);
		while (strcmp(argv[0], "--"))
			argv++;
		execvp(argv[1], argv + 1);
		fprintf(stderr, "rig-testbed: %s: %s\n", argv[1],
			strerror(errno));
		_exit(127);
	}
	while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
		;
	status = WIFEXITED(status) ? WEXITSTATUS(status)
				   : 128 + WTERMSIG(status);
	summary(status);
	if (tb_violations)
		return 3;
	return status;
}
