/*
 * tb_usb.c - rig-testbed: usbdevfs as the kernel answers it (URBs
 * submitted, reaped and discarded, control requests), the FTDI set-up
 * checked against the APT documentation.
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
		tb_violation(n, "control request type 0x%02x, not vendor OUT",
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
		tb_violation(n, "FTDI not reset and purged (reset %d, purge rx "
			     "%d tx %d)", n->ftdi_reset, n->ftdi_purge_rx,
			     n->ftdi_purge_tx);
	if (err > 0.005 || err < -0.005)
		tb_violation(n, "FTDI runs at %.0f baud, APT needs 115200 "
			     "(%+.2f %%)", n->ftdi_baud, 100 * err);
	if (!n->ftdi_8n1)
		tb_violation(n, "FTDI line not set to 8N1");
	if (!n->ftdi_flow_rtscts)
		tb_violation(n, "FTDI flow control not RTS/CTS");
	if (!n->ftdi_rts)
		tb_violation(n, "RTS not asserted: under RTS/CTS flow control "
			     "the controller never sends");
	if (n->ftdi_latency_ms == 0)
		tb_violation(n, "FTDI latency timer never set (16 ms default "
			     "delays every short APT answer)");
}

static int sim_rc_to_status(struct node *n, int rc)
{
	if (rc == RIG_EDISCONNECT) {
		tb_unplug(n);
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
		tb_violation(n, "URB type %u to endpoint 0x%02x, which the "
			     "device does not have", u->type, u->endpoint);
		g_object_unref(ud);
		return -ENOENT;
	}
	if (!n->claimed && u->type != USBDEVFS_URB_TYPE_CONTROL)
		tb_violation(n, "bulk URB on an interface not claimed");
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
		rc = tb_hal.ops->usb_write(tb_hal.self, n->sim, u->endpoint,
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
	rc = tb_hal.ops->usb_read(tb_hal.self, n->sim, r->ep, r->in,
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
		tb_n_timeouts++;
		/* The simulated HAL's read waited out its timeout on the
		 * virtual clock; libusb keeps the URB's timeout to itself,
		 * so this is the camera driver's own formula (camera.c
		 * read_frame: exposure in whole ms + timeout_s). */
		if (n->dev == RIG_DEV_CAMERA)
			tb_hal.ops->clock_sleep(tb_hal.self, 1e-3 * (double)
				(unsigned)(tb_sim.cam.exposure_us / 1000 +
					   tb_cfg.camera.timeout_s * 1000));
		tb_note("%s: URB on 0x%02x never completed; discarded",
			n->what, r->ep);
		return 0;
	}
	return -EINVAL;
}

int tb_usb_ioctl(struct node *n, unsigned long req,
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
			tb_violation(n, "claim while kernel driver %s is bound "
				     "(not detached)", n->driver);
			return -EBUSY;
		}
		n->claimed = 1;
		break;
	case USBDEVFS_DISCONNECT_CLAIM:
		if (n->driver) {
			n->detached++;
			tb_note("%s: kernel driver %s detached", n->what,
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
				tb_note("%s: kernel driver %s re-attached",
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
