/*
 * evlog.c - strayrigd's event log (daemon.h): start, the plan, each fault
 * and what was done about it, completion, operator commands, with the
 * owner, each line stamped in UTC.  Every line goes to stderr, to the
 * system log (syslog, facility daemon) and, while a sweep is open, to
 * DIR/events.log beside its frames, so the folder carries its own
 * history: a recovery is a line saying what failed and when, not a
 * count.  events.log is appended one write per line (O_APPEND), so a
 * kill -9 leaves at worst a torn last line, and the sweep store never
 * takes it for a frame.
 */
#define _DEFAULT_SOURCE	/* vsyslog */
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <syslog.h>
#include <time.h>
#include <unistd.h>

#include "rig/daemon.h"

void rig_daemon_log(struct rig_daemon *d, int level, const char *fmt, ...)
{
	static int opened;
	static const int prio[] = { LOG_INFO, LOG_WARNING, LOG_ERR };
	static const char *const tag[] = { "info", "warn", "error" };
	char msg[1024], when[40], line[1200], path[STRAY_SWEEP_DIR_MAX + 32];
	int w;
	va_list ap;
	int fd, n;

	if (level < RIG_LOG_INFO || level > RIG_LOG_ERR)
		level = RIG_LOG_ERR;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	if (!(d && d->quiet_info && level == RIG_LOG_INFO))
		fprintf(stderr, "strayrigd: %s\n", msg);
	if (!opened) {
		openlog("strayrigd", LOG_PID | LOG_NDELAY, LOG_DAEMON);
		opened = 1;
	}
	syslog(prio[level], "%s", msg);
	if (!d || !d->sweep_open)
		return;
	rig_utc_stamp(when, sizeof(when));
	n = snprintf(line, sizeof(line), "%s %s %s\n", when, tag[level], msg);
	if (n <= 0 || (size_t)n >= sizeof(line))
		n = (int)strlen(line);
	w = snprintf(path, sizeof(path), "%s/%s", d->sweep.mf.dir,
		     RIG_EVENTS_LOG);
	if (w < 0 || (size_t)w >= sizeof(path))
		return;
	fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC |
		  O_NOFOLLOW, 0644);
	if (fd < 0)
		return;	/* the log must never stop the sweep */
	if (write(fd, line, (size_t)n) != n) {
		/* nothing better to do: stderr and syslog have it */
	}
	close(fd);
}

void rig_daemon_log_start(struct rig_daemon *d, int resumed)
{
	const struct rig_sweep *sw = &d->sweep;
	const struct rig_sweep_cfg *c = sw->cfg;
	struct rig_progress p;
	double lo = 0, hi = 0;
	int i, returns = 0;

	for (i = 0; i < sw->n_angles; i++) {
		lo = i ? fmin(lo, sw->angles[i]) : sw->angles[i];
		hi = i ? fmax(hi, sw->angles[i]) : sw->angles[i];
		returns += sw->visit_no[i] > 0;
	}
	rig_sweep_progress(sw, &p);
	rig_daemon_log(d, RIG_LOG_INFO, "sweep %s in %s by %s: %d angles "
		       "%g..%g deg (%d returns), %d repeats, t %g-%g s; %ld of "
		       "about %ld frames already taken",
		       resumed ? "resumed" : "started", sw->mf.dir, sw->owner,
		       sw->n_angles, lo, hi, returns, c->repeats, c->t_min_s,
		       c->t_max_s, p.done, p.total);
}

void rig_daemon_log_end(struct rig_daemon *d, const char *how)
{
	struct rig_progress p;

	rig_sweep_progress(&d->sweep, &p);
	rig_daemon_log(d, RIG_LOG_INFO, "sweep %s: %s, %ld frames (%ld this "
		       "run) in %.0f s lab time, %u recoveries, %u CRC "
		       "re-reads", how, d->sweep.mf.dir, (long)d->sweep.mf.n,
		       d->sweep.taken, p.elapsed_s, d->lab.recoveries,
		       d->lab.crc_rereads + d->lab.camera.crc_rereads);
}

void rig_daemon_lab_event(void *ctx, int recovered, const char *msg)
{
	rig_daemon_log(ctx, recovered ? RIG_LOG_INFO : RIG_LOG_WARN, "%s",
		       msg);
}
