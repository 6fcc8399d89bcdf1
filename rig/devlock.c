/*
 * devlock.c - a lab-wide lock per device (devlock.h).  The socket's lock
 * and the sweep folder's lock are per path: a standalone `strayrigd
 * --sweep` beside a socket daemon drove the same stage and camera.  Each
 * device the config names gets a lock file in lock_dir, named after its
 * bus identity (vid:pid:serial, or GPIO chip and line), held with flock
 * for the daemon's life; whoever holds it is written inside, so a refusal
 * names the other daemon.  flock is released by the kernel when a
 * process dies, so a kill -9 leaves no stale lock.
 */
#define _DEFAULT_SOURCE	/* flock */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <time.h>
#include <unistd.h>

#include "rig/devlock.h"

/* A file-name-safe copy of text: [A-Za-z0-9._-] kept, others '_'. */
static void safe_name(char *out, size_t size, const char *text)
{
	size_t i;

	for (i = 0; text[i] && i + 1 < size; i++) {
		char c = text[i];

		out[i] = ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
			  (c >= '0' && c <= '9') || c == '.' || c == '-')
			 ? c : '_';
	}
	out[i] = '\0';
}

static int take_one(struct rig_devlock *l, const char *dir, const char *what,
		    const char *id, const char *owner, struct rig_error *err)
{
	char name[160], path[RIG_PATH_MAX + 200], held[200] = "", line[240];
	int fd, n;

	safe_name(name, sizeof(name), id);
	snprintf(path, sizeof(path), "%s/straylight-%s.lock", dir, name);
	fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0664);
	if (fd < 0)
		return rig_error_set(err, RIG_EIO,
			"%s: cannot open the device lock: %s (make the "
			"folder writable, or set lock_dir)", path,
			strerror(errno));
	if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
		int e = errno;

		n = (int)pread(fd, held, sizeof(held) - 1, 0);
		held[n > 0 ? n : 0] = '\0';
		held[strcspn(held, "\n")] = '\0';
		close(fd);
		if (e == EWOULDBLOCK)
			return rig_error_set(err, RIG_ESTATE,
				"%s %s is in use by another daemon (%s; lock "
				"%s): stop it first", what, id,
				held[0] ? held : "holder unknown", path);
		return rig_error_set(err, RIG_EIO, "%s: cannot lock: %s",
				     path, strerror(e));
	}
	{
		time_t now = time(NULL);
		struct tm tm;
		char when[32] = "?";

		if (gmtime_r(&now, &tm))
			strftime(when, sizeof(when), "%Y-%m-%dT%H:%M:%SZ", &tm);
		n = snprintf(line, sizeof(line), "strayrigd pid %ld, owner "
			     "%s, since %s\n", (long)getpid(), owner, when);
	}
	if (ftruncate(fd, 0) != 0 || pwrite(fd, line, (size_t)n, 0) != n) {
		/* The lock holds all the same; only the note is missing. */
	}
	l->fd[l->n++] = fd;
	return RIG_OK;
}

int rig_devlock_take(struct rig_devlock *l, const struct rig_config *cfg,
		     const char *owner, struct rig_error *err)
{
	const char *dir = cfg->lock_dir;
	char id[160];
	int i, rc = RIG_OK;

	memset(l, 0, sizeof(*l));
	if (!dir[0])
		return RIG_OK;
	snprintf(id, sizeof(id), "usb-%04x-%04x-%s", cfg->stage.usb.vid,
		 cfg->stage.usb.pid, cfg->stage.serial);
	rc = take_one(l, dir, "stage", id, owner, err);
	snprintf(id, sizeof(id), "hid-%04x-%04x-%s", cfg->wheel.vid,
		 cfg->wheel.pid, cfg->wheel.serial);
	if (rc == RIG_OK)
		rc = take_one(l, dir, "wheel", id, owner, err);
	snprintf(id, sizeof(id), "usb-%04x-%04x-%s", cfg->camera.usb.vid,
		 cfg->camera.usb.pid, cfg->camera.serial);
	if (rc == RIG_OK)
		rc = take_one(l, dir, "camera", id, owner, err);
	snprintf(id, sizeof(id), "hid-%04x-%04x-%s", cfg->monitor.vid,
		 cfg->monitor.pid, cfg->monitor.serial);
	if (rc == RIG_OK && cfg->monitor.enabled)
		rc = take_one(l, dir, "monitor", id, owner, err);
	for (i = 0; rc == RIG_OK && i < RIG_LINE_COUNT; i++) {
		snprintf(id, sizeof(id), "gpio-%s-%s", cfg->lines[i].chip,
			 cfg->lines[i].line);
		rc = take_one(l, dir, "gpio line", id, owner, err);
	}
	if (rc != RIG_OK)
		rig_devlock_release(l);
	return rc;
}

void rig_devlock_release(struct rig_devlock *l)
{
	int i;

	for (i = 0; i < l->n; i++)
		close(l->fd[i]);
	l->n = 0;
}
