/*
 * runner.c - runs the plan of a review: each step by exec of the stray
 * binary in the output folder (the command line a user can re-run by
 * hand, and a step that fails cannot take the review down with it),
 * progress and an estimate of the time left on stderr, and a manifest
 * of what ran with the SHA-256 of its inputs, so that --resume after a
 * kill re-runs only what is missing or whose inputs changed.
 */
#include <cjson/cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "review/review.h"
#include "review_int.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sweep_store.h"

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int exists_in(const char *dir, const char *name)
{
	char path[REVIEW_PATH_MAX * 2];
	struct stat st;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	return stat(path, &st) == 0;
}

/* The step's input hash: its command line and every input's SHA-256
 * (a folder by its manifest.csv, as a lab sweep is sealed). */
static int step_hash(const char *dir, struct review_step *s,
		     struct stray_error *err)
{
	char *buf = NULL, path[REVIEW_PATH_MAX * 2], hex[STRAY_SWEEP_SHA256_HEX];
	size_t len = 0;
	FILE *m = open_memstream(&buf, &len);
	struct stat st;
	int k, rc = STRAY_OK;

	if (!m)
		return stray_error_set(err, STRAY_ENOMEM, "hash", NULL);
	for (k = 0; k < s->argc; k++)
		fprintf(m, "%s%c", s->argv[k], 0);
	for (k = 0; k < s->n_ins && rc == STRAY_OK; k++) {
		if (s->ins[k][0] == '/')
			snprintf(path, sizeof(path), "%s", s->ins[k]);
		else
			snprintf(path, sizeof(path), "%s/%s", dir, s->ins[k]);
		if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
			strncat(path, "/manifest.csv", sizeof(path) - strlen(path) - 1);
		rc = stray_sweep_sha256_file(path, hex, err);
		fprintf(m, "%s%c%s%c", s->ins[k], 0, hex, 0);
	}
	fclose(m);
	if (rc == STRAY_OK)
		stray_sweep_sha256_mem(buf, len, hex), memcpy(s->hash, hex, 65);
	free(buf);
	return rc;
}

int review_alpha_beyond(const char *csv, double theta_deg, double *alpha,
			double *sigma, struct stray_error *err)
{
	FILE *f = fopen(csv, "r");
	char line[4096];
	long n = 0, lineno = 0;
	double t, a, sg;

	if (!f)
		return stray_error_at(err, STRAY_ENOTFOUND, csv, 0, NULL, strerror(errno));
	*alpha = -1.0;
	*sigma = 0.0;
	while (fgets(line, sizeof(line), f)) {
		lineno++;
		if (line[0] == '#' || line[0] == 't')
			continue;
		sg = 0.0;
		if (sscanf(line, "%lf,%lf,%lf", &t, &a, &sg) < 2) {
			fclose(f);
			return stray_error_at(err, STRAY_EPARSE, csv, lineno,
					      "alpha", "not a curve row");
		}
		n++;
		if (t >= theta_deg - 1e-9 && a > *alpha)
			*alpha = a, *sigma = sg;
	}
	fclose(f);
	if (*alpha < 0.0)
		return stray_error_at(err, STRAY_EINVAL, csv, 0, "theta_deg",
				      "no row at or beyond the required angle");
	return n ? STRAY_OK : STRAY_EINVAL;
}

/* heads.json for `stray availability`: the project's heads, each with
 * the flight table the review builds. */
static int write_heads(const char *dir, const struct review_project *p,
		       struct stray_error *err)
{
	struct stray_file_out fo;
	char path[REVIEW_PATH_MAX * 2];
	int i, rc;

	snprintf(path, sizeof(path), "%s/heads.json", dir);
	if ((rc = stray_file_open_atomic(&fo, path, err)) != STRAY_OK)
		return rc;
	fputs("{\"heads\": [\n", fo.f);
	for (i = 0; i < p->n_heads; i++) {
		const struct review_head *h = &p->head[i];

		fprintf(fo.f, " {\"name\": \"%s\", \"boresight_body\": [%.17g, %.17g, %.17g], "
			"\"up_body\": [%.17g, %.17g, %.17g], \"table\": \"flight_table.bin\"}%s\n",
			h->name, h->boresight[0], h->boresight[1], h->boresight[2],
			h->up[0], h->up[1], h->up[2], i + 1 < p->n_heads ? "," : "");
	}
	fputs("]}\n", fo.f);
	return stray_file_commit(&fo, err);
}

