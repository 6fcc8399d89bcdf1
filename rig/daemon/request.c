/*
 * request.c - parse one control request (daemon.h) with cJSON into a
 * struct rig_request: the command must be known, its arguments present,
 * typed and finite.  Pure, so it is fuzzed on its own.
 */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rig/daemon.h"

static const char *const cmd_names[RIG_CMD_COUNT] = {
	"status", "home", "move", "sweep", "pause", "resume", "abort", "safe",
	"shutdown",
};

const char *rig_cmd_name(int cmd)
{
	return cmd >= 0 && cmd < RIG_CMD_COUNT ? cmd_names[cmd] : "?";
}

static int bad(char *msg, size_t size, const char *why, const char *arg)
{
	char *p;

	snprintf(msg, size, why, arg);
	for (p = msg; *p; p++)	/* one line, whatever the client sent */
		if ((unsigned char)*p < 0x20 || *p == 0x7f)
			*p = '?';
	return RIG_EPARSE;
}

static int parse_args(const cJSON *o, struct rig_request *req, char *msg,
		      size_t size)
{
	const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "theta_deg");
	const cJSON *dir = cJSON_GetObjectItemCaseSensitive(o, "dir");
	const cJSON *res = cJSON_GetObjectItemCaseSensitive(o, "resume");
	const cJSON *force = cJSON_GetObjectItemCaseSensitive(o, "force_plan");

	if (req->cmd == RIG_CMD_MOVE) {
		if (!cJSON_IsNumber(t) || !isfinite(t->valuedouble))
			return bad(msg, size, "move: %s",
				   "theta_deg must be a number");
		req->theta_deg = t->valuedouble;
	}
	if (req->cmd != RIG_CMD_SWEEP)
		return RIG_OK;
	if (!cJSON_IsString(dir) || !dir->valuestring[0] ||
	    strlen(dir->valuestring) >= sizeof(req->dir))
		return bad(msg, size, "sweep: %s",
			   "dir must be a folder path");
	if (res && !cJSON_IsBool(res))
		return bad(msg, size, "sweep: %s",
			   "resume must be true or false");
	if (force && !cJSON_IsBool(force))
		return bad(msg, size, "sweep: %s",
			   "force_plan must be true or false");
	strcpy(req->dir, dir->valuestring);
	req->resume = cJSON_IsTrue(res);
	req->force_plan = cJSON_IsTrue(force);
	return RIG_OK;
}

/* Optional "owner": who asks (a user name), for the log and the sweep. */
static int parse_owner(const cJSON *o, struct rig_request *req, char *msg,
		       size_t size)
{
	const cJSON *w = cJSON_GetObjectItemCaseSensitive(o, "owner");
	const char *p;

	if (!w)
		return RIG_OK;
	if (!cJSON_IsString(w) || !w->valuestring[0] ||
	    strlen(w->valuestring) >= sizeof(req->owner))
		return bad(msg, size, "%s", "owner must be a user name of "
			   "1-47 characters");
	for (p = w->valuestring; *p; p++)
		if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
		      (*p >= '0' && *p <= '9') || strchr("._-@", *p)))
			return bad(msg, size, "%s", "owner: letters, digits "
				   "and ._-@ only");
	strcpy(req->owner, w->valuestring);
	return RIG_OK;
}

int rig_request_parse(const char *text, struct rig_request *req, char *msg,
		      size_t size)
{
	cJSON *o = cJSON_Parse(text);
	const cJSON *cmd = cJSON_GetObjectItemCaseSensitive(o, "cmd");
	int rc = RIG_OK;

	memset(req, 0, sizeof(*req));
	msg[0] = '\0';
	if (!o || !cJSON_IsObject(o))
		rc = bad(msg, size, "%s", "request is not a JSON object");
	else if (!cJSON_IsString(cmd))
		rc = bad(msg, size, "%s", "request has no string 'cmd'");
	if (rc == RIG_OK) {
		for (req->cmd = 0; req->cmd < RIG_CMD_COUNT; req->cmd++)
			if (!strcmp(cmd_names[req->cmd], cmd->valuestring))
				break;
		if (req->cmd == RIG_CMD_COUNT)
			rc = bad(msg, size, "unknown command '%.40s'",
				 cmd->valuestring);
	}
	if (rc == RIG_OK)
		rc = parse_args(o, req, msg, size);
	if (rc == RIG_OK)
		rc = parse_owner(o, req, msg, size);
	cJSON_Delete(o);
	return rc;
}
