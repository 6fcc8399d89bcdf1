/*
 * control.c - strayrigd's request handler (daemon.h): a request parsed by
 * request.c is checked against the run state and the interlocks, acted
 * on, and answered with one JSON object.
 */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig/daemon.h"

static const char *const state_names[] = { "idle", "running", "paused",
					   "faulted" };

static void fail(cJSON *resp, const char *fmt, const char *arg)
{
	char msg[RIG_ERROR_MSG_MAX + 64];

	snprintf(msg, sizeof(msg), fmt, arg);
	cJSON_ReplaceItemInObject(resp, "ok", cJSON_CreateFalse());
	cJSON_AddStringToObject(resp, "error", msg);
}

/* Plain numbers: a time to 0.1 s, an angle to 1e-3 deg, not 17 digits. */
static double rounded(double x, double unit)
{
	return round(x / unit) * unit;
}

static void add_sweep(const struct rig_daemon *d, cJSON *resp)
{
	struct rig_progress p;
	cJSON *sw = cJSON_AddObjectToObject(resp, "sweep");

	rig_sweep_progress(&d->sweep, &p);
	cJSON_AddStringToObject(sw, "dir", d->sweep.mf.dir);
	cJSON_AddStringToObject(sw, "owner", d->sweep.owner);
	cJSON_AddNumberToObject(sw, "done", (double)p.done);
	cJSON_AddNumberToObject(sw, "total", (double)p.total);
	cJSON_AddNumberToObject(sw, "percent", rounded(p.percent, 0.1));
	cJSON_AddNumberToObject(sw, "angle_no", p.angle_no);
	cJSON_AddNumberToObject(sw, "n_angles", p.n_angles);
	cJSON_AddNumberToObject(sw, "theta_deg", rounded(p.theta_deg, 1e-3));
	cJSON_AddStringToObject(sw, "step", p.step);
	cJSON_AddNumberToObject(sw, "elapsed_s", rounded(p.elapsed_s, 0.1));
	cJSON_AddNumberToObject(sw, "eta_s", rounded(p.eta_s, 1));
	cJSON_AddBoolToObject(sw, "finished", p.finished);
}

/* A line's read-back state, null when it was not read back. */
static void add_line(cJSON *resp, const char *key, int state)
{
	if (state < 0)
		cJSON_AddNullToObject(resp, key);
	else
		cJSON_AddNumberToObject(resp, key, state);
}

static void status(const struct rig_daemon *d, cJSON *resp)
{
	static const int unknown[RIG_LINE_COUNT] = { -1, -1, -1 };
	const int *line = d->lab.open_mask & (1 << RIG_DEV_GPIO)
			  ? d->lab.lines.state : unknown;
	char why[200];
	int safe;

	cJSON_AddStringToObject(resp, "state", state_names[d->state]);
	if (isfinite(d->lab.theta_deg))
		cJSON_AddNumberToObject(resp, "theta_deg",
					rounded(d->lab.theta_deg, 1e-3));
	else
		cJSON_AddNullToObject(resp, "theta_deg");
	add_line(resp, "lamp", line[RIG_LINE_LAMP]);
	add_line(resp, "beam_blocked", line[RIG_LINE_BEAM_BLOCK]);
	add_line(resp, "shutter_open", line[RIG_LINE_SHUTTER]);
	safe = rig_lab_is_safe(&d->lab, why, sizeof(why));
	cJSON_AddBoolToObject(resp, "safe", safe);
	if (!safe)
		cJSON_AddStringToObject(resp, "unsafe", why);
	cJSON_AddNumberToObject(resp, "recoveries", d->lab.recoveries);
	if (d->last_error[0])
		cJSON_AddStringToObject(resp, "last_error", d->last_error);
	if (d->state == RIG_FAULTED && d->fault_utc[0])
		cJSON_AddStringToObject(resp, "faulted_since", d->fault_utc);
	if (d->sweep_open)
		add_sweep(d, resp);
}

static void end_sweep(struct rig_daemon *d)
{
	if (d->sweep_open)
		rig_sweep_close(&d->sweep);
	d->sweep_open = 0;
}

