/*
 * tb_plug.c - rig-testbed: devices plugged in and out as the kernel shows
 * them (sysfs, udev properties, device nodes, uevents), and the
 * simulator's side opened and the host's sleeps answered.
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

void tb_put_file(const char *rel, const void *data, size_t len)
{
	char *root = umockdev_testbed_get_root_dir(tb_mock);
	char *path = g_build_filename(root, rel, NULL);
	char *dir = g_path_get_dirname(path);

	g_mkdir_with_parents(dir, 0755);
	g_file_set_contents(path, data, (gssize)len, NULL);
	g_free(dir);
	g_free(path);
	g_free(root);
}

/* USB descriptors: device, one configuration, one interface, eps. */
static size_t usb_descriptors(const struct node *n, uint8_t cls,
			      uint8_t *d)
{
	size_t len = 18 + 9 + 9 + 7 * (size_t)n->n_eps, at;
	int i;
	uint8_t dev[18] = { 18, 1, 0x00, 0x02, 0, 0, 0, 64,
			    (uint8_t)n->vid, (uint8_t)(n->vid >> 8),
			    (uint8_t)n->pid, (uint8_t)(n->pid >> 8),
			    0x00, 0x06, 1, 2, 3, 1 };
	uint8_t conf[9] = { 9, 2, (uint8_t)(len - 18),
			    (uint8_t)((len - 18) >> 8), 1, 1, 0, 0x80, 50 };
	uint8_t intf[9] = { 9, 4, 0, 0, (uint8_t)n->n_eps, cls,
			    cls == 3 ? 0 : 0xff, cls == 3 ? 0 : 0xff, 0 };

	memcpy(d, dev, 18);
	memcpy(d + 18, conf, 9);
	memcpy(d + 27, intf, 9);
	at = 36;
	for (i = 0; i < n->n_eps; i++, at += 7) {
		uint8_t e[7] = { 7, 5, n->eps[i], cls == 3 ? 3 : 2,
				 (uint8_t)n->ep_max_packet,
				 (uint8_t)(n->ep_max_packet >> 8),
				 cls == 3 ? 1 : 0 };

		memcpy(d + at, e, 7);
	}
	return len;
}

static void plug_usb(struct node *n)
{
	uint8_t desc[128];
	char vid[8], pid[8], devnum[8];
	size_t len = usb_descriptors(n, 0xff, desc);
	char *sp;

	snprintf(vid, sizeof(vid), "%04x", n->vid);
	snprintf(pid, sizeof(pid), "%04x", n->pid);
	snprintf(devnum, sizeof(devnum), "%d",
		 atoi(strrchr(n->devnode, '/') + 1));
	sp = umockdev_testbed_add_device(tb_mock, "usb", n->name, NULL,
		"idVendor", vid, "idProduct", pid, "busnum", "1",
		"devnum", devnum, "speed", "480", "bConfigurationValue", "1",
		"bNumConfigurations", "1", "manufacturer", "straylight",
		"serial", n->serial,
		"product", n->what, "dev", n->dev == RIG_DEV_STAGE ? "189:1\n"
								  : "189:2\n",
		NULL, "DEVTYPE", "usb_device", "DEVNAME", n->devnode,
		"ID_VENDOR_ID", vid, "ID_MODEL_ID", pid, NULL);
	g_strlcpy(n->syspath, sp, sizeof(n->syspath));
	umockdev_testbed_set_attribute_binary(tb_mock, sp, "descriptors",
					      desc, (gssize)len);
	g_free(sp);
	tb_put_file(n->devnode + 1, "", 0);
	n->driver = n->driver0;
	n->claimed = 0;
	n->n_urbs = 0;
}

/* HID report descriptors: vendor page, one numbered 7-byte output and
 * one input report (wheel_report.h 0x01/0x02, monitor_report.h
 * 0x04/0x05); the id is byte 0 of each report on hidraw. */
#define HID_RDESC(out_id, in_id) {					\
	0x06, 0x00, 0xff, 0x09, 0x01, 0xa1, 0x01,			\
	0x85, out_id, 0x09, 0x02, 0x15, 0x00, 0x26, 0xff, 0x00, 0x75, 0x08, \
	0x95, 0x07, 0x91, 0x02,						\
	0x85, in_id, 0x09, 0x03, 0x15, 0x00, 0x26, 0xff, 0x00, 0x75, 0x08, \
	0x95, 0x07, 0x81, 0x02, 0xc0 }
static const uint8_t rdesc_wheel[] = HID_RDESC(RIG_WHEEL_OUT_ID,
					       RIG_WHEEL_IN_ID);
static const uint8_t rdesc_monitor[] = HID_RDESC(RIG_MONITOR_OUT_ID,
						 RIG_MONITOR_IN_ID);
#define RDESC_LEN sizeof(rdesc_wheel)

size_t tb_rdesc_len(void)
{
	return RDESC_LEN;
}

const uint8_t *tb_rdesc(const struct node *n)
{
	return n->dev == RIG_DEV_WHEEL ? rdesc_wheel : rdesc_monitor;
}

uint8_t tb_out_id(const struct node *n)
{
	return n->dev == RIG_DEV_WHEEL ? RIG_WHEEL_OUT_ID : RIG_MONITOR_OUT_ID;
}


/* SYSPATH/device -> its parent, as the kernel links a class device. */
static void device_link(const char *syspath)
{
	char *root = umockdev_testbed_get_root_dir(tb_mock);
	char *link = g_build_filename(root, syspath, "device", NULL);

	if (symlink("..", link) != 0)
		tb_note("%s: cannot link: %s", link, strerror(errno));
	g_free(link);
	g_free(root);
}

