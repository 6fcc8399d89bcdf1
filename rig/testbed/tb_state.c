/*
 * tb_state.c - rig-testbed's state (tb.h) and its two kinds of message:
 * the log's lines and the protocol violations.
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

struct rig_config tb_cfg;
struct rig_sim tb_sim;
struct rig_hal tb_hal;
UMockdevTestbed *tb_mock;
struct node tb_nodes[16];
int tb_n_nodes;
struct handle tb_handles[MAX_HANDLES];
int tb_n_handles;
unsigned tb_violations, tb_n_disconnects, tb_n_timeouts, tb_n_replugs;
FILE *tb_logf;

void tb_note(const char *fmt, ...)
{
	va_list ap;

	if (!tb_logf)
		return;
	va_start(ap, fmt);
	fputs("rig-testbed: ", tb_logf);
	vfprintf(tb_logf, fmt, ap);
	fputc('\n', tb_logf);
	fflush(tb_logf);
	va_end(ap);
}

void tb_violation(const struct node *n, const char *fmt, ...)
{
	va_list ap;

	tb_violations++;
	va_start(ap, fmt);
	fprintf(stderr, "rig-testbed: %s: ", n->what);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
}
