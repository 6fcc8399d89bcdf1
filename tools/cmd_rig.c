/*
 * cmd_rig.c - `stray rig`: talk to strayrigd over its Unix socket.
 * One JSON request per connection, one JSON response line back (the
 * protocol of rig/include/rig/daemon.h); --json prints that response.
 */
#define _DEFAULT_SOURCE	/* struct sockaddr_un */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <pwd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"

#define DEFAULT_SOCKET "/tmp/strayrigd.sock"
#define RESPONSE_MAX 65536

static const char usage[] =
	"usage: stray rig [--socket PATH] [--json] <action> [<args>]\n"
	"\n"
	"Control the lab sweep daemon strayrigd.  Actions:\n"
	"  status               state, angle, lines, sweep progress and ETA\n"
	"  home                 home the rotation stage\n"
	"  move THETA_DEG       move the stage (refused outside the limits)\n"
	"  sweep DIR [--resume [--force-plan]]\n"
	"                       start (or resume) a sweep into DIR; resuming\n"
	"                       with a plan other than DIR/plan.json is\n"
	"                       refused unless --force-plan\n"
	"  pause | resume       hold a sweep (lab made safe) and go on\n"
	"  abort | safe         stop; lamp off, beam blocked, shutter closed\n"
	"  shutdown             make safe and stop the daemon\n"
	"  probe --config RIG.json\n"
	"                       without the daemon: list the devices the real\n"
	"                       backend finds (or the INDI server's) and talk\n"
	"                       to each once (nothing moves; strayrig-probe)\n"
	"\n"
	"  --socket PATH        control socket (default $STRAYRIGD_SOCKET or\n"
	"                       " DEFAULT_SOCKET ")\n"
	"  --json               print the daemon's JSON response\n";

static const char *const plain[] = { "status", "home", "pause", "resume",
				     "abort", "safe", "shutdown", NULL };

/* Who asks: the user name, for the daemon's log and the sweep's owner. */
static void add_owner(cJSON *req)
{
	struct passwd *pw = getpwuid(getuid());
	const char *p;

	if (!pw || !pw->pw_name || !pw->pw_name[0] ||
	    strlen(pw->pw_name) > 47)
		return;
	for (p = pw->pw_name; *p; p++)
		if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
		      (*p >= '0' && *p <= '9') || strchr("._-@", *p)))
			return;
	cJSON_AddStringToObject(req, "owner", pw->pw_name);
}

/* Build the request for argv[0..n); NULL after a usage message. */
static cJSON *build_request(int n, char **args, int resume, int force_plan,
			    int *rc)
{
	cJSON *req = cJSON_CreateObject();
	const char *const *p;
	double theta;

	*rc = CLI_USAGE;
	cJSON_AddStringToObject(req, "cmd", args[0]);
	add_owner(req);
	for (p = plain; *p; p++)
		if (!strcmp(*p, args[0]) && n == 1 && !resume && !force_plan)
			return req;
	if (!strcmp(args[0], "move") && n == 2) {
		char *end;

		theta = strtod(args[1], &end);
		if (end != args[1] && !*end && isfinite(theta)) {
			cJSON_AddNumberToObject(req, "theta_deg", theta);
			return req;
		}
		cJSON_Delete(req);
		cli_usage_error("rig", "move: angle '%s' is not a finite number",
				args[1]);
		return NULL;
	}
	if (!strcmp(args[0], "sweep") && n == 2 && (resume || !force_plan)) {
		cJSON_AddStringToObject(req, "dir", args[1]);
		cJSON_AddBoolToObject(req, "resume", resume);
		if (force_plan)
			cJSON_AddBoolToObject(req, "force_plan", 1);
		return req;
	}
	cJSON_Delete(req);
	cli_usage_error("rig", "bad action or arguments '%s'", args[0]);
	return NULL;
}

