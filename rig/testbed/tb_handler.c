/*
 * tb_handler.c - rig-testbed: the umockdev ioctl handler class, one
 * instance per node, dispatching ioctls, reads and writes to the node's
 * kind.
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
		rc = tb_usb_ioctl(n, req, arg);
		break;
	case N_HID:
		rc = tb_hid_ioctl(n, req, arg);
		break;
	case N_GPIO:
		rc = tb_gpio_ioctl(n, c, req, arg);
		break;
	case N_CLOCK:
		if (req == RIGTB_SLEEP) {
			d = umockdev_ioctl_data_resolve(arg, 0, 8, NULL);
			rc = tb_host_sleep(*(uint64_t *)d->data);
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

	finish(c, n->kind == N_HID ? tb_hid_read(n,
			umockdev_ioctl_client_get_arg(c)) : -EINVAL);
	return TRUE;
}

static gboolean tb_write(UMockdevIoctlBase *base, UMockdevIoctlClient *c)
{
	struct node *n = ((TbHandler *)base)->node;

	finish(c, n->kind == N_HID ? tb_hid_write(n,
			umockdev_ioctl_client_get_arg(c)) : -EINVAL);
	return TRUE;
}

static void tb_connected(UMockdevIoctlBase *base, UMockdevIoctlClient *c)
{
	struct node *n = ((TbHandler *)base)->node;

	(void)c;
	/* The host opened the node: the simulated HAL's open. */
	if (!n->gone && tb_sim_open(n) != RIG_OK)
		tb_unplug(n);
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

int tb_attach(struct node *n)
{
	TbHandler *h = g_object_new(tb_handler_get_type(), NULL);
	GError *e = NULL;

	h->node = n;
	if (!umockdev_testbed_attach_ioctl(tb_mock, n->devnode,
					   UMOCKDEV_IOCTL_BASE(h), &e)) {
		fprintf(stderr, "rig-testbed: %s: %s\n", n->devnode,
			e ? e->message : "cannot attach");
		return -1;
	}
	return 0;
}
