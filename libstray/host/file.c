/*
 * file.c - whole-file reads and atomic writes (hosted).
 */
#define _DEFAULT_SOURCE	/* syscall */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <sys/syscall.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/file.h"

int stray_file_read(const char *path, char **buf, size_t *len,
		    struct stray_error *err)
{
	FILE *f = fopen(path, "rb");
	struct stat st;
	size_t cap = 65536, n = 0;
	char *b;

	*buf = NULL;
	*len = 0;
	if (!f)		/* a missing input is the caller's mistake: bad input */
		return stray_error_at(err, errno == ENOENT || errno == ENOTDIR ? STRAY_ENOTFOUND
				      : errno == EISDIR ? STRAY_EINVAL : STRAY_EIO,
				      path, 0, 0, errno == EISDIR
				      ? "is a directory, not a file"
				      : strerror(errno));
	/* a pipe (/dev/stdin, <(cmd)) is read up to the limit; a directory
	 * or a device never */
	if (fstat(fileno(f), &st) == 0 && !S_ISREG(st.st_mode) &&
	    !S_ISFIFO(st.st_mode)) {
		fclose(f);
		return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
				      S_ISDIR(st.st_mode)
				      ? "is a directory, not a file"
				      : "is not a regular file");
	}
	if (fstat(fileno(f), &st) == 0 && st.st_size > STRAY_FILE_READ_MAX) {
		fclose(f);
		return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
				      "larger than the 256 MiB input limit "
				      "(docs/limits.md)");
	}
	b = malloc(cap);
	while (b) {
		n += fread(b + n, 1, cap - n - 1, f);
		if (n < cap - 1 || n > (size_t)STRAY_FILE_READ_MAX)
			break;
		cap *= 2;
		{
			char *nb = realloc(b, cap);

			if (!nb)
				free(b);
			b = nb;
		}
	}
	if (!b) {
		fclose(f);
		return stray_error_at(err, STRAY_ENOMEM, path, 0, 0, 0);
	}
	if (n > (size_t)STRAY_FILE_READ_MAX) {	/* grew while being read */
		free(b);
		fclose(f);
		return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
				      "larger than the 256 MiB input limit "
				      "(docs/limits.md)");
	}
	if (ferror(f)) {
		free(b);
		fclose(f);
		return stray_error_at(err, STRAY_EIO, path, 0, 0, "read error");
	}
	fclose(f);
	stray_file_note_input(path);	/* its outputs may not replace it */
	b[n] = '\0';
	*buf = b;
	*len = n;
	return STRAY_OK;
}

/*
 * Pending temporaries: a fixed registry of the paths being written, so a
 * SIGINT/SIGTERM (or an exit that skipped stray_file_abort) removes them.
 * The handler only calls unlink, signal and raise (async-signal-safe).
 */
#define PENDING_MAX 16

static char pending[PENDING_MAX][sizeof(((struct stray_file_out *)0)->tmp)];
static volatile sig_atomic_t pending_used[PENDING_MAX];
static int handlers_set;

/* Deferred mode: closed temporaries wait here for stray_file_finish. */
static char ready_path[PENDING_MAX][sizeof(pending[0])];	/* copies */
static int ready[PENDING_MAX];
static int deferring;

static pid_t pending_owner;	/* a forked child never removes them */

/* One entry of getdents64 (Linux): the raw call is async-signal-safe,
 * opendir is not. */
struct dirent64_raw {
	uint64_t ino;
	int64_t off;
	unsigned short reclen;
	unsigned char type;
	char name[];
};

/* Unlink every entry of the open folder fd; a subfolder (sub set) is
 * emptied the same way one level down and removed (`stray sweep import`
 * keeps its originals in original/).  Raw system calls only. */
static void unlink_entries(int fd, int sub)
{
	long long buf[512];	/* aligned for the entries */
	long n, i;

	while ((n = syscall(SYS_getdents64, fd, buf, sizeof(buf))) > 0)
		for (i = 0; i < n;) {
			struct dirent64_raw *d = (struct dirent64_raw *)
				((char *)buf + i);
			int cfd;

			if (strcmp(d->name, ".") && strcmp(d->name, "..") &&
			    unlinkat(fd, d->name, 0) != 0 && errno == EISDIR &&
			    sub && (cfd = openat(fd, d->name, O_RDONLY |
						 O_DIRECTORY | O_NOFOLLOW)) >= 0) {
				unlink_entries(cfd, 0);
				close(cfd);
				unlinkat(fd, d->name, AT_REMOVEDIR);
			}
			i += d->reclen;
		}
}

