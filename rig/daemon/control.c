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

static void add_sweep(const struct rig_daemon *d, cJSON *resp)
{
	struct rig_progress p;
	cJSON *sw = cJSON_AddObjectToObject(resp, "sweep");

	rig_sweep_progress(&d->sweep, &p);
	cJSON_AddStringToObject(sw, "dir", d->sweep.mf.dir);
	cJSON_AddNumberToObject(sw, "done", (double)p.done);
	cJSON_AddNumberToObject(sw, "total", (double)p.total);
	cJSON_AddNumberToObject(sw, "elapsed_s", p.elapsed_s);
	cJSON_AddNumberToObject(sw, "eta_s", p.eta_s);
	cJSON_AddBoolToObject(sw, "finished", p.finished);
}

static void status(const struct rig_daemon *d, cJSON *resp)
{
	const int *line = d->lab.lines.state;

	cJSON_AddStringToObject(resp, "state", state_names[d->state]);
	if (isfinite(d->lab.theta_deg))
		cJSON_AddNumberToObject(resp, "theta_deg", d->lab.theta_deg);
	else
		cJSON_AddNullToObject(resp, "theta_deg");
	cJSON_AddNumberToObject(resp, "lamp", line[RIG_LINE_LAMP]);
	cJSON_AddNumberToObject(resp, "beam_blocked", line[RIG_LINE_BEAM_BLOCK]);
	cJSON_AddNumberToObject(resp, "shutter_open", line[RIG_LINE_SHUTTER]);
	cJSON_AddNumberToObject(resp, "recoveries", d->lab.recoveries);
	if (d->last_error[0])
		cJSON_AddStringToObject(resp, "last_error", d->last_error);
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
	struct rig_error err;
	int rc = RIG_OK;

	rig_error_clear(&err);
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
		rc = rig_sweep_open(&d->sweep, &d->lab, req->dir,
				    (req->resume ? RIG_SWEEP_RESUME : 0) |
				    (req->force_plan ? RIG_SWEEP_FORCE_PLAN : 0),
				    &err);
		d->sweep_open = rc == RIG_OK;
		d->state = rc == RIG_OK ? RIG_RUNNING : RIG_IDLE;
		d->last_error[0] = '\0';
		break;
	case RIG_CMD_PAUSE:
		d->state = RIG_PAUSED;
		rc = rig_lab_safe(&d->lab, &err);
		break;
	case RIG_CMD_RESUME:
		d->state = RIG_RUNNING;
		break;
	default:	/* abort, safe, shutdown */
		end_sweep(d);
		d->state = RIG_IDLE;
		d->quit = req->cmd == RIG_CMD_SHUTDOWN;
		rc = rig_lab_safe(&d->lab, &err);
		break;
	}
	if (rc != RIG_OK)
		fail(resp, "%s", err.msg);
}

/* Interlocks of the run state: returns the refusal text or NULL. */
static const char *refusal(const struct rig_daemon *d, int cmd)
{
	int busy = d->state == RIG_RUNNING || d->state == RIG_PAUSED;

	if (busy && (cmd == RIG_CMD_HOME || cmd == RIG_CMD_MOVE ||
		     cmd == RIG_CMD_SWEEP))
		return "refused: '%s' while a sweep is running; abort it first";
	if ((cmd == RIG_CMD_PAUSE && d->state != RIG_RUNNING) ||
	    (cmd == RIG_CMD_RESUME && d->state != RIG_PAUSED))
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
		snprintf(d->last_error, sizeof(d->last_error), "%s", err.msg);
		fprintf(stderr, "strayrigd: sweep stopped safe: %s\n", err.msg);
		d->state = RIG_FAULTED;
		return;
	}
	if (d->sweep.finished)
		d->state = RIG_IDLE;
}