/* The child's stderr passed on as it comes (progress stays live), its
 * last line kept for the step's "why" when it fails. */
static void relay(int fd, char *last, size_t size)
{
	char buf[4096], line[512];
	size_t n_line = 0;
	ssize_t n, k;

	last[0] = '\0';
	while ((n = read(fd, buf, sizeof(buf))) != 0) {
		if (n < 0) {
			if (errno == EINTR)
				continue;
			break;
		}
		if (write(2, buf, (size_t)n) < 0) {
			/* nowhere to show it: still keep the last line */
		}
		for (k = 0; k < n; k++) {
			if (buf[k] == '\n' || buf[k] == '\r') {
				if (n_line) {
					line[n_line] = '\0';
					snprintf(last, size, "%s", line);
				}
				n_line = 0;
			} else if (n_line + 1 < sizeof(line)) {
				line[n_line++] = buf[k];
			}
		}
	}
	if (n_line) {
		line[n_line] = '\0';
		snprintf(last, size, "%s", line);
	}
}

/* One step by exec of self in dir; stdout to its file (renamed into
 * place on success only).  Returns the exit status, -1 if killed. */
static int exec_step(const char *self, const char *dir,
		     const struct review_step *s, char *last, size_t size)
{
	char part[REVIEW_PATH_MAX * 2 + 8], final[REVIEW_PATH_MAX * 2];
	int st, pfd[2];
	pid_t pid;

	snprintf(final, sizeof(final), "%s/%s", dir, s->stdout_file);
	snprintf(part, sizeof(part), "%s.part", final);
	fflush(NULL);
	if (pipe(pfd) != 0)
		return -1;
	pid = fork();
	if (pid < 0) {
		close(pfd[0]);
		close(pfd[1]);
		return -1;
	}
	if (pid == 0) {
		int fd;

		/* killed with the review: no orphan writing into DIR while
		 * a resumed review runs the same step */
		prctl(PR_SET_PDEATHSIG, SIGKILL);
		if (getppid() == 1)
			_exit(126);
		close(pfd[0]);
		fd = s->stdout_file[0] ? open(part, O_WRONLY | O_CREAT | O_TRUNC, 0644)
				       : open("/dev/null", O_WRONLY);
		if (fd < 0 || dup2(fd, 1) < 0 || dup2(pfd[1], 2) < 0 ||
		    chdir(dir) != 0)
			_exit(126);
		execv(self, s->argv);
		_exit(127);
	}
	close(pfd[1]);
	relay(pfd[0], last, size);
	close(pfd[0]);
	while (waitpid(pid, &st, 0) < 0)
		if (errno != EINTR)
			return -1;
	if (!WIFEXITED(st))
		return -1;
	if (WEXITSTATUS(st) == 0 && s->stdout_file[0] && rename(part, final) != 0)
		return 1;
	if (WEXITSTATUS(st) != 0 && s->stdout_file[0])
		unlink(part);
	return WEXITSTATUS(st);
}

static cJSON *manifest_json(const struct review_project *p,
			    const struct review_plan *plan, const char *dir)
{
	cJSON *root = cJSON_CreateObject(), *steps = cJSON_CreateArray();
	int i, k;

	cJSON_AddStringToObject(root, "name", p->name);
	cJSON_AddStringToObject(root, "project", p->path);
	cJSON_AddNumberToObject(root, "rays", (double)plan->rays);
	cJSON_AddItemToObject(root, "steps", steps);
	for (i = 0; i < plan->n; i++) {
		const struct review_step *s = &plan->step[i];
		cJSON *j, *a = cJSON_CreateArray();

		for (k = 0; k < s->n_outs; k++)
			if (s->status && strcmp(s->status, "done") == 0 &&
			    exists_in(dir, s->outs[k]))
				cJSON_AddItemToArray(a, cJSON_CreateString(s->outs[k]));
		/* review.json's step, with what --resume compares */
		j = review_step_json(s, a);
		cJSON_AddStringToObject(j, "hash", s->hash);
		a = cJSON_CreateArray();
		for (k = 0; k < s->argc; k++)
			cJSON_AddItemToArray(a, cJSON_CreateString(s->argv[k]));
		cJSON_AddItemToObject(j, "command", a);
		cJSON_AddItemToArray(steps, j);
	}
	return root;
}

