/*
 * rig_daemon_util.h - helpers of the tests that run strayrigd as a user
 * would: spawn it with arguments and its stderr in a file, wait for its
 * exit with a limit, talk to its Unix socket, and a monotonic clock in
 * milliseconds for the latencies the tests report.
 */
#ifndef RIG_DAEMON_UTIL_H
#define RIG_DAEMON_UTIL_H

#include <cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static inline double ms_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static inline void nap_ms(long ms)
{
	struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };

	nanosleep(&ts, NULL);
}

static inline void put_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");

	if (f) {
		fputs(text, f);
		fclose(f);
	}
}

/* Whole small file into buf ("" if missing). */
static inline void get_file(const char *path, char *buf, size_t size)
{
	FILE *f = fopen(path, "r");
	size_t n = f ? fread(buf, 1, size - 1, f) : 0;

	buf[n] = '\0';
	if (f)
		fclose(f);
}

/* strayrigd with args (NULL-terminated), stderr to errpath. */
static inline pid_t spawn_rigd(const char *const *args, const char *errpath)
{
	const char *b = getenv("STRAY_BUILD");
	char bin[512];
	const char *argv[16];
	pid_t pid;
	int i;

	snprintf(bin, sizeof(bin), "%s/bin/strayrigd", b ? b : "build");
	argv[0] = bin;
	for (i = 0; args[i] && i < 14; i++)
		argv[i + 1] = args[i];
	argv[i + 1] = NULL;
	pid = fork();
	if (pid == 0) {
		int fd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644);

		if (fd >= 0)
			dup2(fd, 2);
		execv(bin, (char *const *)argv);
		_exit(127);
	}
	return pid;
}

/* Exit status of pid within limit_ms, or -1 (then it is killed). */
static inline int wait_exit(pid_t pid, long limit_ms)
{
	double t0 = ms_now();
	int status;

	while (ms_now() - t0 < limit_ms) {
		if (waitpid(pid, &status, WNOHANG) == pid)
			return WIFEXITED(status) ? WEXITSTATUS(status)
						 : 128 + WTERMSIG(status);
		nap_ms(10);
	}
	kill(pid, SIGKILL);
	waitpid(pid, &status, 0);
	return -1;
}

/* A connected client socket, or -1. */
static inline int dial(const char *sock)
{
	struct sockaddr_un a;
	int fd = socket(AF_UNIX, SOCK_STREAM, 0);

	memset(&a, 0, sizeof(a));
	a.sun_family = AF_UNIX;
	if (strlen(sock) >= sizeof(a.sun_path)) {
		close(fd);
		return -1;
	}
	memcpy(a.sun_path, sock, strlen(sock));
	if (fd >= 0 && connect(fd, (struct sockaddr *)&a, sizeof(a)) != 0) {
		close(fd);
		fd = -1;
	}
	return fd;
}

/* One request, one parsed response; NULL if nobody answers. */
static inline cJSON *ask_on(const char *sock, const char *req)
{
	char buf[8192];
	size_t n = 0;
	ssize_t k;
	int fd = dial(sock);

	if (fd < 0)
		return NULL;
	if (write(fd, req, strlen(req)) < 0 || write(fd, "\n", 1) != 1) {
		close(fd);
		return NULL;
	}
	while (n < sizeof(buf) - 1 &&
	       (k = read(fd, buf + n, sizeof(buf) - 1 - n)) > 0)
		n += (size_t)k;
	buf[n] = '\0';
	close(fd);
	return cJSON_Parse(buf);
}

/* 1 when fd has something to read (an answer, or EOF) within wait_ms. */
static inline int readable(int fd, int wait_ms)
{
	struct pollfd p = { fd, POLLIN, 0 };

	return poll(&p, 1, wait_ms) > 0;
}

/* Wait until the daemon answers status on sock (up to limit_ms). */
static inline int wait_answers(const char *sock, long limit_ms)
{
	double t0 = ms_now();
	cJSON *r;

	while (ms_now() - t0 < limit_ms) {
		if ((r = ask_on(sock, "{\"cmd\":\"status\"}")) != NULL) {
			cJSON_Delete(r);
			return 1;
		}
		nap_ms(10);
	}
	return 0;
}

static inline int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

#endif /* RIG_DAEMON_UTIL_H */
