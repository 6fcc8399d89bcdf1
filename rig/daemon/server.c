/*
 * server.c - strayrigd's lifecycle and its serving loop.  The socket is
 * claimed by listen.c, its connections served by clients.c, one request
 * line per connection; between poll rounds a running sweep takes one
 * frame, so control stays responsive without threads.
 */
#include <stdio.h>
#include <string.h>

#include "rig/daemon.h"

#define IDLE_POLL_MS 200

static void hal_fini(struct rig_daemon *d)
{
	if (d->is_sim)
		rig_sim_fini(&d->sim);
	else if (strcmp(d->cfg.backend, "real") == 0)
		rig_hal_real_fini(&d->hal);
}

int rig_daemon_start(struct rig_daemon *d, struct rig_error *err)
{
	int rc;

	d->is_sim = strcmp(d->cfg.backend, "sim") == 0;
	rc = RIG_OK;
	if (strcmp(d->cfg.backend, "indi") == 0)
		rig_hal_indi_init(&d->hal);	/* a clock; no fini */
	else
		rc = d->is_sim ? rig_sim_init(&d->sim, &d->cfg, &d->hal)
			       : rig_hal_real_init(&d->hal);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "backend '%s': cannot start",
				     d->cfg.backend);
	rc = rig_lab_open(&d->lab, &d->cfg, &d->hal, err);
	if (rc == RIG_OK) {
		d->lab.on_event = rig_daemon_lab_event;
		d->lab.event_ctx = d;
		rig_daemon_log(d, RIG_LOG_INFO, "started by %s: backend %s, "
			       "config %s, %s%s; devices checked, lab safe",
			       d->owner, d->cfg.backend,
			       d->cfg.path[0] ? d->cfg.path : "(defaults)",
			       d->listen_fd >= 0 ? "socket " : "one sweep",
			       d->listen_fd >= 0 ? d->cfg.socket_path : "");
	}
	if (rc != RIG_OK)
		hal_fini(d);
	return rc;
}

void rig_daemon_stop(struct rig_daemon *d)
{
	struct rig_error err;
	char line[320];

	rig_error_clear(&err);
	if (rig_lab_safe(&d->lab, &err) != RIG_OK ||
	    !rig_daemon_safe_line(d, line, sizeof(line))) {
		rig_daemon_safe_line(d, line, sizeof(line));
		rig_daemon_log(d, RIG_LOG_ERR, "%s%s%s", line,
			       err.msg[0] ? ": " : "", err.msg);
	}
	if (d->sweep_open)
		rig_sweep_close(&d->sweep);
	d->sweep_open = 0;
	rig_lab_close(&d->lab);
	hal_fini(d);
}

int rig_daemon_serve(struct rig_daemon *d, volatile int *stop,
		     struct rig_error *err)
{
	(void)err;
	rig_clients_init(d);
	while (!d->quit && !*stop) {
		rig_clients_run(d, d->state == RIG_RUNNING ? 0 : IDLE_POLL_MS);
		rig_daemon_work(d);
	}
	rig_clients_close(d);
	return RIG_OK;
}
