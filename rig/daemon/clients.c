/*
 * clients.c - strayrigd's control connections (daemon.h), none of which
 * can stall another or the daemon.  Every socket is non-blocking and one
 * poll() covers the listener and all clients; each client has its own
 * input buffer and one deadline, from its accept, by which its request
 * line must have arrived and its answer gone out, else it is dropped.  A
 * request is handled the moment its line is complete, so `safe`, `abort`
 * and `status` wait for no other client: a client trickling bytes, or
 * many idle ones, cost a poll entry each.  When every slot is taken the
 * oldest client is dropped to admit a new one.
 */
#define _DEFAULT_SOURCE	/* MSG_NOSIGNAL */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "rig/daemon.h"

static long long now_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void client_drop(struct rig_client *c)
{
	if (c->fd >= 0)
		close(c->fd);
	free(c->out);
	c->fd = -1;
	c->out = NULL;
	c->n_in = c->n_out = c->off = 0;
}

void rig_clients_init(struct rig_daemon *d)
{
	int i;

	for (i = 0; i < RIG_CLIENTS_MAX; i++) {
		d->clients[i].fd = -1;
		d->clients[i].out = NULL;
	}
}

void rig_clients_close(struct rig_daemon *d)
{
	int i;

	for (i = 0; i < RIG_CLIENTS_MAX; i++)
		client_drop(&d->clients[i]);
}

/* A free slot, or the oldest client's (dropped). */
static struct rig_client *slot(struct rig_daemon *d)
{
	struct rig_client *old = &d->clients[0];
	int i;

	for (i = 0; i < RIG_CLIENTS_MAX; i++) {
		if (d->clients[i].fd < 0)
			return &d->clients[i];
		if (d->clients[i].deadline_ms < old->deadline_ms)
			old = &d->clients[i];
	}
	client_drop(old);
	return old;
}

static void client_read(struct rig_daemon *d, struct rig_client *c);

static void accept_all(struct rig_daemon *d, long long now)
{
	struct rig_client *c;
	int fd;

	while ((fd = accept(d->listen_fd, NULL, NULL)) >= 0) {
		if (fcntl(fd, F_SETFL, O_NONBLOCK) != 0 ||
		    fcntl(fd, F_SETFD, FD_CLOEXEC) != 0) {
			close(fd);
			continue;
		}
		c = slot(d);
		c->fd = fd;
		c->deadline_ms = now + RIG_CLIENT_DEADLINE_MS;
		client_read(d, c);	/* a request may be there already */
	}
}

/* Send what is pending; drop the client once all is sent or it fails. */
static void client_write(struct rig_client *c)
{
	ssize_t k;

	while (c->off < c->n_out) {
		k = send(c->fd, c->out + c->off, c->n_out - c->off,
			 MSG_NOSIGNAL);
		if (k < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
			return;		/* POLLOUT will bring us back */
		if (k <= 0)
			break;
		c->off += (size_t)k;
	}
	client_drop(c);
}

static void answer(struct rig_daemon *d, struct rig_client *c, int too_long)
{
	char *resp;
	size_t len;

	c->in[c->n_in] = '\0';
	resp = too_long ? strdup("{\"ok\":false,\"error\":\"request too "
				 "long\"}")
			: rig_control_handle(d, c->in);
	len = resp ? strlen(resp) : 0;
	c->out = resp ? realloc(resp, len + 2) : NULL;
	if (!c->out) {
		free(resp);
		client_drop(c);
		return;
	}
	c->out[len] = '\n';
	c->n_out = len + 1;
	c->off = 0;
	client_write(c);
}

/* Take what the client has sent; answer once its line is complete (or
 * it closed its side after a partial line). */
static void client_read(struct rig_daemon *d, struct rig_client *c)
{
	size_t room;
	ssize_t k;
	char *nl;

	for (;;) {
		room = RIG_REQUEST_MAX - c->n_in;
		if (room == 0) {
			answer(d, c, 1);
			return;
		}
		k = recv(c->fd, c->in + c->n_in, room, 0);
		if (k < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
			return;
		if (k <= 0) {
			if (k == 0 && c->n_in > 0)
				answer(d, c, 0);
			else
				client_drop(c);
			return;
		}
		nl = memchr(c->in + c->n_in, '\n', (size_t)k);
		c->n_in += (size_t)k;
		if (nl) {
			c->n_in = (size_t)(nl - c->in);
			answer(d, c, 0);
			return;
		}
	}
}

/* Milliseconds poll may sleep: at most max_ms, less if a deadline is
 * nearer. */
static int wait_ms(const struct rig_daemon *d, long long now, int max_ms)
{
	long long t = max_ms;
	int i;

	for (i = 0; i < RIG_CLIENTS_MAX; i++)
		if (d->clients[i].fd >= 0 &&
		    d->clients[i].deadline_ms - now < t)
			t = d->clients[i].deadline_ms - now;
	return t < 0 ? 0 : (int)t;
}

void rig_clients_run(struct rig_daemon *d, int max_wait_ms)
{
	struct pollfd p[RIG_CLIENTS_MAX + 1];
	struct rig_client *map[RIG_CLIENTS_MAX + 1];
	int i, n = 1;
	long long now = now_ms();

	p[0].fd = d->listen_fd;
	p[0].events = POLLIN;
	for (i = 0; i < RIG_CLIENTS_MAX; i++) {
		struct rig_client *c = &d->clients[i];

		if (c->fd < 0)
			continue;
		p[n].fd = c->fd;
		p[n].events = c->out ? POLLOUT : POLLIN;
		map[n++] = c;
	}
	if (poll(p, (nfds_t)n, wait_ms(d, now, max_wait_ms)) < 0)
		return;		/* a signal: the caller checks its flags */
	for (i = 1; i < n; i++) {
		if (!p[i].revents)
			continue;
		if (map[i]->out)
			client_write(map[i]);
		else
			client_read(d, map[i]);
	}
	now = now_ms();
	for (i = 0; i < RIG_CLIENTS_MAX; i++)
		if (d->clients[i].fd >= 0 && now >= d->clients[i].deadline_ms)
			client_drop(&d->clients[i]);
	if (p[0].revents & POLLIN)
		accept_all(d, now);
}
