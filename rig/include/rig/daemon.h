/*
 * daemon.h - strayrigd's state and its control protocol.
 *
 * Requests and responses are one JSON object per line on a Unix socket
 * (created 0600 unless configured; no network listener):
 *   {"cmd":"status"} {"cmd":"home"} {"cmd":"move","theta_deg":12.5}
 *   {"cmd":"sweep","dir":"/data/s1","resume":false,"force_plan":false}
 *   {"cmd":"pause"} {"cmd":"resume"} {"cmd":"abort"} {"cmd":"safe"}
 *   {"cmd":"shutdown"}
 * Every response has "ok" (bool); a refusal or failure has "error", one
 * line.  Commands that would break an interlock (a move during a sweep,
 * an angle outside the limits) are refused.
 */
#ifndef RIG_DAEMON_H
#define RIG_DAEMON_H

#include <stddef.h>

#include "rig/config.h"
#include "rig/devlock.h"
#include "rig/lab.h"
#include "rig/sim.h"
#include "rig/sweep.h"

enum rig_run_state { RIG_IDLE, RIG_RUNNING, RIG_PAUSED, RIG_FAULTED };

/* Control connections: at most RIG_CLIENTS_MAX at once (the oldest is
 * dropped for a new one), a request line of at most RIG_REQUEST_MAX
 * bytes, and RIG_CLIENT_DEADLINE_MS from accept to the answer sent. */
#define RIG_CLIENTS_MAX 32
#define RIG_REQUEST_MAX 4096
#define RIG_CLIENT_DEADLINE_MS 2000

struct rig_client {
	int fd;				/* -1: free */
	char in[RIG_REQUEST_MAX + 1];
	size_t n_in;
	char *out;			/* the answer line, once handled */
	size_t n_out, off;
	long long deadline_ms;		/* CLOCK_MONOTONIC */
};

struct rig_daemon {
	struct rig_config cfg;
	struct rig_hal hal;
	struct rig_sim sim;
	int is_sim;
	struct rig_lab lab;
	struct rig_sweep sweep;
	int sweep_open;
	enum rig_run_state state;
	char last_error[RIG_ERROR_MSG_MAX];
	char fault_utc[40];		/* when the last fault came */
	int quit;
	int listen_fd, sock_lock_fd;	/* rig_daemon_listen */
	struct rig_devlock devlock;	/* every device, lab-wide */
	char owner[RIG_NAME_MAX];	/* the daemon's user, or a sweep's */
	int quiet_info;			/* --sweep: info lines not on stderr
					 * (its progress lines are there) */
	struct rig_client clients[RIG_CLIENTS_MAX];
};

/* Bring up the backend and the lab (made safe at once). */
int rig_daemon_start(struct rig_daemon *d, struct rig_error *err);
/* Lab safe, sweep closed, devices closed, backend down. */
void rig_daemon_stop(struct rig_daemon *d);

enum rig_cmd { RIG_CMD_STATUS, RIG_CMD_HOME, RIG_CMD_MOVE, RIG_CMD_SWEEP,
	       RIG_CMD_PAUSE, RIG_CMD_RESUME, RIG_CMD_ABORT, RIG_CMD_SAFE,
	       RIG_CMD_SHUTDOWN, RIG_CMD_COUNT };

struct rig_request {
	int cmd;		/* enum rig_cmd */
	double theta_deg;	/* move */
	char dir[RIG_PATH_MAX];	/* sweep */
	int resume;		/* sweep */
	int force_plan;		/* sweep: resume even if the plan changed */
	char owner[48];		/* who asks ("" unknown): log, sweep owner */
};

/* Parse and check one request line (pure: no lab, no files).  On error
 * returns RIG_EPARSE with a one-line reason in msg. */
int rig_request_parse(const char *text, struct rig_request *req, char *msg,
		      size_t size);
const char *rig_cmd_name(int cmd);

/* Handle one request line; returns a malloc'd JSON response line. */
char *rig_control_handle(struct rig_daemon *d, const char *request);

/* One unit of background work: a sweep step when running. */
void rig_daemon_work(struct rig_daemon *d);

/*
 * Claim the control socket (listen.c): refused if another daemon holds
 * the path's lock (PATH.lock) or answers on the socket (RIG_ESTATE), or
 * if PATH is not a socket (RIG_EINVAL; never deleted); a stale socket is
 * replaced.  Done before the lab is touched.
 */
int rig_daemon_listen(struct rig_daemon *d, struct rig_error *err);
/* Close the socket, remove it and release its lock. */
void rig_daemon_unlisten(struct rig_daemon *d);

/* Control connections (clients.c): one poll() round over the listener
 * and every client, waiting at most max_wait_ms. */
void rig_clients_init(struct rig_daemon *d);
void rig_clients_run(struct rig_daemon *d, int max_wait_ms);
void rig_clients_close(struct rig_daemon *d);

/* Serve the claimed socket until shutdown or *stop becomes nonzero. */
int rig_daemon_serve(struct rig_daemon *d, volatile int *stop,
		     struct rig_error *err);

/* The event log (evlog.c): one line, stamped in UTC, to stderr, syslog
 * and (a sweep open) DIR/events.log. */
enum rig_log_level { RIG_LOG_INFO, RIG_LOG_WARN, RIG_LOG_ERR };
#define RIG_EVENTS_LOG "events.log"
void rig_daemon_log(struct rig_daemon *d, int level, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* The sweep's start (its plan, owner, frames already there) and end. */
void rig_daemon_log_start(struct rig_daemon *d, int resumed);
void rig_daemon_log_end(struct rig_daemon *d, const char *how);
/* rig_lab's on_event: retries as warnings, recoveries as info. */
void rig_daemon_lab_event(void *ctx, int recovered, const char *msg);

/* The lab's safe state in one phrase (both modes say the same): 1 and
 * "lab safe (...)" when every line read back safe, else 0 and "safe state
 * NOT confirmed: lamp unknown, ...". */
int rig_daemon_safe_line(const struct rig_daemon *d, char *buf, size_t size);

#endif /* RIG_DAEMON_H */