/* Send text, read the response line into buf. */
static int exchange(const char *sock, const char *text, char *buf,
		    size_t size)
{
	struct sockaddr_un a;
	size_t n = 0;
	ssize_t k;
	int fd;

	memset(&a, 0, sizeof(a));
	a.sun_family = AF_UNIX;
	if (strlen(sock) >= sizeof(a.sun_path))
		return -1;
	strcpy(a.sun_path, sock);
	fd = socket(AF_UNIX, SOCK_STREAM, 0);
	if (fd < 0 || connect(fd, (struct sockaddr *)&a, sizeof(a)) != 0 ||
	    write(fd, text, strlen(text)) != (ssize_t)strlen(text) ||
	    write(fd, "\n", 1) != 1) {
		if (fd >= 0)
			close(fd);
		return -1;
	}
	while (n < size - 1 && (k = read(fd, buf + n, size - 1 - n)) > 0)
		n += (size_t)k;
	buf[n] = '\0';
	close(fd);
	return n > 0 ? 0 : -1;
}

static void print_human(const cJSON *resp)
{
	const cJSON *it;

	cJSON_ArrayForEach(it, resp) {
		char *v;

		if (!strcmp(it->string, "ok"))
			continue;
		v = cJSON_IsString(it) ? NULL : cJSON_PrintUnformatted(it);
		printf("%s: %s\n", it->string, v ? v : it->valuestring);
		free(v);
	}
	if (!resp->child || !resp->child->next)
		printf("ok\n");
}

/* Seconds as 1 h 02 min, 3 min 05 s or 12 s. */
static void duration(double s, char *out, size_t size)
{
	long t = s > 0 && s < 1e9 ? (long)(s + 0.5) : 0;

	if (t >= 3600)
		snprintf(out, size, "%ld h %02ld min", t / 3600, t / 60 % 60);
	else if (t >= 60)
		snprintf(out, size, "%ld min %02ld s", t / 60, t % 60);
	else
		snprintf(out, size, "%ld s", t);
}

static const char *str_of(const cJSON *o, const char *key)
{
	const char *v = cJSON_GetStringValue(cJSON_GetObjectItem(o, key));

	return v ? v : "";
}

