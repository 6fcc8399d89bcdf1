/*
 * listen.c - claim strayrigd's control socket (daemon.h).  One daemon per
 * socket path: an exclusive flock on PATH.lock, held for the daemon's
 * life, comes first, so two daemons starting together cannot both pass
 * the checks.  Then what sits at PATH decides: a socket somebody answers
 * on is refused (another daemon owns it), anything that is not a socket
 * (a regular file, a folder) is refused and left alone, and only a stale
 * socket (nobody listening) is removed and replaced.  The socket is made
 * under a umask that leaves only the configured mode (0600 by default)
 * and optionally handed to a configured group; no network port.
 */
#define _DEFAULT_SOURCE	/* flock, struct sockaddr_un */
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "rig/daemon.h"

#define BACKLOG 16

static int address(const char *path, struct sockaddr_un *a,
		   struct rig_error *err)
{
	memset(a, 0, sizeof(*a));
	a->sun_family = AF_UNIX;
	if (strlen(path) >= sizeof(a->sun_path))
		return rig_error_set(err, RIG_EINVAL, "%s: socket path too "
				     "long", path);
	strcpy(a->sun_path, path);
	return RIG_OK;
}

/* 1 when a listener answers at a (a live socket). */
static int answered(const struct sockaddr_un *a)
{
	int fd = socket(AF_UNIX, SOCK_STREAM, 0), live;

	if (fd < 0)
		return 1;	/* cannot tell: do not replace it */
	live = connect(fd, (const struct sockaddr *)a, sizeof(*a)) == 0 ||
	       (errno != ECONNREFUSED && errno != ENOENT);
	close(fd);
	return live;
}

/* The per-path lock: PATH.lock, flocked for the daemon's life. */
static int take_lock(const char *path, struct rig_error *err)
{
	char lock[RIG_PATH_MAX + 8];
	int fd;

	snprintf(lock, sizeof(lock), "%s.lock", path);
	fd = open(lock, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
	if (fd < 0)
		return -rig_error_set(err, RIG_EIO, "%s: cannot open: %s",
				      lock, strerror(errno));
	if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
		close(fd);
		return -rig_error_set(err, RIG_ESTATE, "%s: socket in use by "
				      "another strayrigd; not taken over",
				      path);
	}
	return fd;
}

/* What is at the path may be replaced: nothing, or a stale socket. */
static int check_path(const char *path, const struct sockaddr_un *a,
		      struct rig_error *err)
{
	struct stat st;

	if (lstat(path, &st) != 0)
		return errno == ENOENT ? RIG_OK
		       : rig_error_set(err, RIG_EIO, "%s: %s", path,
				       strerror(errno));
	if (!S_ISSOCK(st.st_mode))
		return rig_error_set(err, RIG_EINVAL, "%s: exists and is not "
				     "a socket; not replaced", path);
	if (answered(a))
		return rig_error_set(err, RIG_ESTATE, "%s: a daemon answers "
				     "on this socket; not taken over", path);
	if (unlink(path) != 0)
		return rig_error_set(err, RIG_EIO, "%s: stale socket cannot "
				     "be removed: %s", path, strerror(errno));
	return RIG_OK;
}

static int give_group(const struct rig_config *cfg, struct rig_error *err)
{
	struct group *g;

	if (!cfg->socket_group[0])
		return RIG_OK;
	g = getgrnam(cfg->socket_group);
	if (g && chown(cfg->socket_path, (uid_t)-1, g->gr_gid) == 0)
		return RIG_OK;
	return rig_error_set(err, RIG_EINVAL, "%s: socket_group '%s': cannot "
			     "give the socket to it", cfg->path,
			     cfg->socket_group);
}

static int bind_listen(const struct rig_config *cfg,
		       const struct sockaddr_un *a, struct rig_error *err)
{
	mode_t old;
	int fd, rc;

	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
	if (fd < 0)
		return -rig_error_set(err, RIG_EIO, "socket: %s",
				      strerror(errno));
	old = umask(0777 & ~(mode_t)cfg->socket_mode);
	rc = bind(fd, (const struct sockaddr *)a, sizeof(*a));
	umask(old);
	if (rc != 0 || listen(fd, BACKLOG) != 0) {
		rc = -rig_error_set(err, RIG_EIO, "%s: cannot listen: %s",
				    cfg->socket_path, strerror(errno));
		close(fd);
		return rc;
	}
	if (give_group(cfg, err) != RIG_OK) {
		close(fd);
		unlink(cfg->socket_path);
		return -err->code;
	}
	return fd;
}

int rig_daemon_listen(struct rig_daemon *d, struct rig_error *err)
{
	struct sockaddr_un a;
	int rc;

	d->listen_fd = d->sock_lock_fd = -1;
	if ((rc = address(d->cfg.socket_path, &a, err)) != RIG_OK)
		return rc;
	d->sock_lock_fd = take_lock(d->cfg.socket_path, err);
	if (d->sock_lock_fd < 0)
		return -d->sock_lock_fd;
	rc = check_path(d->cfg.socket_path, &a, err);
	if (rc == RIG_OK) {
		d->listen_fd = bind_listen(&d->cfg, &a, err);
		rc = d->listen_fd < 0 ? -d->listen_fd : RIG_OK;
	}
	if (rc != RIG_OK) {
		close(d->sock_lock_fd);
		d->sock_lock_fd = -1;
		d->listen_fd = -1;
	}
	return rc;
}

void rig_daemon_unlisten(struct rig_daemon *d)
{
	if (d->listen_fd >= 0) {
		close(d->listen_fd);
		unlink(d->cfg.socket_path);	/* ours: we hold its lock */
	}
	if (d->sock_lock_fd >= 0)
		close(d->sock_lock_fd);
	d->listen_fd = d->sock_lock_fd = -1;
}