/* Remove a temporary folder and the files in it (a sweep folder holds
 * files, and an imported one its original/ folder of files); raw system
 * calls only, so the handler may call it. */
static void remove_dir_flat(const char *dir)
{
	int pass, fd;

	for (pass = 0; pass < 4; pass++) {
		if ((fd = open(dir, O_RDONLY | O_DIRECTORY)) < 0)
			return;
		unlink_entries(fd, 1);
		close(fd);
		if (rmdir(dir) == 0 || errno != ENOTEMPTY)
			return;
	}
}

/* A temporary file, or a temporary folder with its files. */
static void remove_tmp(const char *path)
{
	if (unlink(path) != 0 && (errno == EISDIR || errno == EPERM))
		remove_dir_flat(path);
}

static void pending_unlink_all(void)
{
	int i;

	if (getpid() != pending_owner)
		return;
	for (i = 0; i < PENDING_MAX; i++)
		if (pending_used[i]) {
			remove_tmp(pending[i]);
			pending_used[i] = 0;
		}
}

static void on_signal(int sig)
{
	pending_unlink_all();
	signal(sig, SIG_DFL);
	raise(sig);
}

static void install_handlers(void)
{
	static const int sigs[] = { SIGINT, SIGTERM, SIGHUP };
	size_t i;

	if (handlers_set)
		return;
	handlers_set = 1;
	atexit(pending_unlink_all);
	for (i = 0; i < sizeof(sigs) / sizeof(sigs[0]); i++) {
		struct sigaction old, sa;

		/* leave a program's own handlers (and ignored signals) alone */
		if (sigaction(sigs[i], NULL, &old) != 0 ||
		    old.sa_handler != SIG_DFL)
			continue;
		memset(&sa, 0, sizeof(sa));
		sa.sa_handler = on_signal;
		sigemptyset(&sa.sa_mask);
		sigaction(sigs[i], &sa, NULL);
	}
}

static int pending_add(const char *tmp)
{
	int i;

	install_handlers();
	pending_owner = getpid();
	for (i = 0; i < PENDING_MAX; i++)
		if (!pending_used[i]) {
			memcpy(pending[i], tmp, strlen(tmp) + 1);
			pending_used[i] = 1;
			return 0;
		}
	return -1;
}

static int pending_find(const char *tmp)
{
	int i;

	for (i = 0; i < PENDING_MAX; i++)
		if (pending_used[i] && strcmp(pending[i], tmp) == 0)
			return i;
	return -1;
}

static void pending_drop(const char *tmp)
{
	int i = pending_find(tmp);

	if (i >= 0) {
		ready[i] = 0;
		pending_used[i] = 0;
	}
}

void stray_file_defer(void)
{
	deferring = 1;
}

int stray_file_finish(int ok, struct stray_error *err)
{
	int i, rc = STRAY_OK;

	deferring = 0;
	for (i = 0; i < PENDING_MAX; i++) {
		if (!pending_used[i] || !ready[i])
			continue;
		if (ok && rc == STRAY_OK && rename(pending[i], ready_path[i]) != 0)
			rc = stray_error_at(err, STRAY_EIO, ready_path[i], 0, 0,
					    strerror(errno));
		else if (!ok || rc != STRAY_OK)
			remove_tmp(pending[i]);
		ready[i] = 0;
		pending_used[i] = 0;
	}
	return rc;
}

int stray_file_open_atomic(struct stray_file_out *out, const char *path,
			   struct stray_error *err)
{
	struct stat st;
	int n;

	out->path = path;
	out->f = NULL;
	out->tmp[0] = '\0';
	if (stray_file_claim_output(path, err) != STRAY_OK)
		return STRAY_EINVAL;
	if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
		/* /dev/stdout, a pipe: written in place, never renamed over
		 * (as root that would replace the device node) */
		if (S_ISDIR(st.st_mode))
			return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
					      "is a directory, not a file");
		out->f = fopen(path, "wb");
		if (!out->f)
			return stray_error_at(err, STRAY_EIO, path, 0, 0,
					      strerror(errno));
		return STRAY_OK;
	}
	n = snprintf(out->tmp, sizeof(out->tmp), "%s.tmp.%ld", path,
		     (long)getpid());
	if (n < 0 || (size_t)n >= sizeof(out->tmp)) {
		out->tmp[0] = '\0';
		return stray_error_at(err, STRAY_EINVAL, path, 0, "path",
				      "too long");
	}
	if (pending_add(out->tmp) != 0)
		return stray_error_at(err, STRAY_EIO, path, 0, 0,
				      "too many files open for writing");
	out->f = fopen(out->tmp, "wb");
	if (!out->f) {
		int saved = errno;

		pending_drop(out->tmp);
		return stray_error_at(err, STRAY_EIO, path, 0, 0,
				      strerror(saved));
	}
	return STRAY_OK;
}