/* Act on a request that the state allows; failures go into resp. */
static void act(struct rig_daemon *d, const struct rig_request *req,
		cJSON *resp)
{
	const char *who = req->owner[0] ? req->owner : "?";
	struct rig_error err;
	char line[320];
	int rc = RIG_OK;

	rig_error_clear(&err);
	if (req->cmd != RIG_CMD_STATUS)
		rig_daemon_log(d, RIG_LOG_INFO, "command '%s'%s%s from %s",
			       rig_cmd_name(req->cmd),
			       req->cmd == RIG_CMD_SWEEP ? " " : "",
			       req->cmd == RIG_CMD_SWEEP ? req->dir : "", who);
	switch (req->cmd) {
	case RIG_CMD_STATUS:
		status(d, resp);
		return;
	case RIG_CMD_HOME:
		rc = rig_lab_home(&d->lab, &err);
		break;
	case RIG_CMD_MOVE:
		rc = rig_lab_move(&d->lab, req->theta_deg, &err);
		break;
	case RIG_CMD_SWEEP:
		end_sweep(d);
		rc = rig_sweep_open_as(&d->sweep, &d->lab, req->dir,
				       (req->resume ? RIG_SWEEP_RESUME : 0) |
				       (req->force_plan ? RIG_SWEEP_FORCE_PLAN
							: 0), who, &err);
		d->sweep_open = rc == RIG_OK;
		d->state = rc == RIG_OK ? RIG_RUNNING : RIG_IDLE;
		d->last_error[0] = '\0';
		if (rc == RIG_OK)
			rig_daemon_log_start(d, req->resume);
		break;
	case RIG_CMD_PAUSE:
		d->state = RIG_PAUSED;
		rc = rig_lab_safe(&d->lab, &err);
		break;
	case RIG_CMD_RESUME:
		d->state = RIG_RUNNING;
		d->last_error[0] = '\0';
		break;
	case RIG_CMD_SAFE:
		/* Safe, and the sweep kept: resume goes on where it stopped,
		 * abort drops it. */
		if (d->sweep_open && !d->sweep.finished)
			d->state = d->state == RIG_FAULTED ? RIG_FAULTED
							   : RIG_PAUSED;
		else
			d->state = RIG_IDLE;
		rc = rig_lab_safe(&d->lab, &err);
		if (d->sweep_open && !d->sweep.finished)
			cJSON_AddStringToObject(resp, "sweep_kept",
				"resume with 'stray rig resume', drop it "
				"with 'stray rig abort'");
		break;
	default:	/* abort, shutdown */
		if (d->sweep_open && !d->sweep.finished)
			rig_daemon_log(d, RIG_LOG_WARN, "sweep %s left "
				       "unfinished (%zu frames); resume it "
				       "with 'stray rig sweep DIR --resume'",
				       d->sweep.mf.dir, d->sweep.mf.n);
		end_sweep(d);
		d->state = RIG_IDLE;
		d->quit = req->cmd == RIG_CMD_SHUTDOWN;
		rc = rig_lab_safe(&d->lab, &err);
		break;
	}
	if (req->cmd >= RIG_CMD_PAUSE && req->cmd != RIG_CMD_RESUME) {
		int safe = rig_daemon_safe_line(d, line, sizeof(line));

		cJSON_AddBoolToObject(resp, "safe", safe && rc == RIG_OK);
		if (rc == RIG_OK && !safe)
			rc = rig_error_set(&err, RIG_EDEVICE, "%s", line);
	}
	if (rc != RIG_OK)
		fail(resp, "%s", err.msg);
}

/* Interlocks of the run state: returns the refusal text or NULL. */
static const char *refusal(const struct rig_daemon *d, int cmd)
{
	int busy = d->state == RIG_RUNNING || d->state == RIG_PAUSED;

	/* A faulted sweep is kept for resume; moving the stage meanwhile
	 * is allowed (to free it), a new sweep only after abort. */
	if (d->state == RIG_FAULTED && d->sweep_open && cmd == RIG_CMD_SWEEP)
		return "refused: '%s' while a faulted sweep is kept; resume "
		       "or abort it first";

	if (busy && (cmd == RIG_CMD_HOME || cmd == RIG_CMD_MOVE ||
		     cmd == RIG_CMD_SWEEP))
		return "refused: '%s' while a sweep is running; abort it first";
	if ((cmd == RIG_CMD_PAUSE && d->state != RIG_RUNNING) ||
	    (cmd == RIG_CMD_RESUME && (!d->sweep_open ||
		(d->state != RIG_PAUSED && d->state != RIG_FAULTED))))
		return "refused: '%s': no sweep to act on";
	return NULL;
}

char *rig_control_handle(struct rig_daemon *d, const char *request)
{
	static struct rig_request req;	/* large: keep it off the stack */
	cJSON *resp = cJSON_CreateObject();
	char msg[RIG_ERROR_MSG_MAX];
	const char *no;
	char *out;

	cJSON_AddTrueToObject(resp, "ok");
	if (rig_request_parse(request, &req, msg, sizeof(msg)) != RIG_OK)
		fail(resp, "%s", msg);
	else if ((no = refusal(d, req.cmd)) != NULL)
		fail(resp, no, rig_cmd_name(req.cmd));
	else
		act(d, &req, resp);
	out = cJSON_PrintUnformatted(resp);
	cJSON_Delete(resp);
	return out;
}

void rig_daemon_work(struct rig_daemon *d)
{
	struct rig_error err;

	if (d->state != RIG_RUNNING)
		return;
	rig_error_clear(&err);
	if (rig_sweep_step(&d->sweep, &err) != RIG_OK) {
		char line[320];

		/* Said as it is: "safe" only when every line read back so
		 * (rig_sweep_step has just tried to make it so). */
		rig_daemon_safe_line(d, line, sizeof(line));
		snprintf(d->last_error, sizeof(d->last_error), "%s", err.msg);
		rig_utc_stamp(d->fault_utc, sizeof(d->fault_utc));
		rig_daemon_log(d, RIG_LOG_ERR, "sweep stopped: %s; %s; the "
			       "sweep is kept: 'stray rig resume' once fixed",
			       err.msg, line);
		d->state = RIG_FAULTED;
		return;
	}
	if (d->sweep.finished) {
		d->state = RIG_IDLE;
		rig_daemon_log_end(d, "complete");
	}
}

/* The lab's safe state in words, each line read back (rig_lab_is_safe):
 * what the daemon says at a stop, at `safe` and in `rig status`. */
int rig_daemon_safe_line(const struct rig_daemon *d, char *buf, size_t size)
{
	char why[200];
	int safe = rig_lab_is_safe(&d->lab, why, sizeof(why));

	if (safe)
		snprintf(buf, size, "lab safe (lamp off, beam blocked, "
			 "shutter closed: each read back)");
	else
		snprintf(buf, size, "safe state NOT confirmed: %s; check the "
			 "lamp, beam block and shutter by hand", why);
	return safe;
}
