/*
 * test_clients.c - strayrigd's control connections (rig/daemon/clients.c)
 * against a running daemon: no client can stall another.  A client that
 * trickles its request byte by byte, or idle clients that never send,
 * must not hold back `safe` or `status` from another client (issue 14:
 * one byte every 0.8 s kept `safe` unanswered over 60 s; five idle
 * clients delayed `status` by 5 s).  The checks are logical (the other
 * client is answered while the trickler's request is still incomplete
 * and unanswered); the latencies are measured and printed, not asserted
 * against a tight timer.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig_daemon_util.h"
#include "rig_test_util.h"

#define N_TRIES 15

static struct {
	char *dir;
	char sock[600], conf[600], errf[600];
	pid_t pid;
} dm;

static int start_daemon(void **state)
{
	const char *args[] = { "--config", dm.conf, "--socket", dm.sock,
			       NULL };

	(void)state;
	dm.dir = temp_dir();
	snprintf(dm.sock, sizeof(dm.sock), "%s/rig.sock", dm.dir);
	snprintf(dm.conf, sizeof(dm.conf), "%s/rig.json", dm.dir);
	snprintf(dm.errf, sizeof(dm.errf), "%s/err.txt", dm.dir);
	put_file(dm.conf, "{\"camera\":{\"rows\":[960,961,1100,1101],"
		 "\"col0\":960,\"n_cols\":128},\"sweep\":{\"theta_stop_deg\""
		 ":30,\"theta_step_deg\":10,\"repeats\":2}}");
	dm.pid = spawn_rigd(args, dm.errf);
	return dm.pid > 0 && wait_answers(dm.sock, 5000) ? 0 : -1;
}

static int stop_daemon(void **state)
{
	(void)state;
	kill(dm.pid, SIGTERM);
	wait_exit(dm.pid, 5000);
	remove_tree(dm.dir);
	free(dm.dir);
	return 0;
}

/* `safe` from another client, timed; asserts it was answered ok. */
static double timed_safe(void)
{
	double t0 = ms_now(), dt;
	cJSON *r = ask_on(dm.sock, "{\"cmd\":\"safe\"}");

	dt = ms_now() - t0;
	assert_non_null(r);
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(r, "ok")));
	cJSON_Delete(r);
	return dt;
}

static void report(const char *what, double *t, int n)
{
	qsort(t, (size_t)n, sizeof(*t), cmp_double);
	print_message("%s over %d tries: median %.2f ms, max %.2f ms\n",
		      what, n, t[n / 2], t[n - 1]);
}

/* A client sends its request one byte at a time; between its bytes
 * another client asks `safe`, which must come back while the trickler's
 * request is still incomplete and unanswered. */
static void test_clients_trickler_does_not_stall_safe(void **state)
{
	const char *req = "{\"cmd\":\"status\",\"pad\":\"xxxxxxxxxxxx\"}\n";
	double t[N_TRIES];
	int fd = dial(dm.sock), i;

	(void)state;
	assert_true(fd >= 0);
	assert_true(strlen(req) > N_TRIES);
	for (i = 0; i < N_TRIES; i++) {
		assert_int_equal(write(fd, req + i, 1), 1);
		t[i] = timed_safe();
		/* The trickler is neither answered nor dropped yet. */
		assert_false(readable(fd, 0));
		nap_ms(40);
	}
	close(fd);
	report("safe under a trickling client", t, N_TRIES);
}

/* A trickler that is not done by its deadline is dropped: EOF, no
 * answer, within a few seconds of its connect. */
static void test_clients_trickler_dropped_at_deadline(void **state)
{
	char buf[64];
	double t0 = ms_now();
	int fd = dial(dm.sock);

	(void)state;
	assert_true(fd >= 0);
	assert_int_equal(write(fd, "{\"cmd\"", 6), 6);
	while (!readable(fd, 100) && ms_now() - t0 < 6000)
		if (write(fd, " ", 1) != 1)
			break;
	assert_true(readable(fd, 0));
	assert_int_equal(read(fd, buf, sizeof(buf)), 0);	/* no answer */
	print_message("trickler dropped after %.0f ms (deadline %d ms)\n",
		      ms_now() - t0, 2000);
	close(fd);
}

/* Idle clients that never send do not delay `status`, and are still
 * pending (unanswered, open) when it comes back. */
static void test_clients_idle_do_not_delay_status(void **state)
{
	int fd[5], i, k;
	double t[N_TRIES];

	(void)state;
	for (i = 0; i < 5; i++)
		assert_true((fd[i] = dial(dm.sock)) >= 0);
	for (k = 0; k < N_TRIES; k++) {
		double t0 = ms_now();
		cJSON *r = ask_on(dm.sock, "{\"cmd\":\"status\"}");

		t[k] = ms_now() - t0;
		assert_non_null(r);
		assert_true(cJSON_IsTrue(cJSON_GetObjectItem(r, "ok")));
		cJSON_Delete(r);
		for (i = 0; i < 5; i++)
			assert_false(readable(fd[i], 0));
		if (ms_now() - t0 > 1500)
			break;
	}
	for (i = 0; i < 5; i++)
		close(fd[i]);
	report("status with 5 idle clients", t, k < N_TRIES ? k + 1 : k);
}

/* More connections than slots: the oldest are dropped, a new client is
 * still answered. */
static void test_clients_full_table_drops_oldest(void **state)
{
	int fd[40], i, dropped = 0;
	cJSON *r;

	(void)state;
	for (i = 0; i < 40; i++)
		assert_true((fd[i] = dial(dm.sock)) >= 0);
	r = ask_on(dm.sock, "{\"cmd\":\"status\"}");
	assert_non_null(r);
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(r, "ok")));
	cJSON_Delete(r);
	for (i = 0; i < 40; i++) {
		dropped += readable(fd[i], 0);
		close(fd[i]);
	}
	assert_true(dropped >= 40 + 1 - 32);
}

/* A request that ends with EOF instead of a newline is still answered;
 * one longer than the limit is refused. */
static void test_clients_eof_and_long_request(void **state)
{
	char buf[256], *big = malloc(8192);
	ssize_t n;
	int fd = dial(dm.sock);

	(void)state;
	assert_true(fd >= 0);
	assert_int_equal(write(fd, "{\"cmd\":\"status\"}", 16), 16);
	shutdown(fd, SHUT_WR);
	n = read(fd, buf, sizeof(buf) - 1);
	assert_true(n > 0);
	buf[n] = '\0';
	assert_non_null(strstr(buf, "\"ok\":true"));
	close(fd);
	memset(big, 'x', 8192);
	fd = dial(dm.sock);
	assert_true(fd >= 0);
	assert_int_equal(write(fd, big, 8192), 8192);
	n = read(fd, buf, sizeof(buf) - 1);
	assert_true(n > 0);
	buf[n] = '\0';
	assert_non_null(strstr(buf, "request too long"));
	close(fd);
	free(big);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_clients_trickler_does_not_stall_safe),
		cmocka_unit_test(test_clients_trickler_dropped_at_deadline),
		cmocka_unit_test(test_clients_idle_do_not_delay_status),
		cmocka_unit_test(test_clients_full_table_drops_oldest),
		cmocka_unit_test(test_clients_eof_and_long_request),
	};

	return cmocka_run_group_tests(tests, start_daemon, stop_daemon);
}
