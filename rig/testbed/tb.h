/*
 * tb.h - what the files of rig-testbed share (private to rig/testbed/):
 * the devices as nodes, the URBs and GPIO line handles, the state (touched
 * only on umockdev's worker thread once the command runs), the messages,
 * plugging devices in and out (tb_plug.c), the usbdevfs, hidraw and GPIO
 * answers (tb_usb.c, tb_hid.c, tb_gpio.c) and the umockdev handler that
 * dispatches to them (tb_handler.c); testbed.c sets up and runs.
 */
#ifndef RIG_TESTBED_TB_H
#define RIG_TESTBED_TB_H

#include <glib.h>
#include <linux/gpio.h>
#include <stdint.h>
#include <stdio.h>
#include <umockdev.h>

#include "rig/config.h"
#include "rig/sim.h"

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

extern struct rig_config tb_cfg;
extern struct rig_sim tb_sim;
extern struct rig_hal tb_hal;
extern UMockdevTestbed *tb_mock;
extern struct node tb_nodes[16];
extern int tb_n_nodes;
extern struct handle tb_handles[MAX_HANDLES];
extern int tb_n_handles;
extern unsigned tb_violations, tb_n_disconnects, tb_n_timeouts, tb_n_replugs;
extern FILE *tb_logf;

/* A line of the log (--log), and a protocol violation (stderr, exit 3). */
void tb_note(const char *fmt, ...) G_GNUC_PRINTF(1, 2);
void tb_violation(const struct node *n, const char *fmt, ...)
	G_GNUC_PRINTF(2, 3);

/* Plugging devices in and out (tb_plug.c). */
void tb_put_file(const char *rel, const void *data, size_t len);
size_t tb_rdesc_len(void);	/* every report descriptor's length */
const uint8_t *tb_rdesc(const struct node *n);
uint8_t tb_out_id(const struct node *n);
void tb_plug(struct node *n);
void tb_unplug(struct node *n);
int tb_sim_open(struct node *n);
int tb_host_sleep(uint64_t ns);

/* usbdevfs (tb_usb.c). */
int tb_usb_ioctl(struct node *n, unsigned long req,
		 UMockdevIoctlData *arg);

/* hidraw (tb_hid.c). */
int tb_hid_ioctl(struct node *n, unsigned long req,
		 UMockdevIoctlData *arg);
gssize tb_hid_write(struct node *n, UMockdevIoctlData *arg);
gssize tb_hid_read(struct node *n, UMockdevIoctlData *arg);

/* The GPIO character device (tb_gpio.c). */
int tb_gpio_ioctl(struct node *n, UMockdevIoctlClient *client,
		  unsigned long req, UMockdevIoctlData *arg);

/* The umockdev handler of a node (tb_handler.c). */
int tb_attach(struct node *n);

#endif /* RIG_TESTBED_TB_H */
