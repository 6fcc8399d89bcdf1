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

#define MAX_URBS 64
#define GPIO_LINES 8
#define MAX_HANDLES 32
#define USB_EP_MAX 4

/* ---- the test bed's state (touched only on umockdev's worker thread
 * once the command runs) ---- */
enum node_kind { N_USB, N_HID, N_GPIO, N_CLOCK };

struct urb {
	uint64_t addr;		/* the client's struct usbdevfs_urb */
	uint8_t ep, type;
	int len, status, actual, done;
	uint8_t *in;		/* IN data to deliver */
	int ctrl_in;		/* in[] starts with the 8 setup bytes */
};

struct node {
	enum node_kind kind;
	int dev;		/* enum rig_device */
	const char *what;
	const char *serial;	/* iSerialNumber, HID_UNIQ */
	char name[32];		/* sysfs name */
	char devnode[64];
	char syspath[256];
	char sub[3][256];	/* HID: interface, hid, hidraw below */
	uint16_t vid, pid;
	uint8_t eps[USB_EP_MAX];
	int n_eps, ep_max_packet;
	void *sim;		/* the simulator's device handle */
	int gone;
	/* USB */
	struct urb urbs[MAX_URBS];
	int n_urbs;
	const char *driver;	/* kernel driver bound now, or NULL */
	const char *driver0;	/* the one bound at plug-in */
	int claimed, detached, reattached;
	/* FTDI, as set by vendor requests */
	int ftdi_reset, ftdi_purge_rx, ftdi_purge_tx, ftdi_flow_rtscts,
	    ftdi_rts, ftdi_8n1, ftdi_latency_ms;
	double ftdi_baud;
	int ftdi_checked;
	/* GPIO: chip name, and the rig line at each offset (-1 none) */
	char chip[RIG_NAME_MAX];
	int line_at[GPIO_LINES];
};

struct handle {
	struct node *chip;
	int n, offsets[GPIOHANDLES_MAX];
	void *sim[GPIOHANDLES_MAX];
	uint32_t flags;
};

static struct rig_config cfg;
static struct rig_sim sim;
static struct rig_hal hal;
static UMockdevTestbed *tb;
static struct node nodes[16];
static int n_nodes;
static struct handle handles[MAX_HANDLES];
static int n_handles;
static unsigned violations, n_disconnects, n_timeouts, n_replugs;
static FILE *logf;

static void note(const char *fmt, ...) G_GNUC_PRINTF(1, 2);
static void note(const char *fmt, ...)
{
	va_list ap;

	if (!logf)
		return;
	va_start(ap, fmt);
	fputs("rig-testbed: ", logf);
	vfprintf(logf, fmt, ap);
	fputc('\n', logf);
	fflush(logf);
	va_end(ap);
}

static void violation(const struct node *n, const char *fmt, ...)
	G_GNUC_PRINTF(2, 3);
static void violation(const struct node *n, const char *fmt, ...)
{
	va_list ap;

	violations++;
	va_start(ap, fmt);
	fprintf(stderr, "rig-testbed: %s: ", n->what);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
}

