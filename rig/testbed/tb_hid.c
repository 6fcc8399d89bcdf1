/*
 * tb_hid.c - rig-testbed: hidraw nodes (report descriptor, numbered
 * reports written and read).
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

int tb_hid_ioctl(struct node *n, unsigned long req,
		 UMockdevIoctlData *arg)
{
	UMockdevIoctlData *d = NULL;
	int rc = 0;

	if (n->gone)
		return -ENODEV;
	if (req == HIDIOCGRDESCSIZE) {
		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(int), NULL);
		*(int *)d->data = (int)tb_rdesc_len();
	} else if (req == HIDIOCGRDESC) {
		struct hidraw_report_descriptor *rd;

		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(*rd), NULL);
		rd = (struct hidraw_report_descriptor *)d->data;
		rd->size = tb_rdesc_len();
		memcpy(rd->value, tb_rdesc(n), tb_rdesc_len());
	} else if (req == HIDIOCGRAWINFO) {
		struct hidraw_devinfo *di;

		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(*di), NULL);
		di = (struct hidraw_devinfo *)d->data;
		di->bustype = 3;
		di->vendor = (__s16)n->vid;
		di->product = (__s16)n->pid;
	} else {
		rc = -ENOTTY;
	}
	if (d)
		g_object_unref(d);
	return rc;
}

gssize tb_hid_write(struct node *n, UMockdevIoctlData *arg)
{
	int rc;

	if (n->gone)
		return -ENODEV;
	if (arg->data_len != 8 || arg->data[0] != tb_out_id(n))
		tb_violation(n, "output report of %d bytes with id 0x%02x; the "
			     "descriptor has 7-byte report 0x%02x (id first)",
			     arg->data_len, arg->data_len ? arg->data[0] : 0,
			     tb_out_id(n));
	rc = tb_hal.ops->hid_write(tb_hal.self, n->sim, arg->data,
				(size_t)arg->data_len);
	if (rc == RIG_EDISCONNECT) {
		tb_unplug(n);
		return -ENODEV;
	}
	return arg->data_len;
}

gssize tb_hid_read(struct node *n, UMockdevIoctlData *arg)
{
	size_t got = 0;
	int rc;

	if (n->gone)
		return -ENODEV;
	rc = tb_hal.ops->hid_read(tb_hal.self, n->sim, arg->data,
			       (size_t)arg->data_len, &got, 0);
	if (rc == RIG_ETIMEOUT)
		return -EAGAIN;
	if (rc != RIG_OK) {
		tb_unplug(n);
		return -ENODEV;
	}
	return (gssize)got;
}
