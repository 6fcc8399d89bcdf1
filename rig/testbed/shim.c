/*
 * shim.c - rig-testbed-shim.so, preloaded before umockdev's preload in
 * the command the test bed runs.  Two jobs only (testbed.h):
 *   nanosleep  reported to the test bed's clock node (the device side
 *              runs on the simulator's virtual clock), then slept for at
 *              most 5 ms of real time, 200 ms after a device came back
 *              (libusb's hotplug thread must see it first);
 *   ioctl      after GPIO_GET_LINEHANDLE_IOCTL succeeds, opens the chip
 *              node again and binds the new fd to the handle the test
 *              bed created, doing what the kernel does with anon inodes.
 * Everything else goes straight to the next ioctl (umockdev's).
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <linux/gpio.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include "testbed.h"

typedef int (*ioctl_fn)(int, unsigned long, ...);
typedef int (*nanosleep_fn)(const struct timespec *, struct timespec *);

static ioctl_fn next_ioctl(void)
{
	static ioctl_fn f;

	if (!f)
		f = (ioctl_fn)dlsym(RTLD_NEXT, "ioctl");
	return f;
}

int nanosleep(const struct timespec *req, struct timespec *rem)
{
	static nanosleep_fn real;
	static int clock_fd = -2;
	struct timespec shortened;
	uint64_t ns;
	int replugged;

	if (!real)
		real = (nanosleep_fn)dlsym(RTLD_NEXT, "nanosleep");
	if (clock_fd == -2)
		clock_fd = open(RIGTB_CLOCK_NODE, O_RDWR | O_CLOEXEC);
	if (clock_fd < 0 || !req)
		return real(req, rem);
	ns = (uint64_t)req->tv_sec * 1000000000u + (uint64_t)req->tv_nsec;
	/* > 0: devices were plugged back; libusb's hotplug thread must
	 * see their "add" uevents before the host looks for them. */
	replugged = next_ioctl()(clock_fd, RIGTB_SLEEP, &ns);
	shortened.tv_sec = 0;
	shortened.tv_nsec = replugged > 0 ? 200000000
			  : ns < 5000000 ? (long)ns : 5000000;
	if (rem)
		rem->tv_sec = rem->tv_nsec = 0;
	return real(&shortened, NULL);
}

/* The chip node fd was opened from, without the test bed's root. */
static int node_of(int fd, char *path, size_t cap)
{
	char link[64], buf[4096];
	const char *root = getenv("UMOCKDEV_DIR");
	ssize_t n;

	snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
	n = readlink(link, buf, sizeof(buf) - 1);
	if (n <= 0)
		return -1;
	buf[n] = '\0';
	if (root && strncmp(buf, root, strlen(root)) == 0)
		snprintf(path, cap, "%s", buf + strlen(root));
	else
		snprintf(path, cap, "%s", buf);
	return 0;
}

int ioctl(int fd, unsigned long request, ...)
{
	struct gpiohandle_request *hr;
	char path[4096];
	void *arg;
	va_list ap;
	int rc, nfd;
	int32_t token;

	va_start(ap, request);
	arg = va_arg(ap, void *);
	va_end(ap);
	rc = next_ioctl()(fd, request, arg);
	if (request != GPIO_GET_LINEHANDLE_IOCTL || rc != 0)
		return rc;
	hr = arg;
	if (hr->fd < RIGTB_TOKEN_BASE)
		return rc;	/* a real kernel's fd */
	token = hr->fd;
	if (node_of(fd, path, sizeof(path)) != 0 ||
	    (nfd = open(path, O_RDWR | O_CLOEXEC)) < 0)
		return -1;
	if (next_ioctl()(nfd, RIGTB_BIND_HANDLE, &token) != 0) {
		close(nfd);
		return -1;
	}
	hr->fd = nfd;
	return 0;
}