/* ---- plugging devices in and out ---- */
static void put_file(const char *rel, const void *data, size_t len)
{
	char *root = umockdev_testbed_get_root_dir(tb);
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
	sp = umockdev_testbed_add_device(tb, "usb", n->name, NULL,
		"idVendor", vid, "idProduct", pid, "busnum", "1",
		"devnum", devnum, "speed", "480", "bConfigurationValue", "1",
		"bNumConfigurations", "1", "manufacturer", "straylight",
		"serial", n->serial,
		"product", n->what, "dev", n->dev == RIG_DEV_STAGE ? "189:1\n"
								  : "189:2\n",
		NULL, "DEVTYPE", "usb_device", "DEVNAME", n->devnode,
		"ID_VENDOR_ID", vid, "ID_MODEL_ID", pid, NULL);
	g_strlcpy(n->syspath, sp, sizeof(n->syspath));
	umockdev_testbed_set_attribute_binary(tb, sp, "descriptors",
					      desc, (gssize)len);
	g_free(sp);
	put_file(n->devnode + 1, "", 0);
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

static const uint8_t *rdesc(const struct node *n)
{
	return n->dev == RIG_DEV_WHEEL ? rdesc_wheel : rdesc_monitor;
}

static uint8_t out_id(const struct node *n)
{
	return n->dev == RIG_DEV_WHEEL ? RIG_WHEEL_OUT_ID : RIG_MONITOR_OUT_ID;
}


/* SYSPATH/device -> its parent, as the kernel links a class device. */
static void device_link(const char *syspath)
{
	char *root = umockdev_testbed_get_root_dir(tb);
	char *link = g_build_filename(root, syspath, "device", NULL);

	if (symlink("..", link) != 0)
		note("%s: cannot link: %s", link, strerror(errno));
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
	usb = umockdev_testbed_add_device(tb, "usb", usbname, NULL,
		"idVendor", vid, "idProduct", pid, "manufacturer",
		"straylight", "product", n->what, "bcdDevice", "0100",
		"busnum", "1", NULL, "DEVTYPE", "usb_device", NULL);
	intf = umockdev_testbed_add_device(tb, "usb", ifname, usb,
		"bInterfaceNumber", "00", "bInterfaceClass", "03", NULL,
		"DEVTYPE", "usb_interface", NULL);
	hid = umockdev_testbed_add_device(tb, "hid", hidname, intf, NULL,
		"HID_ID", hid_id, "HID_NAME", hid_name, "HID_UNIQ", n->serial,
		NULL);
	umockdev_testbed_set_attribute_binary(tb, hid, "report_descriptor",
		(guint8 *)rdesc(n), RDESC_LEN);
	raw = umockdev_testbed_add_device(tb, "hidraw", n->name, hid,
		"dev", n->dev == RIG_DEV_WHEEL ? "240:0\n" : "240:1\n", NULL,
		"DEVNAME", n->devnode, NULL);
	g_strlcpy(n->syspath, usb, sizeof(n->syspath));
	g_strlcpy(n->sub[0], intf, sizeof(n->sub[0]));
	g_strlcpy(n->sub[1], hid, sizeof(n->sub[1]));
	g_strlcpy(n->sub[2], raw, sizeof(n->sub[2]));
	device_link(raw);
	put_file(n->devnode + 1, "", 0);
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
	sp = umockdev_testbed_add_device(tb, "gpio", n->name, NULL,
		"dev", dev, NULL, "DEVNAME", n->devnode, NULL);
	g_strlcpy(n->syspath, sp, sizeof(n->syspath));
	put_file(n->devnode + 1, "", 0);
	g_free(sp);
}

static void plug(struct node *n)
{
	if (n->kind == N_USB)
		plug_usb(n);
	else if (n->kind == N_HID)
		plug_hid(n);
	else if (n->kind == N_GPIO)
		plug_gpio(n, (int)(n - nodes));
	n->gone = 0;
}

static void unplug(struct node *n)
{
	int i;

	if (n->gone)
		return;
	n->gone = 1;
	n_disconnects++;
	note("%s: unplugged (remove uevent)", n->what);
	for (i = 2; n->kind == N_HID && i >= 0; i--) {
		umockdev_testbed_uevent(tb, n->sub[i], "remove");
		umockdev_testbed_remove_device(tb, n->sub[i]);
	}
	umockdev_testbed_uevent(tb, n->syspath, "remove");
	umockdev_testbed_remove_device(tb, n->syspath);
	for (i = 0; i < n->n_urbs; i++)
		if (!n->urbs[i].done) {
			n->urbs[i].done = 1;
			n->urbs[i].status = -ESHUTDOWN;
		}
}

/* Open the simulator's side of n, as the simulated HAL's open does. */
static int sim_open(struct node *n)
{
	struct rig_usb_id id = { n->vid, n->pid, NULL, 0 };

	if (n->kind == N_USB)
		return hal.ops->usb_open(hal.self, &id, &n->sim);
	if (n->kind == N_HID)
		return hal.ops->hid_open(hal.self, n->vid, n->pid, NULL,
					 &n->sim);
	return RIG_OK;
}

/* A host sleep: the virtual clock moves; unplugged devices come back
 * when the fault schedule lets them re-open. */
static int host_sleep(uint64_t ns)
{
	int i, replugged = 0;

	hal.ops->clock_sleep(hal.self, (double)ns * 1e-9);
	for (i = 0; i < n_nodes; i++) {
		struct node *n = &nodes[i];

		if (!n->gone || rig_sim_core_open(&sim.core, n->dev) != RIG_OK)
			continue;
		plug(n);
		umockdev_testbed_uevent(tb, n->syspath, "add");
		if (n->kind == N_HID)
			umockdev_testbed_uevent(tb, n->sub[2], "add");
		n_replugs++;
		replugged++;
		note("%s: plugged back (add uevent)", n->what);
	}
	return replugged;
}

/* ---- usbdevfs ---- */
static int ep_known(const struct node *n, uint8_t ep)
{
	int i;

	for (i = 0; i < n->n_eps; i++)
		if (n->eps[i] == ep)
			return 1;
	return 0;
}

/* FTDI vendor requests [FTDI AN232B-04/05; APT protocol §2.1]. */
static double ftdi_baud(uint16_t value, uint16_t index)
{
	static const double frac[8] = { 0, 0.5, 0.25, 0.125, 0.375, 0.625,
					0.75, 0.875 };
	unsigned code = (value >> 14) | ((index & 1u) << 2);
	double div = (double)(value & 0x3fff) + frac[code];

	if ((value & 0x3fff) == 0)
		return 3000000.0;
	if ((value & 0x3fff) == 1 && code == 0)
		return 2000000.0;
	return 3000000.0 / div;
}

static void ftdi_request(struct node *n, const uint8_t *s)
{
	uint16_t value = (uint16_t)(s[2] | s[3] << 8);
	uint16_t index = (uint16_t)(s[4] | s[5] << 8);

	if (s[0] != 0x40) {
		violation(n, "control request type 0x%02x, not vendor OUT",
			  s[0]);
		return;
	}
	switch (s[1]) {
	case 0:		/* SIO_RESET */
		if (value == 0)
			n->ftdi_reset = 1;
		else if (value == 1)
			n->ftdi_purge_rx = 1;
		else if (value == 2)
			n->ftdi_purge_tx = 1;
		break;
	case 1:		/* SIO_MODEM_CTRL: high byte = mask, low = level */
		if (value & 0x0200)
			n->ftdi_rts = value & 0x02 ? 1 : 0;
		break;
	case 2:		/* SIO_SET_FLOW_CTRL: flow in the high byte of index */
		n->ftdi_flow_rtscts = (index >> 8) == 0x01;
		break;
	case 3:		/* SIO_SET_BAUD_RATE */
		n->ftdi_baud = ftdi_baud(value, index);
		break;
	case 4:		/* SIO_SET_DATA */
		n->ftdi_8n1 = value == 0x0008;
		break;
	case 9:		/* SIO_SET_LATENCY_TIMER */
		n->ftdi_latency_ms = value & 0xff;
		break;
	default:
		break;
	}
}

/* The first APT bytes the host sends: is the bridge set up as the APT
 * protocol requires?  (A UART at another rate or framing, or RTS not
 * asserted under RTS/CTS flow control, and the controller hears noise
 * or never answers.) */
static void ftdi_check(struct node *n)
{
	double err = (n->ftdi_baud - 115200.0) / 115200.0;

	if (n->ftdi_checked)
		return;
	n->ftdi_checked = 1;
	if (!n->ftdi_reset || !n->ftdi_purge_rx || !n->ftdi_purge_tx)
		violation(n, "FTDI not reset and purged (reset %d, purge rx "
			  "%d tx %d)", n->ftdi_reset, n->ftdi_purge_rx,
			  n->ftdi_purge_tx);
	if (err > 0.005 || err < -0.005)
		violation(n, "FTDI runs at %.0f baud, APT needs 115200 "
			  "(%+.2f %%)", n->ftdi_baud, 100 * err);
	if (!n->ftdi_8n1)
		violation(n, "FTDI line not set to 8N1");
	if (!n->ftdi_flow_rtscts)
		violation(n, "FTDI flow control not RTS/CTS");
	if (!n->ftdi_rts)
		violation(n, "RTS not asserted: under RTS/CTS flow control "
			  "the controller never sends");
	if (n->ftdi_latency_ms == 0)
		violation(n, "FTDI latency timer never set (16 ms default "
			  "delays every short APT answer)");
}

static int sim_rc_to_status(struct node *n, int rc)
{
	if (rc == RIG_EDISCONNECT) {
		unplug(n);
		return -ESHUTDOWN;
	}
	return rc == RIG_OK ? 0 : -EPROTO;
}

/* Standard GET_DESCRIPTOR (string) on endpoint 0: language 0x0409,
 * 1 manufacturer, 2 product, 3 serial; anything else stalls.  The answer
 * is delivered at reap as IN data after the 8 setup bytes. */
static void control_in(struct node *n, const uint8_t *s, struct urb *r)
{
	const char *str = NULL;
	uint16_t want = (uint16_t)(s[6] | s[7] << 8);
	uint8_t d[2 + 2 * 32];
	size_t len, i;

	r->done = 1;
	if (s[0] != 0x80 || s[1] != 6 || s[3] != 3) {
		r->status = -EPIPE;
		return;
	}
	if (s[2] == 0) {
		d[0] = 4, d[1] = 3, d[2] = 0x09, d[3] = 0x04;
		len = 4;
	} else {
		str = s[2] == 1 ? "straylight" : s[2] == 2 ? n->what
		    : n->serial;
		for (i = 0; str[i] && i < 32; i++) {
			d[2 + 2 * i] = (uint8_t)str[i];
			d[3 + 2 * i] = 0;
		}
		len = 2 + 2 * i;
		d[0] = (uint8_t)len, d[1] = 3;
	}
	if (len > want)
		len = want;
	r->in = g_malloc((size_t)r->len);
	memset(r->in, 0, (size_t)r->len);
	memcpy(r->in + 8, d, len);
	r->actual = (int)len;
	r->status = 0;
	r->ctrl_in = 1;
}

static int submit(struct node *n, UMockdevIoctlData *arg)
{
	UMockdevIoctlData *ud = umockdev_ioctl_data_resolve(arg, 0,
				 sizeof(struct usbdevfs_urb), NULL);
	UMockdevIoctlData *bd;
	struct usbdevfs_urb *u;
	struct urb *r;
	int rc;

	if (!ud)
		return -EFAULT;
	u = (struct usbdevfs_urb *)ud->data;
	if (n->n_urbs == MAX_URBS) {
		g_object_unref(ud);
		return -ENOMEM;
	}
	if (u->type != USBDEVFS_URB_TYPE_CONTROL &&
	    (!ep_known(n, u->endpoint) ||
	     u->type != USBDEVFS_URB_TYPE_BULK)) {
		violation(n, "URB type %u to endpoint 0x%02x, which the "
			  "device does not have", u->type, u->endpoint);
		g_object_unref(ud);
		return -ENOENT;
	}
	if (!n->claimed && u->type != USBDEVFS_URB_TYPE_CONTROL)
		violation(n, "bulk URB on an interface not claimed");
	r = &n->urbs[n->n_urbs++];
	memset(r, 0, sizeof(*r));
	r->addr = ud->client_addr;
	r->ep = u->endpoint;
	r->type = u->type;
	r->len = u->buffer_length;
	bd = u->buffer_length > 0 ? umockdev_ioctl_data_resolve(ud,
			offsetof(struct usbdevfs_urb, buffer),
			(gsize)u->buffer_length, NULL) : NULL;
	if (u->type == USBDEVFS_URB_TYPE_CONTROL && bd &&
	    bd->data_len >= 8 && (bd->data[0] & 0x80)) {
		control_in(n, bd->data, r);
	} else if (u->type == USBDEVFS_URB_TYPE_CONTROL) {
		if (bd && bd->data_len >= 8 && n->dev == RIG_DEV_STAGE)
			ftdi_request(n, bd->data);
		r->done = 1;
		r->status = 0;
	} else if (!(u->endpoint & 0x80)) {
		if (n->dev == RIG_DEV_STAGE)
			ftdi_check(n);
		rc = hal.ops->usb_write(hal.self, n->sim, u->endpoint,
					bd ? bd->data : NULL,
					(size_t)u->buffer_length, 0);
		r->done = 1;
		r->status = sim_rc_to_status(n, rc);
		r->actual = r->status == 0 ? u->buffer_length : 0;
	}
	if (bd)
		g_object_unref(bd);
	g_object_unref(ud);
	return 0;
}

/* Try a pending IN URB against the device; 1 when it completed. */
static int try_in(struct node *n, struct urb *r)
{
	size_t got = 0;
	int rc;

	if (r->done)
		return 1;
	r->in = g_malloc((size_t)r->len);
	rc = hal.ops->usb_read(hal.self, n->sim, r->ep, r->in,
			       (size_t)r->len, &got, 0);
	if (rc == RIG_ETIMEOUT) {	/* nothing: the URB stays queued */
		g_free(r->in);
		r->in = NULL;
		return 0;
	}
	r->done = 1;
	r->status = sim_rc_to_status(n, rc);
	r->actual = r->status == 0 ? (int)got : 0;
	return 1;
}

static int reap(struct node *n, UMockdevIoctlData *arg)
{
	UMockdevIoctlData *holder, *ud, *bd;
	struct usbdevfs_urb *u;
	struct urb r;
	int i;

	for (i = 0; i < n->n_urbs; i++)
		if (try_in(n, &n->urbs[i]))
			break;
	if (i == n->n_urbs)
		return n->gone ? -ENODEV : -EAGAIN;
	r = n->urbs[i];
	memmove(&n->urbs[i], &n->urbs[i + 1],
		(size_t)(n->n_urbs - i - 1) * sizeof(r));
	n->n_urbs--;
	holder = umockdev_ioctl_data_resolve(arg, 0, sizeof(void *), NULL);
	if (!holder) {
		g_free(r.in);
		return -EFAULT;
	}
	memcpy(holder->data, &r.addr, sizeof(r.addr));
	ud = umockdev_ioctl_data_resolve(holder, 0,
					 sizeof(struct usbdevfs_urb), NULL);
	u = (struct usbdevfs_urb *)ud->data;
	u->status = r.status;
	u->actual_length = r.actual;
	if (r.in && (r.actual > 0 || r.ctrl_in)) {
		bd = umockdev_ioctl_data_resolve(ud,
			offsetof(struct usbdevfs_urb, buffer),
			(gsize)r.len, NULL);
		memcpy(bd->data + (r.ctrl_in ? 8 : 0), r.in + (r.ctrl_in ? 8 : 0),
		       (size_t)r.actual);
		g_object_unref(bd);
	}
	g_free(r.in);
	g_object_unref(ud);
	g_object_unref(holder);
	return 0;
}

static int discard(struct node *n, uint64_t addr)
{
	int i;

	for (i = 0; i < n->n_urbs; i++) {
		struct urb *r = &n->urbs[i];

		if (r->addr != addr || r->done)
			continue;
		r->done = 1;
		r->status = -ENOENT;
		n_timeouts++;
		/* The simulated HAL's read waited out its timeout on the
		 * virtual clock; libusb keeps the URB's timeout to itself,
		 * so this is the camera driver's own formula (camera.c
		 * read_frame: exposure in whole ms + timeout_s). */
		if (n->dev == RIG_DEV_CAMERA)
			hal.ops->clock_sleep(hal.self, 1e-3 * (double)
				(unsigned)(sim.cam.exposure_us / 1000 +
					   cfg.camera.timeout_s * 1000));
		note("%s: URB on 0x%02x never completed; discarded",
		     n->what, r->ep);
		return 0;
	}
	return -EINVAL;
}

static int usb_ioctl(struct node *n, unsigned long req,
		     UMockdevIoctlData *arg)
{
	UMockdevIoctlData *d = NULL;
	uint64_t addr = *(unsigned long *)arg->data;
	int rc = 0;

	if (n->gone && req != USBDEVFS_REAPURBNDELAY)
		return -ENODEV;
	switch (req) {
	case USBDEVFS_GET_CAPABILITIES:
		d = umockdev_ioctl_data_resolve(arg, 0, 4, NULL);
		/* One URB per transfer, as a current kernel allows;
		 * DISCONNECT_CLAIM is an ioctl, not a capability. */
		*(uint32_t *)d->data = USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
				       USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
		break;
	case USBDEVFS_CLAIMINTERFACE:
		if (n->driver) {
			violation(n, "claim while kernel driver %s is bound "
				  "(not detached)", n->driver);
			return -EBUSY;
		}
		n->claimed = 1;
		break;
	case USBDEVFS_DISCONNECT_CLAIM:
		if (n->driver) {
			n->detached++;
			note("%s: kernel driver %s detached", n->what,
			     n->driver);
		}
		n->driver = NULL;
		n->claimed = 1;
		break;
	case USBDEVFS_RELEASEINTERFACE:
		n->claimed = 0;
		break;
	case USBDEVFS_GETDRIVER:
		d = umockdev_ioctl_data_resolve(arg, 0,
				sizeof(struct usbdevfs_getdriver), NULL);
		if (!n->driver)
			rc = -ENODATA;
		else
			g_strlcpy(((struct usbdevfs_getdriver *)d->data)->driver,
				  n->driver, USBDEVFS_MAXDRIVERNAME + 1);
		break;
	case USBDEVFS_IOCTL:
		d = umockdev_ioctl_data_resolve(arg, 0,
				sizeof(struct usbdevfs_ioctl), NULL);
		if (((struct usbdevfs_ioctl *)d->data)->ioctl_code ==
		    USBDEVFS_CONNECT) {
			if (n->driver0 && !n->driver) {
				n->reattached++;
				note("%s: kernel driver %s re-attached",
				     n->what, n->driver0);
			}
			n->driver = n->driver0;
		} else if (((struct usbdevfs_ioctl *)d->data)->ioctl_code ==
			   USBDEVFS_DISCONNECT) {
			n->driver = NULL;
			n->detached++;
		}
		break;
	case USBDEVFS_SUBMITURB:
		rc = n->gone ? -ENODEV : submit(n, arg);
		break;
	case USBDEVFS_REAPURBNDELAY:
	case USBDEVFS_REAPURB:
		rc = reap(n, arg);
		break;
	case USBDEVFS_DISCARDURB:
		rc = discard(n, addr);
		break;
	case USBDEVFS_SETCONFIGURATION:
	case USBDEVFS_RESET:
	case USBDEVFS_CLEAR_HALT:
	case USBDEVFS_SETINTERFACE:
		break;
	default:
		rc = -ENOTTY;
	}
	if (d)
		g_object_unref(d);
	return rc;
}

/* ---- hidraw ---- */
static int hid_ioctl(struct node *n, unsigned long req,
		     UMockdevIoctlData *arg)
{
	UMockdevIoctlData *d = NULL;
	int rc = 0;

	if (n->gone)
		return -ENODEV;
	if (req == HIDIOCGRDESCSIZE) {
		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(int), NULL);
		*(int *)d->data = (int)RDESC_LEN;
	} else if (req == HIDIOCGRDESC) {
		struct hidraw_report_descriptor *rd;

		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(*rd), NULL);
		rd = (struct hidraw_report_descriptor *)d->data;
		rd->size = RDESC_LEN;
		memcpy(rd->value, rdesc(n), RDESC_LEN);
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

static gssize hid_write(struct node *n, UMockdevIoctlData *arg)
{
	int rc;

	if (n->gone)
		return -ENODEV;
	if (arg->data_len != 8 || arg->data[0] != out_id(n))
		violation(n, "output report of %d bytes with id 0x%02x; the "
			  "descriptor has 7-byte report 0x%02x (id first)",
			  arg->data_len, arg->data_len ? arg->data[0] : 0,
			  out_id(n));
	rc = hal.ops->hid_write(hal.self, n->sim, arg->data,
				(size_t)arg->data_len);
	if (rc == RIG_EDISCONNECT) {
		unplug(n);
		return -ENODEV;
	}
	return arg->data_len;
}

static gssize hid_read(struct node *n, UMockdevIoctlData *arg)
{
	size_t got = 0;
	int rc;

	if (n->gone)
		return -ENODEV;
	rc = hal.ops->hid_read(hal.self, n->sim, arg->data,
			       (size_t)arg->data_len, &got, 0);
	if (rc == RIG_ETIMEOUT)
		return -EAGAIN;
	if (rc != RIG_OK) {
		unplug(n);
		return -ENODEV;
	}
	return (gssize)got;
}

/* ---- GPIO character device, uAPI v1 ---- */
static const int safe_on[RIG_LINE_COUNT] = { 0, 1, 0 };

static int gpio_handle_request(struct node *n, UMockdevIoctlData *arg)
{
	UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0,
				sizeof(struct gpiohandle_request), NULL);
	struct gpiohandle_request *hr = (struct gpiohandle_request *)d->data;
	struct handle *h;
	unsigned i;
	int rc = 0;

	if (n_handles == MAX_HANDLES || hr->lines == 0 ||
	    hr->lines > GPIOHANDLES_MAX) {
		g_object_unref(d);
		return -EINVAL;
	}
	h = &handles[n_handles];
	memset(h, 0, sizeof(*h));
	h->chip = n;
	h->flags = hr->flags;
	if (!(hr->flags & GPIOHANDLE_REQUEST_OUTPUT) ||
	    (hr->flags & GPIOHANDLE_REQUEST_INPUT))
		violation(n, "line request flags 0x%x: shutter, beam block "
			  "and lamp are outputs", hr->flags);
	if (!hr->consumer_label[0])
		violation(n, "line request without a consumer label");
	for (i = 0; i < hr->lines && rc == 0; i++) {
		unsigned off = hr->lineoffsets[i];
		int line = off < GPIO_LINES ? n->line_at[off] : -1;
		int lvl = hr->default_values[i] ? 1 : 0;
		struct rig_gpio_id id;

		if (line < 0) {
			rc = -EINVAL;
			break;
		}
		if (hr->flags & GPIOHANDLE_REQUEST_ACTIVE_LOW)
			lvl ^= 1;
		if ((lvl ^ (cfg.lines[line].active_low ? 1 : 0)) !=
		    safe_on[line])
			violation(n, "line %s requested at level %d: not its "
				  "safe level (a glitch before the first "
				  "write)", cfg.lines[line].line, lvl);
		id.chip = cfg.lines[line].chip;
		id.line = cfg.lines[line].line;
		id.output = 1;
		id.initial = lvl;
		h->offsets[i] = line;
		if (hal.ops->gpio_open(hal.self, &id, &h->sim[i]) != RIG_OK)
			rc = -EBUSY;
	}
	h->n = (int)hr->lines;
	if (rc == 0)
		hr->fd = RIGTB_TOKEN_BASE + n_handles++;
	g_object_unref(d);
	return rc;
}