static double num_of(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItem(o, key);

	return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* A line's state in words; "unknown" when the daemon could not read it
 * back (null). */
static const char *line_word(const cJSON *o, const char *key,
			     const char *on, const char *off)
{
	const cJSON *v = cJSON_GetObjectItem(o, key);

	return !cJSON_IsNumber(v) ? "unknown" : v->valuedouble != 0 ? on
								    : off;
}

/* `stray rig status` for a person: plain units, the sweep in words. */
static void print_status(const cJSON *r)
{
	const cJSON *sw = cJSON_GetObjectItem(r, "sweep");
	char el[32], eta[32];

	printf("state: %s%s%s\n", str_of(r, "state"),
	       *str_of(r, "faulted_since") ? " since " : "",
	       str_of(r, "faulted_since"));
	if (cJSON_IsTrue(cJSON_GetObjectItem(r, "safe")))
		printf("safe: yes (lamp off, beam blocked, shutter closed, "
		       "read back)\n");
	else
		printf("safe: NO: %s\n", *str_of(r, "unsafe")
		       ? str_of(r, "unsafe") : "not reported");
	printf("lines: lamp %s, beam %s, shutter %s\n",
	       line_word(r, "lamp", "on", "off"),
	       line_word(r, "beam_blocked", "blocked", "not blocked"),
	       line_word(r, "shutter_open", "open", "closed"));
	if (isfinite(num_of(r, "theta_deg")))
		printf("stage: %.3f deg\n", num_of(r, "theta_deg"));
	else
		printf("stage: position unknown (home it)\n");
	if (*str_of(r, "last_error"))
		printf("last error: %s\n", str_of(r, "last_error"));
	printf("recoveries: %.0f\n", num_of(r, "recoveries"));
	if (!sw)
		return;
	duration(num_of(sw, "elapsed_s"), el, sizeof(el));
	duration(num_of(sw, "eta_s"), eta, sizeof(eta));
	printf("sweep: %s (owner %s)\n", str_of(sw, "dir"),
	       str_of(sw, "owner"));
	printf("  %.0f of %.0f frames (%.1f %%), angle %.0f of %.0f\n",
	       num_of(sw, "done"), num_of(sw, "total"),
	       num_of(sw, "percent"), num_of(sw, "angle_no"),
	       num_of(sw, "n_angles"));
	printf("  now: %s\n", str_of(sw, "step"));
	if (cJSON_IsTrue(cJSON_GetObjectItem(sw, "finished")))
		printf("  finished after %s\n", el);
	else
		printf("  elapsed %s, about %s to go\n", el, eta);
}

static int talk(const char *sock, cJSON *req)
{
	char *text = cJSON_PrintUnformatted(req), *buf = malloc(RESPONSE_MAX);
	cJSON *resp = NULL;
	int rc = CLI_FAIL;

	if (!text || !buf || exchange(sock, text, buf, RESPONSE_MAX) != 0) {
		fprintf(stderr, "stray rig: cannot talk to strayrigd at '%s': "
			"%s\n", sock, strerror(errno));
		goto out;
	}
	resp = cJSON_Parse(buf);
	if (!resp) {
		fprintf(stderr, "stray rig: '%s': response is not JSON\n",
			sock);
		goto out;
	}
	if (cli.json) {
		printf("%s\n", buf);
	} else if (cJSON_IsTrue(cJSON_GetObjectItem(resp, "ok"))) {
		if (!strcmp(str_of(req, "cmd"), "status"))
			print_status(resp);
		else
			print_human(resp);
	}
	if (cJSON_IsTrue(cJSON_GetObjectItem(resp, "ok")))
		rc = CLI_OK;
	/* A faulted lab is not "ok" to a script polling status. */
	if (rc == CLI_OK && !strcmp(str_of(resp, "state"), "faulted")) {
		fprintf(stderr, "stray rig: strayrigd is faulted: %s; %s\n",
			str_of(resp, "last_error"),
			cJSON_IsTrue(cJSON_GetObjectItem(resp, "safe"))
			? "lab safe" : "safe state NOT confirmed");
		rc = CLI_FAIL;
	} else if (rc != CLI_OK)
		fprintf(stderr, "stray rig: %s\n", cJSON_GetStringValue(
			cJSON_GetObjectItem(resp, "error")));
out:
	cJSON_Delete(resp);
	free(text);
	free(buf);
	return rc;
}

/* `stray rig probe --config FILE`: strayrig-probe beside this binary,
 * else on PATH (it links the real backend; stray does not). */
static int probe(int argc, char **argv)
{
	char self[4096], *slash;
	ssize_t n;

	if (argc != 3 || strcmp(argv[1], "--config"))
		return cli_usage_error("rig", "probe: expected --config "
				       "RIG.json");
	n = readlink("/proc/self/exe", self, sizeof(self) - 32);
	if (n > 0) {
		self[n] = '\0';
		slash = strrchr(self, '/');
		strcpy(slash + 1, "strayrig-probe");
		execl(self, "strayrig-probe", "--config", argv[2],
		      (char *)NULL);
	}
	execlp("strayrig-probe", "strayrig-probe", "--config", argv[2],
	       (char *)NULL);
	fprintf(stderr, "stray rig: probe: cannot run strayrig-probe: %s\n",
		strerror(errno));
	return CLI_FAIL;
}

int cmd_rig(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "socket", required_argument, NULL, 's' },
		{ "resume", no_argument, NULL, 'r' },
		{ "force-plan", no_argument, NULL, 'f' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	const char *sock = getenv("STRAYRIGD_SOCKET");
	int opt, resume = 0, force_plan = 0, rc;
	cJSON *req;

	if (argc >= 2 && !strcmp(argv[1], "probe"))
		return probe(argc - 1, argv + 1);
	while ((opt = getopt_long(argc, argv, "hs:", opts, NULL)) != -1) {
		switch (opt) {
		case 0: break;
		case 'h': fputs(usage, stdout); return CLI_OK;
		case 's': sock = optarg; break;
		case 'r': resume = 1; break;
		case 'f': force_plan = 1; break;
		default:
			return cli_usage_error("rig", "unknown option '%s'",
					       argv[optind - 1]);
		}
	}
	if (optind >= argc)
		return cli_usage_error("rig", "no action given");
	req = build_request(argc - optind, argv + optind, resume, force_plan,
			    &rc);
	if (!req)
		return rc;
	rc = talk(sock ? sock : DEFAULT_SOCKET, req);
	cJSON_Delete(req);
	return rc;
}