static int write_manifest(const char *dir, const struct review_project *p,
			  const struct review_plan *plan,
			  struct stray_error *err)
{
	char path[REVIEW_PATH_MAX * 2], *text;
	struct stray_file_out fo;
	cJSON *root = manifest_json(p, plan, dir);
	int rc;

	snprintf(path, sizeof(path), "%s/manifest.json", dir);
	text = cJSON_Print(root);
	cJSON_Delete(root);
	if (!text)
		return stray_error_set(err, STRAY_ENOMEM, "manifest", NULL);
	/* the review's own resumable record, read at --resume and written
	 * again after every step: neither an input nor a second output */
	stray_file_forget_input(path);
	stray_file_forget_output(path);
	if ((rc = stray_file_open_atomic(&fo, path, err)) == STRAY_OK) {
		fputs(text, fo.f);
		fputc('\n', fo.f);
		rc = stray_file_commit(&fo, err);
	}
	free(text);
	return rc;
}

/* A step of an earlier run that can be kept: same inputs, outputs all
 * there, done. */
static int kept(const cJSON *old, const char *dir, struct review_step *s)
{
	const cJSON *j, *st, *h, *sec;
	int k;

	cJSON_ArrayForEach(j, cJSON_GetObjectItemCaseSensitive(old, "steps")) {
		const cJSON *n = cJSON_GetObjectItemCaseSensitive(j, "name");

		if (!cJSON_IsString(n) || strcmp(n->valuestring, s->name))
			continue;
		st = cJSON_GetObjectItemCaseSensitive(j, "status");
		h = cJSON_GetObjectItemCaseSensitive(j, "hash");
		sec = cJSON_GetObjectItemCaseSensitive(j, "seconds");
		if (!cJSON_IsString(st) || strcmp(st->valuestring, "done") ||
		    !cJSON_IsString(h) || strcmp(h->valuestring, s->hash))
			return 0;
		for (k = 0; k < s->n_outs; k++)
			if (!exists_in(dir, s->outs[k]))
				return 0;
		s->seconds = cJSON_IsNumber(sec) ? sec->valuedouble : 0.0;
		return 1;
	}
	return 0;
}

static cJSON *old_manifest(const char *dir)
{
	char path[REVIEW_PATH_MAX * 2], *text = NULL;
	struct stray_error e;
	size_t len;
	cJSON *j;

	snprintf(path, sizeof(path), "%s/manifest.json", dir);
	if (access(path, F_OK) != 0 || stray_file_read(path, &text, &len, &e))
		return NULL;
	j = cJSON_ParseWithLength(text, len);
	free(text);
	return j;
}

/* Fill @ALPHA: the system's worst alpha beyond the required Sun angle. */
static int resolve_alpha(const char *dir, const struct review_project *p,
			 struct review_step *s, struct stray_error *err)
{
	char csv[REVIEW_PATH_MAX * 2];
	double alpha, sigma, theta = 0.0;
	int k, i, rc;

	for (k = 0; k < s->argc; k++) {
		if (strcmp(s->argv[k], "@ALPHA"))
			continue;
		for (i = 0; i < p->n_req; i++)
			if (strcmp(p->req[i].key, "sun_exclusion_deg_max") == 0)
				theta = p->req[i].value;
		snprintf(csv, sizeof(csv), "%s/system.csv", dir);
		rc = review_alpha_beyond(csv, theta, &alpha, &sigma, err);
		if (rc != STRAY_OK)
			return rc;
		free(s->argv[k]);
		if (!(s->argv[k] = malloc(32)))
			return stray_error_set(err, STRAY_ENOMEM, "alpha", NULL);
		snprintf(s->argv[k], 32, "%.10g", alpha > 0.0 ? alpha : 1e-30);
	}
	return STRAY_OK;
}