static int gpio_values(struct handle *h, unsigned long req,
		       UMockdevIoctlData *arg)
{
	UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0,
				sizeof(struct gpiohandle_data), NULL);
	struct gpiohandle_data *v = (struct gpiohandle_data *)d->data;
	int inv = h->flags & GPIOHANDLE_REQUEST_ACTIVE_LOW ? 1 : 0;
	int i, rc = 0, s;

	for (i = 0; i < h->n && rc == 0; i++) {
		if (req == GPIOHANDLE_SET_LINE_VALUES_IOCTL) {
			s = hal.ops->gpio_set(hal.self, h->sim[i],
					      (v->values[i] ? 1 : 0) ^ inv);
		} else {
			int lvl = 0;

			s = hal.ops->gpio_get(hal.self, h->sim[i], &lvl);
			v->values[i] = (uint8_t)(lvl ^ inv);
		}
		if (s != RIG_OK)
			rc = s == RIG_EDISCONNECT ? -ENODEV : -EIO;
	}
	g_object_unref(d);
	return rc;
}

static int gpio_ioctl(struct node *n, UMockdevIoctlClient *client,
		      unsigned long req, UMockdevIoctlData *arg)
{
	struct handle *h = g_object_get_data(G_OBJECT(client), "handle");
	UMockdevIoctlData *d = NULL;
	int rc = 0;

	if (req == RIGTB_BIND_HANDLE) {
		int32_t token;

		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(token), NULL);
		memcpy(&token, d->data, sizeof(token));
		g_object_unref(d);
		token -= RIGTB_TOKEN_BASE;
		if (token < 0 || token >= n_handles)
			return -EINVAL;
		g_object_set_data(G_OBJECT(client), "handle",
				  &handles[token]);
		return 0;
	}
	if (h && (req == GPIOHANDLE_SET_LINE_VALUES_IOCTL ||
		  req == GPIOHANDLE_GET_LINE_VALUES_IOCTL))
		return gpio_values(h, req, arg);
	if (req == GPIO_GET_CHIPINFO_IOCTL) {
		struct gpiochip_info *ci;

		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(*ci), NULL);
		ci = (struct gpiochip_info *)d->data;
		g_strlcpy(ci->name, n->name, sizeof(ci->name));
		g_strlcpy(ci->label, "straylight-testbed", sizeof(ci->label));
		ci->lines = GPIO_LINES;
	} else if (req == GPIO_GET_LINEINFO_IOCTL) {
		struct gpioline_info *li;
		int line, k;

		d = umockdev_ioctl_data_resolve(arg, 0, sizeof(*li), NULL);
		li = (struct gpioline_info *)d->data;
		if (li->line_offset >= GPIO_LINES) {
			rc = -EINVAL;
		} else {
			line = n->line_at[li->line_offset];
			li->flags = 0;
			li->name[0] = li->consumer[0] = '\0';
			if (line >= 0)
				g_strlcpy(li->name, cfg.lines[line].line,
					  sizeof(li->name));
			for (k = 0; line >= 0 && k < n_handles; k++)
				if (handles[k].chip == n &&
				    handles[k].offsets[0] == line) {
					li->flags = GPIOLINE_FLAG_KERNEL |
						    GPIOLINE_FLAG_IS_OUT;
					g_strlcpy(li->consumer, "strayrigd",
						  sizeof(li->consumer));
				}
		}
	} else if (req == GPIO_GET_LINEHANDLE_IOCTL) {
		rc = gpio_handle_request(n, arg);
	} else {
		rc = -ENOTTY;
	}
	if (d)
		g_object_unref(d);
	return rc;
}

