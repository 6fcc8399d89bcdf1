/*
 * strayrigd.c - the lab sweep daemon.
 *
 *   strayrigd --config FILE [--socket PATH]     serve the control socket
 *   strayrigd --config FILE --sweep DIR [--resume [--force-plan]]
 *                                              one sweep, then exit
 *
 * The socket and every device (a lab-wide lock per device, devlock.h)
 * are claimed before the lab is touched: a second daemon on the same
 * socket or devices is refused at once and never drives them.  A sweep
 * folder is made only after the devices answered and the config passed
 * the check against them (rig_lab_check).  Exit 0 done, 1 refused because in use (a
 * live socket, a folder another writer holds) or a device/I/O failure,
 * 2 bad input (config, arguments, a path that is not a socket, a resume
 * whose plan differs from the folder's plan.json).
 *
 * On SIGINT, SIGTERM or SIGHUP the current step finishes, the lab is made
 * safe (lamp off, beam blocked, shutter closed, stage stopped) and the
 * daemon exits.  At start the lab is made safe before anything else, so
 * a restart after kill -9 begins from a safe state too.
 */
#include <getopt.h>
#include <pwd.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rig/daemon.h"

static volatile int stop_flag;

static void on_signal(int sig)
{
	(void)sig;
	stop_flag = 1;
}

static void usage(FILE *out)
{
	fprintf(out,
		"usage: strayrigd --config FILE [--socket PATH]\n"
		"       strayrigd --config FILE --sweep DIR [--resume "
		"[--force-plan]]\n\n"
		"  -c, --config FILE   JSON configuration (docs/rig-config.md)\n"
		"  -s, --socket PATH   control socket (overrides the config)\n"
		"  -w, --sweep DIR     run one sweep into DIR and exit\n"
		"  -r, --resume        continue the sweep already in DIR\n"
		"  -f, --force-plan    resume even if the config's plan "
		"differs from DIR/plan.json\n"
		"  -h, --help          this text\n");
}

static void install_signals(void)
{
	struct sigaction sa;

	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	sigaction(SIGHUP, &sa, NULL);
	signal(SIGPIPE, SIG_IGN);
}

/* The folder claimed once the lab answered (rig_sweep_claim_as). */
static int run_sweep(struct rig_daemon *d, int resumed, struct rig_error *err)
{
	struct rig_progress p;
	char line[320];
	int rc = rig_sweep_attach(&d->sweep, &d->lab, err);

	d->sweep_open = rc == RIG_OK;	/* attach closes it on failure */
	if (rc != RIG_OK)
		return rc;
	rig_daemon_log_start(d, resumed);
	while (rc == RIG_OK && !d->sweep.finished && !stop_flag) {
		rc = rig_sweep_step(&d->sweep, err);
		rig_sweep_progress(&d->sweep, &p);
		fprintf(stderr, "strayrigd: %ld/%ld frames (%.1f %%), theta "
			"%.3f deg, %s, eta %.0f s\n", p.done, p.total,
			p.percent, p.theta_deg, p.step, p.eta_s);
	}
	if (rc == RIG_OK && stop_flag)
		rc = rig_error_set(err, RIG_ESTATE,
				   "interrupted; lab made safe, resume with "
				   "--resume");
	if (rc != RIG_OK) {
		rig_daemon_safe_line(d, line, sizeof(line));
		rig_daemon_log(d, RIG_LOG_ERR, "sweep stopped: %s; %s",
			       err->msg, line);
	}
	rig_daemon_log_end(d, rc == RIG_OK ? "complete" : "stopped");
	rig_sweep_progress(&d->sweep, &p);
	fprintf(stderr, "strayrigd: sweep %s: %ld frames (%ld this run) in "
		"%.0f s lab time, %u recoveries, %u CRC re-reads, %u faults "
		"injected\n", rc == RIG_OK ? "complete" : "stopped",
		(long)d->sweep.mf.n, d->sweep.taken, p.elapsed_s,
		d->lab.recoveries, d->lab.crc_rereads +
		d->lab.camera.crc_rereads,
		d->is_sim ? rig_sim_faults_fired(&d->sim) : 0);
	return rc;
}

static int exit_code(int rc)
{
	return rc == RIG_OK ? 0 : rc == RIG_EPARSE || rc == RIG_EINVAL ? 2 : 1;
}

