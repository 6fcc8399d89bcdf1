/*
 * test_listen.c - claiming strayrigd's control socket
 * (rig/daemon/listen.c), with real daemons: a second daemon on a live
 * socket is refused (exit 1) and the first stays reachable; a regular
 * file at the socket path is refused (exit 2) and left as it was; a
 * stale socket (nobody listening) is replaced; a world-writable
 * socket_mode is refused before anything starts (issue 14).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <sys/stat.h>

#include "rig_daemon_util.h"
#include "rig_test_util.h"

struct lab {
	char *dir;
	char sock[600], conf[600], err1[600], err2[600];
};

static void lab_init(struct lab *l, const char *extra)
{
	char text[600];

	l->dir = temp_dir();
	assert_non_null(l->dir);
	snprintf(l->sock, sizeof(l->sock), "%s/rig.sock", l->dir);
	snprintf(l->conf, sizeof(l->conf), "%s/rig.json", l->dir);
	snprintf(l->err1, sizeof(l->err1), "%s/err1.txt", l->dir);
	snprintf(l->err2, sizeof(l->err2), "%s/err2.txt", l->dir);
	snprintf(text, sizeof(text), "{\"camera\":{\"rows\":[960,961,1100,"
		 "1101],\"col0\":960,\"n_cols\":128}%s}", extra);
	put_file(l->conf, text);
}

static void lab_fini(struct lab *l)
{
	remove_tree(l->dir);
	free(l->dir);
}

static pid_t serve(struct lab *l, const char *errpath)
{
	const char *args[] = { "--config", l->conf, "--socket", l->sock,
			       NULL };

	return spawn_rigd(args, errpath);
}

static void test_listen_live_socket_refused(void **state)
{
	struct lab l;
	char msg[1024];
	pid_t a, b;

	(void)state;
	lab_init(&l, "");
	a = serve(&l, l.err1);
	assert_true(wait_answers(l.sock, 5000));
	b = serve(&l, l.err2);
	assert_int_equal(wait_exit(b, 5000), 1);
	get_file(l.err2, msg, sizeof(msg));
	print_message("second daemon: %s", msg);
	assert_non_null(strstr(msg, "not taken over"));
	/* one line */
	assert_ptr_equal(strchr(msg, '\n'), msg + strlen(msg) - 1);
	/* The first still owns the socket and answers on it. */
	assert_true(wait_answers(l.sock, 1000));
	kill(a, SIGTERM);
	assert_int_equal(wait_exit(a, 5000), 0);
	lab_fini(&l);
}

static void test_listen_regular_file_kept(void **state)
{
	struct lab l;
	char msg[1024], path[700];
	const char *args[] = { "--config", NULL, "--socket", path, NULL };
	pid_t b;

	(void)state;
	lab_init(&l, "");
	snprintf(path, sizeof(path), "%s/notes.txt", l.dir);
	put_file(path, "precious\n");
	args[1] = l.conf;
	b = spawn_rigd(args, l.err2);
	assert_int_equal(wait_exit(b, 5000), 2);
	get_file(l.err2, msg, sizeof(msg));
	assert_non_null(strstr(msg, "not a socket"));
	get_file(path, msg, sizeof(msg));
	assert_string_equal(msg, "precious\n");
	lab_fini(&l);
}

static void test_listen_stale_socket_replaced(void **state)
{
	struct sockaddr_un a;
	struct lab l;
	struct stat st;
	pid_t d;
	int fd;

	(void)state;
	lab_init(&l, "");
	/* A socket file whose owner died: bound, never listened, closed. */
	fd = socket(AF_UNIX, SOCK_STREAM, 0);
	memset(&a, 0, sizeof(a));
	a.sun_family = AF_UNIX;
	strcpy(a.sun_path, l.sock);
	assert_int_equal(bind(fd, (struct sockaddr *)&a, sizeof(a)), 0);
	close(fd);
	assert_int_equal(stat(l.sock, &st), 0);
	d = serve(&l, l.err1);
	assert_true(wait_answers(l.sock, 5000));
	kill(d, SIGTERM);
	assert_int_equal(wait_exit(d, 5000), 0);
	lab_fini(&l);
}

/* o+w in socket_mode (0777, 0666, 0602) refused with exit 2 naming the
 * key; 0660 accepted. */
static void test_listen_world_writable_mode_refused(void **state)
{
	static const char *const bad[] = { ",\"socket_mode\":511",
					   ",\"socket_mode\":438",
					   ",\"socket_mode\":386" };
	struct lab l;
	struct stat st;
	char msg[1024];
	size_t i;
	pid_t d;

	(void)state;
	for (i = 0; i < sizeof(bad) / sizeof(*bad); i++) {
		lab_init(&l, bad[i]);
		d = serve(&l, l.err1);
		assert_int_equal(wait_exit(d, 5000), 2);
		get_file(l.err1, msg, sizeof(msg));
		assert_non_null(strstr(msg, "socket_mode"));
		assert_non_null(strstr(msg, "world-writable"));
		assert_int_not_equal(access(l.sock, F_OK), 0);
		lab_fini(&l);
	}
	lab_init(&l, ",\"socket_mode\":432");
	d = serve(&l, l.err1);
	assert_true(wait_answers(l.sock, 5000));
	assert_int_equal(stat(l.sock, &st), 0);
	assert_int_equal(st.st_mode & 0777, 0660);
	kill(d, SIGTERM);
	assert_int_equal(wait_exit(d, 5000), 0);
	lab_fini(&l);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_listen_live_socket_refused),
		cmocka_unit_test(test_listen_regular_file_kept),
		cmocka_unit_test(test_listen_stale_socket_replaced),
		cmocka_unit_test(test_listen_world_writable_mode_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