/* ---- the umockdev handler class ---- */
typedef struct {
	UMockdevIoctlBase parent;
	struct node *node;
} TbHandler;
typedef struct {
	UMockdevIoctlBaseClass parent_class;
} TbHandlerClass;

static GType tb_handler_get_type(void);
G_DEFINE_TYPE(TbHandler, tb_handler, UMOCKDEV_TYPE_IOCTL_BASE)

static void finish(UMockdevIoctlClient *client, long rc)
{
	if (rc < 0)
		umockdev_ioctl_client_complete(client, -1, (int)-rc);
	else
		umockdev_ioctl_client_complete(client, rc, 0);
}

static gboolean tb_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *c)
{
	struct node *n = ((TbHandler *)base)->node;
	unsigned long req = umockdev_ioctl_client_get_request(c);
	UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(c);
	UMockdevIoctlData *d;
	long rc = -ENOTTY;

	switch (n->kind) {
	case N_USB:
		rc = usb_ioctl(n, req, arg);
		break;
	case N_HID:
		rc = hid_ioctl(n, req, arg);
		break;
	case N_GPIO:
		rc = gpio_ioctl(n, c, req, arg);
		break;
	case N_CLOCK:
		if (req == RIGTB_SLEEP) {
			d = umockdev_ioctl_data_resolve(arg, 0, 8, NULL);
			rc = host_sleep(*(uint64_t *)d->data);
			g_object_unref(d);
		}
		break;
	}
	finish(c, rc);
	return TRUE;
}