/* The user the daemon runs as: the owner of a --sweep sweep and of the
 * device locks. */
static void own_name(char *out, size_t size)
{
	struct passwd *pw = getpwuid(getuid());

	snprintf(out, size, "%s", pw && pw->pw_name ? pw->pw_name : "?");
}

/* Claim the socket (socket mode) and every device, before the lab is
 * touched: nothing else may hold them. */
static int claim(struct rig_daemon *d, const char *dir, struct rig_error *err)
{
	int rc;

	d->listen_fd = d->sock_lock_fd = -1;
	if (!dir && (rc = rig_daemon_listen(d, err)) != RIG_OK)
		return rc;
	rc = rig_devlock_take(&d->devlock, &d->cfg, d->owner, err);
	if (rc != RIG_OK)
		rig_daemon_unlisten(d);
	return rc;
}

int main(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "config", required_argument, NULL, 'c' },
		{ "socket", required_argument, NULL, 's' },
		{ "sweep", required_argument, NULL, 'w' },
		{ "resume", no_argument, NULL, 'r' },
		{ "force-plan", no_argument, NULL, 'f' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	static struct rig_daemon d;
	const char *config = NULL, *sock = NULL, *dir = NULL;
	struct rig_error err;
	int opt, flags = 0, rc;

	while ((opt = getopt_long(argc, argv, "c:s:w:rfh", opts, NULL)) != -1) {
		switch (opt) {
		case 'c': config = optarg; break;
		case 's': sock = optarg; break;
		case 'w': dir = optarg; break;
		case 'r': flags |= RIG_SWEEP_RESUME; break;
		case 'f': flags |= RIG_SWEEP_FORCE_PLAN; break;
		case 'h': usage(stdout); return 0;
		default: usage(stderr); return 2;
		}
	}
	if (optind != argc) {
		fprintf(stderr, "strayrigd: unexpected argument '%s'\n",
			argv[optind]);
		return 2;
	}
	rig_error_clear(&err);
	rig_config_defaults(&d.cfg);
	if (config && rig_config_load(&d.cfg, config, &err) != RIG_OK) {
		fprintf(stderr, "strayrigd: %s\n", err.msg);
		return 2;
	}
	if (sock)
		snprintf(d.cfg.socket_path, sizeof(d.cfg.socket_path), "%s",
			 sock);
	/* Test beds and CI runs on one machine each lock their own
	 * emulated lab, not the real one's /run/lock. */
	if (getenv("STRAYRIGD_LOCK_DIR"))
		snprintf(d.cfg.lock_dir, sizeof(d.cfg.lock_dir), "%s",
			 getenv("STRAYRIGD_LOCK_DIR"));
	if ((rc = rig_config_env(&d.cfg, &err)) != RIG_OK) {
		fprintf(stderr, "strayrigd: %s\n", err.msg);
		return 2;
	}
	install_signals();
	own_name(d.owner, sizeof(d.owner));
	d.quiet_info = dir != NULL;
	if ((rc = claim(&d, dir, &err)) != RIG_OK) {
		fprintf(stderr, "strayrigd: %s\n", err.msg);
		return exit_code(rc);
	}
	if ((rc = rig_daemon_start(&d, &err)) != RIG_OK) {
		fprintf(stderr, "strayrigd: %s\n", err.msg);
		rig_devlock_release(&d.devlock);
		rig_daemon_unlisten(&d);
		return exit_code(rc);
	}
	/* The folder only once the devices have answered and passed the
	 * config check: a refused start leaves nothing on disk. */
	if (dir) {
		rc = rig_sweep_claim_as(&d.sweep, &d.cfg, dir, flags, d.owner,
					&err);
		d.sweep_open = rc == RIG_OK;
		if (rc == RIG_OK)
			rc = run_sweep(&d, flags & RIG_SWEEP_RESUME, &err);
	} else {
		rc = rig_daemon_serve(&d, &stop_flag, &err);
	}
	rig_daemon_stop(&d);
	rig_daemon_unlisten(&d);
	rig_devlock_release(&d.devlock);
	if (rc != RIG_OK) {
		fprintf(stderr, "strayrigd: %s\n", err.msg);
		return exit_code(rc);
	}
	return 0;
}