int stray_file_commit(struct stray_file_out *out, struct stray_error *err)
{
	int bad, saved;

	if (!out->tmp[0]) {	/* a device or pipe, written in place */
		bad = ferror(out->f) || fflush(out->f) != 0;
		saved = errno;
		if (fclose(out->f) != 0 && !bad) {
			bad = 1;
			saved = errno;
		}
		out->f = NULL;
		return bad ? stray_error_at(err, STRAY_EIO, out->path, 0, 0,
				saved ? strerror(saved) : "write error")
			   : STRAY_OK;
	}
	bad = ferror(out->f) || fflush(out->f) != 0 ||
	      fsync(fileno(out->f)) != 0;
	saved = errno;

	if (fclose(out->f) != 0 && !bad) {
		bad = 1;
		saved = errno;
	}
	out->f = NULL;
	if (!bad && deferring) {	/* renamed by stray_file_finish */
		int i = pending_find(out->tmp);

		size_t n = strlen(out->path);

		if (i >= 0 && n < sizeof(ready_path[i])) {
			memcpy(ready_path[i], out->path, n + 1);
			ready[i] = 1;
			return STRAY_OK;
		}
	}
	if (!bad && rename(out->tmp, out->path) == 0) {
		pending_drop(out->tmp);
		return STRAY_OK;
	}
	if (!bad)
		saved = errno;
	remove(out->tmp);
	pending_drop(out->tmp);
	return stray_error_at(err, STRAY_EIO, out->path, 0, 0,
			      saved ? strerror(saved) : "write error");
}

void stray_file_abort(struct stray_file_out *out)
{
	if (out->f)
		fclose(out->f);
	out->f = NULL;
	if (out->tmp[0]) {
		remove(out->tmp);
		pending_drop(out->tmp);
	}
}

int stray_dir_open_atomic(struct stray_dir_out *out, const char *path,
			  struct stray_error *err)
{
	struct stat st;
	int n;

	out->path = path;
	out->tmp[0] = '\0';
	if (stray_file_claim_output(path, err) != STRAY_OK)
		return STRAY_EINVAL;
	if (stat(path, &st) == 0) {
		if (!S_ISDIR(st.st_mode))
			return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
					      "exists and is not a folder");
		if (rmdir(path) != 0)	/* an empty folder is replaced */
			return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
				"exists and is not empty; give a new folder");
		if (mkdir(path, 0777) != 0)
			return stray_error_at(err, STRAY_EIO, path, 0, 0,
					      strerror(errno));
	}
	n = snprintf(out->tmp, sizeof(out->tmp), "%s.tmp.%ld", path,
		     (long)getpid());
	if (n < 0 || (size_t)n >= sizeof(out->tmp)) {
		out->tmp[0] = '\0';
		return stray_error_at(err, STRAY_EINVAL, path, 0, "path",
				      "too long");
	}
	if (pending_add(out->tmp) != 0) {
		out->tmp[0] = '\0';
		return stray_error_at(err, STRAY_EIO, path, 0, 0,
				      "too many files open for writing");
	}
	if (mkdir(out->tmp, 0777) != 0) {
		int saved = errno;

		pending_drop(out->tmp);
		out->tmp[0] = '\0';
		return stray_error_at(err, STRAY_EIO, path, 0, 0,
				      strerror(saved));
	}
	return STRAY_OK;
}

int stray_dir_commit(struct stray_dir_out *out, struct stray_error *err)
{
	int i = pending_find(out->tmp), fd;
	size_t n = strlen(out->path);

	if (deferring && i >= 0 && n < sizeof(ready_path[i])) {
		memcpy(ready_path[i], out->path, n + 1);
		ready[i] = 1;	/* renamed by stray_file_finish */
		return STRAY_OK;
	}
	if ((fd = open(out->tmp, O_RDONLY | O_DIRECTORY)) >= 0) {
		fsync(fd);
		close(fd);
	}
	if (rename(out->tmp, out->path) == 0) {
		pending_drop(out->tmp);
		return STRAY_OK;
	}
	i = errno;
	stray_dir_abort(out);
	return stray_error_at(err, STRAY_EIO, out->path, 0, 0, strerror(i));
}

void stray_dir_abort(struct stray_dir_out *out)
{
	if (out->tmp[0]) {
		remove_tmp(out->tmp);
		pending_drop(out->tmp);
		out->tmp[0] = '\0';
	}
}