static gboolean tb_read(UMockdevIoctlBase *base, UMockdevIoctlClient *c)
{
	struct node *n = ((TbHandler *)base)->node;

	finish(c, n->kind == N_HID ? hid_read(n,
			umockdev_ioctl_client_get_arg(c)) : -EINVAL);
	return TRUE;
}

static gboolean tb_write(UMockdevIoctlBase *base, UMockdevIoctlClient *c)
{
	struct node *n = ((TbHandler *)base)->node;

	finish(c, n->kind == N_HID ? hid_write(n,
			umockdev_ioctl_client_get_arg(c)) : -EINVAL);
	return TRUE;
}

static void tb_connected(UMockdevIoctlBase *base, UMockdevIoctlClient *c)
{
	struct node *n = ((TbHandler *)base)->node;

	(void)c;
	/* The host opened the node: the simulated HAL's open. */
	if (!n->gone && sim_open(n) != RIG_OK)
		unplug(n);
}

static void tb_handler_class_init(TbHandlerClass *klass)
{
	UMockdevIoctlBaseClass *b = UMOCKDEV_IOCTL_BASE_CLASS(klass);

	b->handle_ioctl = tb_ioctl;
	b->handle_read = tb_read;
	b->handle_write = tb_write;
	b->client_connected = tb_connected;
}