static void plug_hid(struct node *n)
{
	char vid[8], pid[8], hid_id[40], hid_name[48], usbname[32], ifname[40],
	     hidname[48];
	char *usb, *intf, *hid, *raw;

	snprintf(vid, sizeof(vid), "%04x", n->vid);
	snprintf(pid, sizeof(pid), "%04x", n->pid);
	snprintf(usbname, sizeof(usbname), "1-%d", n->dev + 4);
	snprintf(ifname, sizeof(ifname), "%s:1.0", usbname);
	snprintf(hidname, sizeof(hidname), "0003:%04X:%04X.%04d", n->vid,
		 n->pid, n->dev);
	snprintf(hid_id, sizeof(hid_id), "0003:%08X:%08X", n->vid, n->pid);
	snprintf(hid_name, sizeof(hid_name), "straylight %s", n->what);
	usb = umockdev_testbed_add_device(tb_mock, "usb", usbname, NULL,
		"idVendor", vid, "idProduct", pid, "manufacturer",
		"straylight", "product", n->what, "bcdDevice", "0100",
		"busnum", "1", NULL, "DEVTYPE", "usb_device", NULL);
	intf = umockdev_testbed_add_device(tb_mock, "usb", ifname, usb,
		"bInterfaceNumber", "00", "bInterfaceClass", "03", NULL,
		"DEVTYPE", "usb_interface", NULL);
	hid = umockdev_testbed_add_device(tb_mock, "hid", hidname, intf, NULL,
		"HID_ID", hid_id, "HID_NAME", hid_name, "HID_UNIQ", n->serial,
		NULL);
	umockdev_testbed_set_attribute_binary(tb_mock, hid, "report_descriptor",
		(guint8 *)tb_rdesc(n), RDESC_LEN);
	raw = umockdev_testbed_add_device(tb_mock, "hidraw", n->name, hid,
		"dev", n->dev == RIG_DEV_WHEEL ? "240:0\n" : "240:1\n", NULL,
		"DEVNAME", n->devnode, NULL);
	g_strlcpy(n->syspath, usb, sizeof(n->syspath));
	g_strlcpy(n->sub[0], intf, sizeof(n->sub[0]));
	g_strlcpy(n->sub[1], hid, sizeof(n->sub[1]));
	g_strlcpy(n->sub[2], raw, sizeof(n->sub[2]));
	device_link(raw);
	tb_put_file(n->devnode + 1, "", 0);
	g_free(usb);
	g_free(intf);
	g_free(hid);
	g_free(raw);
}

static void plug_gpio(struct node *n, int minor)
{
	char dev[16];
	char *sp;

	snprintf(dev, sizeof(dev), "254:%d\n", minor);
	sp = umockdev_testbed_add_device(tb_mock, "gpio", n->name, NULL,
		"dev", dev, NULL, "DEVNAME", n->devnode, NULL);
	g_strlcpy(n->syspath, sp, sizeof(n->syspath));
	tb_put_file(n->devnode + 1, "", 0);
	g_free(sp);
}

void tb_plug(struct node *n)
{
	if (n->kind == N_USB)
		plug_usb(n);
	else if (n->kind == N_HID)
		plug_hid(n);
	else if (n->kind == N_GPIO)
		plug_gpio(n, (int)(n - tb_nodes));
	n->gone = 0;
}

void tb_unplug(struct node *n)
{
	int i;

	if (n->gone)
		return;
	n->gone = 1;
	tb_n_disconnects++;
	tb_note("%s: unplugged (remove uevent)", n->what);
	for (i = 2; n->kind == N_HID && i >= 0; i--) {
		umockdev_testbed_uevent(tb_mock, n->sub[i], "remove");
		umockdev_testbed_remove_device(tb_mock, n->sub[i]);
	}
	umockdev_testbed_uevent(tb_mock, n->syspath, "remove");
	umockdev_testbed_remove_device(tb_mock, n->syspath);
	for (i = 0; i < n->n_urbs; i++)
		if (!n->urbs[i].done) {
			n->urbs[i].done = 1;
			n->urbs[i].status = -ESHUTDOWN;
		}
}

/* Open the simulator's side of n, as the simulated HAL's open does. */
int tb_sim_open(struct node *n)
{
	struct rig_usb_id id = { n->vid, n->pid, NULL, 0 };

	if (n->kind == N_USB)
		return tb_hal.ops->usb_open(tb_hal.self, &id, &n->sim);
	if (n->kind == N_HID)
		return tb_hal.ops->hid_open(tb_hal.self, n->vid, n->pid, NULL,
					 &n->sim);
	return RIG_OK;
}

/* A host sleep: the virtual clock moves; unplugged devices come back
 * when the fault schedule lets them re-open. */
int tb_host_sleep(uint64_t ns)
{
	int i, replugged = 0;

	tb_hal.ops->clock_sleep(tb_hal.self, (double)ns * 1e-9);
	for (i = 0; i < tb_n_nodes; i++) {
		struct node *n = &tb_nodes[i];

		if (!n->gone ||
		    rig_sim_core_open(&tb_sim.core, n->dev) != RIG_OK)
			continue;
		tb_plug(n);
		umockdev_testbed_uevent(tb_mock, n->syspath, "add");
		if (n->kind == N_HID)
			umockdev_testbed_uevent(tb_mock, n->sub[2], "add");
		tb_n_replugs++;
		replugged++;
		tb_note("%s: plugged back (add uevent)", n->what);
	}
	return replugged;
}
