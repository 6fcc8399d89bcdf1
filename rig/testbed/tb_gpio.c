/*
 * tb_gpio.c - rig-testbed: the GPIO character device, uAPI v1 (line
 * handles requested, values got and set), the request flags and initial
 * levels checked.
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

static const int safe_on[RIG_LINE_COUNT] = { 0, 1, 0 };

static int gpio_handle_request(struct node *n, UMockdevIoctlData *arg)
{
	UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0,
				sizeof(struct gpiohandle_request), NULL);
	struct gpiohandle_request *hr = (struct gpiohandle_request *)d->data;
	struct handle *h;
	unsigned i;
	int rc = 0;

	if (tb_n_handles == MAX_HANDLES || hr->lines == 0 ||
	    hr->lines > GPIOHANDLES_MAX) {
		g_object_unref(d);
		return -EINVAL;
	}
	h = &tb_handles[tb_n_handles];
	memset(h, 0, sizeof(*h));
	h->chip = n;
	h->flags = hr->flags;
	if (!(hr->flags & GPIOHANDLE_REQUEST_OUTPUT) ||
	    (hr->flags & GPIOHANDLE_REQUEST_INPUT))
		tb_violation(n, "line request flags 0x%x: shutter, beam block "
			     "and lamp are outputs", hr->flags);
	if (!hr->consumer_label[0])
		tb_violation(n, "line request without a consumer label");
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
		if ((lvl ^ (tb_cfg.lines[line].active_low ? 1 : 0)) !=
		    safe_on[line])
			tb_violation(n, "line %s requested at level %d: "
				     "not its safe level (a glitch before the "
				     "first write)", tb_cfg.lines[line].line,
				     lvl);
		id.chip = tb_cfg.lines[line].chip;
		id.line = tb_cfg.lines[line].line;
		id.output = 1;
		id.initial = lvl;
		h->offsets[i] = line;
		if (tb_hal.ops->gpio_open(tb_hal.self, &id, &h->sim[i]) !=
		    RIG_OK)
			rc = -EBUSY;
	}
	h->n = (int)hr->lines;
	if (rc == 0)
		hr->fd = RIGTB_TOKEN_BASE + tb_n_handles++;
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
			s = tb_hal.ops->gpio_set(tb_hal.self, h->sim[i],
					      (v->values[i] ? 1 : 0) ^ inv);
		} else {
			int lvl = 0;

			s = tb_hal.ops->gpio_get(tb_hal.self, h->sim[i], &lvl);
			v->values[i] = (uint8_t)(lvl ^ inv);
		}
		if (s != RIG_OK)
			rc = s == RIG_EDISCONNECT ? -ENODEV : -EIO;
	}
	g_object_unref(d);
	return rc;
}

int tb_gpio_ioctl(struct node *n, UMockdevIoctlClient *client,
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
		if (token < 0 || token >= tb_n_handles)
			return -EINVAL;
		g_object_set_data(G_OBJECT(client), "handle",
				  &tb_handles[token]);
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
				g_strlcpy(li->name, tb_cfg.lines[line].line,
					  sizeof(li->name));
			for (k = 0; line >= 0 && k < tb_n_handles; k++)
				if (tb_handles[k].chip == n &&
				    tb_handles[k].offsets[0] == line) {
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