static void tb_handler_init(TbHandler *self)
{
	self->node = NULL;
}

/* ---- setting up ---- */
static struct node *add_node(enum node_kind kind, int dev, const char *what)
{
	struct node *n = &nodes[n_nodes++];
	int i;

	memset(n, 0, sizeof(*n));
	n->kind = kind;
	n->dev = dev;
	n->what = what;
	for (i = 0; i < GPIO_LINES; i++)
		n->line_at[i] = -1;
	return n;
}

static int attach(struct node *n)
{
	TbHandler *h = g_object_new(tb_handler_get_type(), NULL);
	GError *e = NULL;

	h->node = n;
	if (!umockdev_testbed_attach_ioctl(tb, n->devnode,
					   UMOCKDEV_IOCTL_BASE(h), &e)) {
		fprintf(stderr, "rig-testbed: %s: %s\n", n->devnode,
			e ? e->message : "cannot attach");
		return -1;
	}
	return 0;
}

static void build_lab(void)
{
	struct node *n;
	int i, j;

	n = add_node(N_USB, RIG_DEV_STAGE, "stage");
	g_strlcpy(n->name, "1-2", sizeof(n->name));
	g_strlcpy(n->devnode, "/dev/bus/usb/001/002", sizeof(n->devnode));
	n->serial = cfg.stage.serial[0] ? cfg.stage.serial : "83000001";
	n->vid = cfg.stage.usb.vid;
	n->pid = cfg.stage.usb.pid;
	n->eps[0] = 0x81;
	n->eps[1] = 0x02;
	n->n_eps = 2;
	n->ep_max_packet = 64;
	n->driver0 = "ftdi_sio";
	n = add_node(N_USB, RIG_DEV_CAMERA, "camera");
	g_strlcpy(n->name, "1-3", sizeof(n->name));
	g_strlcpy(n->devnode, "/dev/bus/usb/001/003", sizeof(n->devnode));
	n->serial = cfg.camera.serial[0] ? cfg.camera.serial : "CAM0001";
	n->vid = cfg.camera.usb.vid;
	n->pid = cfg.camera.usb.pid;
	n->eps[0] = RIG_FL_EP_CMD;
	n->eps[1] = RIG_FL_EP_DATA;
	n->n_eps = 2;
	n->ep_max_packet = 512;
	n = add_node(N_HID, RIG_DEV_WHEEL, "wheel");
	g_strlcpy(n->name, "hidraw0", sizeof(n->name));
	g_strlcpy(n->devnode, "/dev/hidraw0", sizeof(n->devnode));
	n->serial = cfg.wheel.serial[0] ? cfg.wheel.serial : "ND0001";
	n->vid = cfg.wheel.vid;
	n->pid = cfg.wheel.pid;
	if (cfg.monitor.enabled) {
		n = add_node(N_HID, RIG_DEV_MONITOR, "monitor");
		g_strlcpy(n->name, "hidraw1", sizeof(n->name));
		g_strlcpy(n->devnode, "/dev/hidraw1", sizeof(n->devnode));
		n->serial = cfg.monitor.serial[0] ? cfg.monitor.serial
						   : "MON0001";
		n->vid = cfg.monitor.vid;
		n->pid = cfg.monitor.pid;
	}
	/* One chip per chip name; lines at offsets 2, 3, 4, ... */
	for (i = 0; i < RIG_LINE_COUNT; i++) {
		struct node *chip = NULL;

		for (j = 0; j < n_nodes; j++)
			if (nodes[j].kind == N_GPIO &&
			    !strcmp(nodes[j].chip, cfg.lines[i].chip))
				chip = &nodes[j];
		if (!chip) {
			chip = add_node(N_GPIO, RIG_DEV_GPIO, "gpio");
			g_strlcpy(chip->chip, cfg.lines[i].chip,
				  sizeof(chip->chip));
			g_strlcpy(chip->name, cfg.lines[i].chip,
				  sizeof(chip->name));
			snprintf(chip->devnode, sizeof(chip->devnode),
				 "/dev/%s", cfg.lines[i].chip);
		}
		chip->line_at[2 + i] = i;
	}
	n = add_node(N_CLOCK, -1, "clock");
	g_strlcpy(n->devnode, RIGTB_CLOCK_NODE, sizeof(n->devnode));
	put_file(n->devnode + 1, "", 0);
	for (i = 0; i < n_nodes; i++)
		if (nodes[i].kind != N_CLOCK)
			plug(&nodes[i]);
}

