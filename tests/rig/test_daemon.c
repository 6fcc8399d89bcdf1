/*
 * test_daemon.c - strayrigd end to end over its Unix socket, against the
 * simulators: socket permissions, status, malformed and refused requests,
 * home and move, a sweep with pause/resume and interlock refusals while
 * it runs, abort and SIGTERM leaving the lab safe.
 */
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <cJSON.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>

#include "rig_daemon_util.h"
#include "rig_test_util.h"

struct daemon {
	char *dir;
	char sock[600], conf[600];
	pid_t pid;
};

static struct daemon dm;

/* One request, one response (parsed); NULL if the daemon is gone. */
static cJSON *ask(const char *req)
{
	return ask_on(dm.sock, req);
}

static int ok_of(const cJSON *r)
{
	return cJSON_IsTrue(cJSON_GetObjectItem(r, "ok"));
}

static const char *error_of(const cJSON *r)
{
	return cJSON_GetStringValue(cJSON_GetObjectItem(r, "error"));
}

static double num_of(const cJSON *r, const char *key)
{
	return cJSON_GetNumberValue(cJSON_GetObjectItem(r, key));
}

static int start_daemon(void **state)
{
	const char *b = getenv("STRAY_BUILD");
	char bin[512];
	FILE *f;
	int i;

	(void)state;
	dm.dir = temp_dir();
	snprintf(dm.sock, sizeof(dm.sock), "%s/rig.sock", dm.dir);
	snprintf(dm.conf, sizeof(dm.conf), "%s/rig.json", dm.dir);
	f = fopen(dm.conf, "w");
	fprintf(f, "{\"camera\":{\"rows\":[960,961,1100,1101],\"col0\":960,"
		   "\"n_cols\":128},\"sweep\":{\"theta_stop_deg\":30,"
		   "\"theta_step_deg\":10,\"repeats\":2},"
		   "\"sim\":{\"real_delay_s\":0.02}}");
	fclose(f);
	snprintf(bin, sizeof(bin), "%s/bin/strayrigd", b ? b : "build");
	dm.pid = fork();
	if (dm.pid == 0) {
		execl(bin, bin, "--config", dm.conf, "--socket", dm.sock,
		      (char *)NULL);
		_exit(127);
	}
	for (i = 0; i < 500 && access(dm.sock, F_OK) != 0; i++)
		nap_ms(10);
	return access(dm.sock, F_OK) == 0 ? 0 : -1;
}

static int stop_daemon(void **state)
{
	int status;

	(void)state;
	if (dm.pid > 0) {
		kill(dm.pid, SIGKILL);
		waitpid(dm.pid, &status, 0);
	}
	remove_tree(dm.dir);
	free(dm.dir);
	return 0;
}

static void test_daemon_socket_is_private(void **state)
{
	struct stat st;

	(void)state;
	assert_int_equal(stat(dm.sock, &st), 0);
	assert_true(S_ISSOCK(st.st_mode));
	assert_int_equal(st.st_mode & 0777, 0600);
}

static void test_daemon_starts_safe(void **state)
{
	cJSON *r = ask("{\"cmd\":\"status\"}");

	(void)state;
	assert_non_null(r);
	assert_true(ok_of(r));
	assert_string_equal(cJSON_GetStringValue(cJSON_GetObjectItem(r,
						 "state")), "idle");
	assert_true(num_of(r, "lamp") == 0);
	assert_true(num_of(r, "beam_blocked") == 1);
	assert_true(num_of(r, "shutter_open") == 0);
	cJSON_Delete(r);
}

static void expect_refusal(const char *req, const char *needle)
{
	cJSON *r = ask(req);

	assert_non_null(r);
	assert_false(ok_of(r));
	assert_non_null(error_of(r));
	if (!strstr(error_of(r), needle))
		fail_msg("'%s' -> '%s' lacks '%s'", req, error_of(r), needle);
	cJSON_Delete(r);
}

static void test_daemon_rejects_malformed(void **state)
{
	(void)state;
	expect_refusal("this is not json", "not a JSON object");
	expect_refusal("[1,2,3]", "not a JSON object");
	expect_refusal("{}", "no string 'cmd'");
	expect_refusal("{\"cmd\":5}", "no string 'cmd'");
	expect_refusal("{\"cmd\":\"fly\"}", "unknown command 'fly'");
	expect_refusal("{\"cmd\":\"move\"}", "theta_deg must be a number");
	expect_refusal("{\"cmd\":\"move\",\"theta_deg\":\"ten\"}",
		       "theta_deg must be a number");
	expect_refusal("{\"cmd\":\"sweep\"}", "dir must be");
	expect_refusal("{\"cmd\":\"sweep\",\"dir\":\"/tmp/x\",\"resume\":1}",
		       "resume must be");
	expect_refusal("{\"cmd\":\"pause\"}", "no sweep");
}

static void test_daemon_move_and_limits(void **state)
{
	cJSON *r;

	(void)state;
	expect_refusal("{\"cmd\":\"move\",\"theta_deg\":95}", "limits");
	r = ask("{\"cmd\":\"home\"}");
	assert_true(ok_of(r));
	cJSON_Delete(r);
	r = ask("{\"cmd\":\"move\",\"theta_deg\":12.5}");
	assert_true(ok_of(r));
	cJSON_Delete(r);
	r = ask("{\"cmd\":\"status\"}");
	assert_float_equal(num_of(r, "theta_deg"), 12.5, 1e-9);
	cJSON_Delete(r);
}

