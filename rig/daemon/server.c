/*
 * server.c - strayrigd's lifecycle and its Unix socket.  The socket is
 * created under a umask that leaves only the configured mode (0600 by
 * default), optionally handed to a configured group, and is the only
 * listener: no network port.  One request line
 * per connection; between requests a running sweep takes one frame per
 * loop, so control stays responsive without threads.
 */
#define _DEFAULT_SOURCE	/* struct sockaddr_un helpers */
#include <errno.h>
#include <grp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include "rig/daemon.h"

#define REQUEST_MAX 65536
#define IDLE_POLL_MS 200

int rig_daemon_start(struct rig_daemon *d, struct rig_error *err)
{
	int rc;

	d->is_sim = strcmp(d->cfg.backend, "sim") == 0;
	rc = d->is_sim ? rig_sim_init(&d->sim, &d->cfg, &d->hal)
		       : rig_hal_real_init(&d->hal);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "backend '%s': cannot start",
				     d->cfg.backend);
	rc = rig_lab_open(&d->lab, &d->cfg, &d->hal, err);
	if (rc != RIG_OK) {
		if (d->is_sim)
			rig_sim_fini(&d->sim);
		else
			rig_hal_real_fini(&d->hal);
	}
	return rc;
}

void rig_daemon_stop(struct rig_daemon *d)
{
	struct rig_error err;

	rig_error_clear(&err);
	if (rig_lab_safe(&d->lab, &err) != RIG_OK)
		fprintf(stderr, "strayrigd: safe state not confirmed: %s\n",
			err.msg);
	if (d->sweep_open)
		rig_sweep_close(&d->sweep);
	d->sweep_open = 0;
	rig_lab_close(&d->lab);
	if (d->is_sim)
		rig_sim_fini(&d->sim);
	else
		rig_hal_real_fini(&d->hal);
}

static int listen_on(const struct rig_config *cfg, struct rig_error *err)
{
	struct sockaddr_un addr;
	mode_t old;
	int fd, rc;

	memset(&addr, 0, sizeof(addr));
	addr.sun_family = AF_UNIX;
	if (strlen(cfg->socket_path) >= sizeof(addr.sun_path))
		return -rig_error_set(err, RIG_EINVAL, "%s: socket path too "
				      "long", cfg->socket_path);
	strcpy(addr.sun_path, cfg->socket_path);
	fd = socket(AF_UNIX, SOCK_STREAM, 0);
	if (fd < 0)
		return -rig_error_set(err, RIG_EIO, "socket: %s",
				      strerror(errno));
	unlink(cfg->socket_path);
	old = umask(0777 & ~(mode_t)cfg->socket_mode);
	rc = bind(fd, (struct sockaddr *)&addr, sizeof(addr));
	umask(old);
	if (rc != 0 || listen(fd, 8) != 0) {
		close(fd);
		return -rig_error_set(err, RIG_EIO, "%s: cannot listen: %s",
				      cfg->socket_path, strerror(errno));
	}
	if (cfg->socket_group[0]) {
		struct group *g = getgrnam(cfg->socket_group);

		if (!g || chown(cfg->socket_path, (uid_t)-1, g->gr_gid) != 0) {
			close(fd);
			unlink(cfg->socket_path);
			return -rig_error_set(err, RIG_EINVAL,
				"%s: socket_group '%s': cannot give the socket "
				"to it", cfg->path, cfg->socket_group);
		}
	}
	return fd;
}

/* Read one request line (bounded, 1 s receive timeout), answer it. */
static void serve_client(struct rig_daemon *d, int fd)
{
	struct timeval tv = { 1, 0 };
	char *buf = malloc(REQUEST_MAX + 1), *resp;
	size_t n = 0;
	ssize_t k;

	setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
	while (buf && n < REQUEST_MAX &&
	       (k = read(fd, buf + n, REQUEST_MAX - n)) > 0) {
		n += (size_t)k;
		if (memchr(buf + n - k, '\n', (size_t)k))
			break;
	}
	if (!buf) {
		close(fd);
		return;
	}
	buf[n] = '\0';
	if (n == REQUEST_MAX)
		resp = strdup("{\"ok\":false,\"error\":\"request too long\"}");
	else
		resp = rig_control_handle(d, buf);
	if (resp) {
		size_t len = strlen(resp);

		if (write(fd, resp, len) != (ssize_t)len ||
		    write(fd, "\n", 1) != 1)
			fprintf(stderr, "strayrigd: client went away\n");
	}
	free(resp);
	free(buf);
	close(fd);
}

int rig_daemon_serve(struct rig_daemon *d, volatile int *stop,
		     struct rig_error *err)
{
	struct pollfd p;
	int lfd = listen_on(&d->cfg, err);

	if (lfd < 0)
		return -lfd;
	while (!d->quit && !*stop) {
		p.fd = lfd;
		p.events = POLLIN;
		p.revents = 0;
		if (poll(&p, 1, d->state == RIG_RUNNING ? 0 : IDLE_POLL_MS) > 0
		    && (p.revents & POLLIN)) {
			int c = accept(lfd, NULL, NULL);

			if (c >= 0)
				serve_client(d, c);
		}
		rig_daemon_work(d);
	}
	close(lfd);
	unlink(d->cfg.socket_path);
	return RIG_OK;
}