/* An input an earlier step makes ("./name") that is not there. */
static const char *missing_input(const char *dir, const struct review_step *s)
{
	int k;

	for (k = 0; k < s->n_ins; k++)
		if (strncmp(s->ins[k], "./", 2) == 0 && !exists_in(dir, s->ins[k] + 2))
			return s->ins[k] + 2;
	return NULL;
}

static void progress(int k, const struct review_plan *plan, const char *what,
		     double t0, double w_run, double w_left)
{
	double el = now_s() - t0;

	if (w_run > 0.0)
		fprintf(stderr, "review: [%d/%d] %s: %.0f s so far, about %.0f s left\n",
			k + 1, plan->n, what, el, el / w_run * w_left);
	else
		fprintf(stderr, "review: [%d/%d] %s: %.0f s so far\n", k + 1,
			plan->n, what, el);
}

int review_run(const char *self, const char *dir,
	       const struct review_project *p, struct review_plan *plan,
	       int resume, struct stray_error *err)
{
	cJSON *old = resume ? old_manifest(dir) : NULL;
	double t0 = now_s(), w_run = 0.0, w_left = 0.0, ts;
	const char *miss;
	char last[512];
	int i, rc = STRAY_OK, failed = 0, st;

	struct stat st_dir;

	if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
		rc = stray_error_at(err, STRAY_EIO, dir, 0, "--out", strerror(errno));
		goto out;
	}
	if (stat(dir, &st_dir) != 0 || !S_ISDIR(st_dir.st_mode)) {
		rc = stray_error_at(err, STRAY_EINVAL, dir, 0, "--out",
				    "exists and is not a folder");
		goto out;
	}
	for (i = 0; i < plan->n; i++)
		w_left += plan->step[i].why ? 0.0 : plan->step[i].weight;
	if (p->n_heads && p->mission != REVIEW_MISSION_NONE &&
	    (rc = write_heads(dir, p, err)) != STRAY_OK)
		goto out;
	for (i = 0; i < plan->n; i++) {
		struct review_step *s = &plan->step[i];

		s->status = "not run";
		s->seconds = 0.0;
		if (s->why) {
			fprintf(stderr, "review: [%d/%d] %s: not run: %s\n", i + 1,
				plan->n, s->name, s->why);
			continue;
		}
		w_left -= s->weight;
		if ((miss = missing_input(dir, s))) {
			snprintf(s->fail, sizeof(s->fail),
				 "needs %s, which an earlier step did not make", miss);
			s->why = s->fail;
			fprintf(stderr, "review: [%d/%d] %s: not run: %s\n", i + 1,
				plan->n, s->name, s->why);
			continue;
		}
		if ((rc = resolve_alpha(dir, p, s, err)) != STRAY_OK ||
		    (rc = step_hash(dir, s, err)) != STRAY_OK)
			goto out;
		if (old && kept(old, dir, s)) {
			s->status = "done";
			fprintf(stderr, "review: [%d/%d] %s: kept from the last run (inputs unchanged)\n",
				i + 1, plan->n, s->name);
			continue;
		}
		progress(i, plan, s->name, t0, w_run, s->weight + w_left);
		ts = now_s();
		st = exec_step(self, dir, s, last, sizeof(last));
		s->seconds = now_s() - ts;
		w_run += s->weight;
		s->status = st == 0 ? "done" : "failed";
		if (st != 0) {
			failed++;
			if (st < 0)
				snprintf(s->fail, sizeof(s->fail), "stray %.40s was killed",
					 s->argv[1]);
			else
				snprintf(s->fail, sizeof(s->fail), "exit status %d: %.150s",
					 st, last[0] ? last : "(no message)");
			s->why = s->fail;
		}
		fprintf(stderr, "review: [%d/%d] %s: %s in %.1f s\n", i + 1,
			plan->n, s->name, s->status, s->seconds);
		if ((rc = write_manifest(dir, p, plan, err)) != STRAY_OK)
			goto out;
	}
	rc = write_manifest(dir, p, plan, err);
out:
	cJSON_Delete(old);
	if (rc == STRAY_OK && failed)
		rc = stray_error_at(err, STRAY_EIO, dir, 0, NULL,
				    "some steps failed (review.json lists them)");
	return rc;
}