/* `stray rig` as a user runs it: exit status and first stdout line. */
static int stray_rig(const char *args, char *out, size_t size)
{
	const char *bin = getenv("STRAY_BIN");
	char cmd[1600], path[700];
	FILE *f;
	int status;

	snprintf(path, sizeof(path), "%s/out.txt", dm.dir);
	snprintf(cmd, sizeof(cmd), "%s rig --socket '%s' %s >'%s' 2>&1",
		 bin ? bin : "build/bin/stray", dm.sock, args, path);
	status = system(cmd);
	f = fopen(path, "r");
	out[0] = '\0';
	if (f && !fgets(out, (int)size, f))
		out[0] = '\0';
	if (f)
		fclose(f);
	return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void test_daemon_stray_rig_client(void **state)
{
	char out[4096];
	cJSON *r;

	(void)state;
	assert_int_equal(stray_rig("--json status", out, sizeof(out)), 0);
	r = cJSON_Parse(out);
	assert_non_null(r);
	assert_true(ok_of(r));
	assert_non_null(cJSON_GetObjectItem(r, "state"));
	cJSON_Delete(r);
	assert_int_equal(stray_rig("move 120", out, sizeof(out)), 1);
	assert_non_null(strstr(out, "outside limits"));
	assert_int_equal(stray_rig("move north", out, sizeof(out)), 2);
	assert_int_equal(stray_rig("teleport", out, sizeof(out)), 2);
	/* --force-plan only with --resume (a new sweep has no plan yet) */
	assert_int_equal(stray_rig("sweep /tmp/never --force-plan", out,
				   sizeof(out)), 2);
	assert_int_equal(stray_rig("move 3", out, sizeof(out)), 0);
}

static cJSON *wait_state(const char *want, int tries)
{
	cJSON *r = NULL;

	while (tries-- > 0) {
		cJSON_Delete(r);
		r = ask("{\"cmd\":\"status\"}");
		if (r && !strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(r,
						      "state")), want))
			return r;
		nap_ms(20);
	}
	return r;
}

static void test_daemon_sweep_pause_resume(void **state)
{
	char req[800], out[700];
	struct rig_config cfg;
	struct rig_error err;
	cJSON *r, *sw;

	(void)state;
	snprintf(out, sizeof(out), "%s/sweep", dm.dir);
	snprintf(req, sizeof(req), "{\"cmd\":\"sweep\",\"dir\":\"%s\"}", out);
	r = ask(req);
	assert_true(ok_of(r));
	cJSON_Delete(r);
	expect_refusal("{\"cmd\":\"move\",\"theta_deg\":3}",
		       "while a sweep is running");
	expect_refusal(req, "while a sweep is running");
	r = ask("{\"cmd\":\"pause\"}");
	assert_true(ok_of(r));
	cJSON_Delete(r);
	r = ask("{\"cmd\":\"status\"}");
	assert_string_equal(cJSON_GetStringValue(cJSON_GetObjectItem(r,
						 "state")), "paused");
	assert_true(num_of(r, "lamp") == 0);	/* paused safe */
	sw = cJSON_GetObjectItem(r, "sweep");
	assert_non_null(sw);
	assert_true(num_of(sw, "total") > num_of(sw, "done"));
	cJSON_Delete(r);
	r = ask("{\"cmd\":\"resume\"}");
	assert_true(ok_of(r));
	cJSON_Delete(r);
	r = wait_state("idle", 1500);
	sw = cJSON_GetObjectItem(r, "sweep");
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(sw, "finished")));
	assert_true(num_of(sw, "done") == num_of(sw, "total"));
	assert_true(num_of(r, "lamp") == 0);
	cJSON_Delete(r);
	rig_config_defaults(&cfg);
	rig_error_clear(&err);
	assert_int_equal(rig_config_load(&cfg, dm.conf, &err), RIG_OK);
	assert_int_equal(check_sweep(out, &cfg).bad, 0);
}

static void test_daemon_abort_then_sigterm_safe(void **state)
{
	char req[800];
	cJSON *r;
	int status;

	(void)state;
	snprintf(req, sizeof(req), "{\"cmd\":\"sweep\",\"dir\":\"%s/s2\"}",
		 dm.dir);
	r = ask(req);
	assert_true(ok_of(r));
	cJSON_Delete(r);
	r = ask("{\"cmd\":\"abort\"}");
	assert_true(ok_of(r));
	cJSON_Delete(r);
	r = ask("{\"cmd\":\"status\"}");
	assert_string_equal(cJSON_GetStringValue(cJSON_GetObjectItem(r,
						 "state")), "idle");
	assert_true(num_of(r, "lamp") == 0 && num_of(r, "shutter_open") == 0 &&
		    num_of(r, "beam_blocked") == 1);
	cJSON_Delete(r);
	kill(dm.pid, SIGTERM);
	assert_int_equal(waitpid(dm.pid, &status, 0), dm.pid);
	dm.pid = 0;
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	assert_int_not_equal(access(dm.sock, F_OK), 0);	/* removed */
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_daemon_socket_is_private),
		cmocka_unit_test(test_daemon_starts_safe),
		cmocka_unit_test(test_daemon_rejects_malformed),
		cmocka_unit_test(test_daemon_move_and_limits),
		cmocka_unit_test(test_daemon_stray_rig_client),
		cmocka_unit_test(test_daemon_sweep_pause_resume),
		cmocka_unit_test(test_daemon_abort_then_sigterm_safe),
	};

	return cmocka_run_group_tests(tests, start_daemon, stop_daemon);
}