static void summary(int status)
{
	int i;

	for (i = 0; i < n_nodes; i++)
		if (nodes[i].driver0)
			note("%s: kernel driver detached %d, re-attached %d",
			     nodes[i].what, nodes[i].detached,
			     nodes[i].reattached);
	note("command exit %d; %u protocol violations, %u disconnects, %u "
	     "re-plugs, %u URBs never completed, %u faults fired", status,
	     violations, n_disconnects, n_replugs, n_timeouts,
	     rig_sim_faults_fired(&sim));
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
	rig_config_defaults(&cfg);
	if (rig_config_load(&cfg, config, &err) != RIG_OK) {
		fprintf(stderr, "rig-testbed: %s\n", err.msg);
		return 2;
	}
	for (i = 0; i < cfg.sim.n_faults; i++)
		if (cfg.sim.faults[i].kind == RIG_FAULT_KILL) {
			fprintf(stderr, "rig-testbed: %s: sim.faults[%d]: kind "
				"'kill' cannot run under the test bed (the "
				"device side would kill the test bed, not the "
				"daemon)\n", config, i);
			return 2;
		}
	logf = logpath ? fopen(logpath, "w") : stderr;
	shim = getenv("RIG_TESTBED_SHIM");
	if (!shim) {
		fprintf(stderr, "rig-testbed: RIG_TESTBED_SHIM (the path of "
			"rig-testbed-shim.so) is not set\n");
		return 2;
	}
	rig_sim_init(&sim, &cfg, &hal);
	tb = umockdev_testbed_new();
	build_lab();
	for (i = 0; i < n_nodes; i++)
		if (attach(&nodes[i]) != 0)
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
	if (violations)
		return 3;
	return status;
}
