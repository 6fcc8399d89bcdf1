/*
 * file_guard.c - one run's inputs and outputs (hosted; stray/file.h).
 *
 * `stray diagnose m.csv --write-model m.csv` used to replace the lab data
 * with a scene file: nothing compared an output with what the run had
 * read, or with its other outputs.  Once a program calls
 * stray_file_run_begin (the `stray` CLI does, before any command), every
 * file read (stray_file_read, or a reader calling stray_file_note_input)
 * is remembered by identity (st_dev, st_ino: a hard link or a second
 * spelling is the same file), and every output opened through
 * stray_file_open_atomic / stray_dir_open_atomic by canonical path (real
 * parent folder + name, so "./a.csv" and "a.csv" are one output).  An
 * output that is an input already read, or an output already opened in
 * this run, is refused before a byte is written.  Library users that
 * never begin a run (tests, the rig daemon rewriting its state) see no
 * change.  Devices and pipes (/dev/null, /dev/stdout) are never compared.
 */
#define _DEFAULT_SOURCE	/* realpath */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "stray/errfmt.h"
#include "stray/file.h"

struct ident {
	dev_t dev;
	ino_t ino;
};

static int armed;
static struct ident *inputs;
static size_t n_inputs, cap_inputs;
static char **outputs;
static size_t n_outputs, cap_outputs;

static void forget_all(void)
{
	size_t i;

	for (i = 0; i < n_outputs; i++)
		free(outputs[i]);
	free(outputs);
	free(inputs);
	outputs = NULL;
	inputs = NULL;
	n_outputs = cap_outputs = n_inputs = cap_inputs = 0;
}

void stray_file_run_begin(void)
{
	forget_all();
	armed = 1;
}

void stray_file_run_end(void)
{
	forget_all();
	armed = 0;
}

/* A growing array; 0 on success, -1 without memory (then the entry is
 * not recorded: the guard fails open rather than refuse a good run). */
static int grow(void **arr, size_t *cap, size_t n, size_t elem)
{
	size_t want = *cap ? 2 * *cap : 16;
	void *p;

	if (n < *cap)
		return 0;
	if (!(p = realloc(*arr, want * elem)))
		return -1;
	*arr = p;
	*cap = want;
	return 0;
}

void stray_file_note_input(const char *path)
{
	struct stat st;
	size_t i;

	if (!armed || !path || stat(path, &st) != 0 ||
	    !(S_ISREG(st.st_mode) || S_ISDIR(st.st_mode)))
		return;
	for (i = 0; i < n_inputs; i++)
		if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino)
			return;
	if (grow((void **)&inputs, &cap_inputs, n_inputs, sizeof(*inputs)))
		return;
	inputs[n_inputs].dev = st.st_dev;
	inputs[n_inputs].ino = st.st_ino;
	n_inputs++;
}

void stray_file_forget_input(const char *path)
{
	struct stat st;
	size_t i;

	if (!armed || !path || stat(path, &st) != 0)
		return;
	for (i = 0; i < n_inputs; i++)
		if (inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino) {
			inputs[i] = inputs[--n_inputs];
			return;
		}
}

void stray_file_forget_output(const char *path)
{
	char c[PATH_MAX];
	size_t i;

	if (!armed || !path || stray_file_canonical(path, c, sizeof(c)) != 0)
		return;
	for (i = 0; i < n_outputs; i++)
		if (strcmp(outputs[i], c) == 0) {
			free(outputs[i]);
			outputs[i] = outputs[--n_outputs];
			return;
		}
}

int stray_file_canonical(const char *path, char *out, size_t size)
{
	char dir[PATH_MAX], real[PATH_MAX];
	const char *slash = strrchr(path, '/'), *name;
	size_t dlen;
	int n;

	if (!path[0])
		return -1;
	if (!slash) {
		strcpy(dir, ".");
		name = path;
	} else {
		dlen = (size_t)(slash - path);
		if (dlen >= sizeof(dir))
			return -1;
		memcpy(dir, path, dlen);
		dir[dlen ? dlen : 1] = '\0';	/* "/name": the root */
		if (!dlen)
			dir[0] = '/';
		name = slash + 1;
	}
	if (!realpath(dir, real))	/* no such folder: the raw spelling */
		n = snprintf(out, size, "%s", path);
	else if (!name[0] || !strcmp(name, ".") || !strcmp(name, ".."))
		n = realpath(path, real) ? snprintf(out, size, "%s", real)
					 : snprintf(out, size, "%s", path);
	else
		n = snprintf(out, size, "%s%s%s", real,
			     strcmp(real, "/") ? "/" : "", name);
	return n < 0 || (size_t)n >= size ? -1 : 0;
}

int stray_file_claim_output(const char *path, struct stray_error *err)
{
	char canon[PATH_MAX];
	struct stat st;
	size_t i;

	if (!armed)
		return STRAY_OK;
	if (stat(path, &st) == 0) {
		if (!(S_ISREG(st.st_mode) || S_ISDIR(st.st_mode)))
			return STRAY_OK;	/* a device or a pipe */
		for (i = 0; i < n_inputs; i++)
			if (inputs[i].dev == st.st_dev &&
			    inputs[i].ino == st.st_ino)
				return stray_error_at(err, STRAY_EINVAL, path,
					0, 0, "is also an input of this run (the "
					"same file); give the output another name");
	}
	if (stray_file_canonical(path, canon, sizeof(canon)) != 0)
		return STRAY_OK;	/* too long: open reports it */
	for (i = 0; i < n_outputs; i++)
		if (strcmp(outputs[i], canon) == 0)
			return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
					      "is named twice as an output "
					      "of this run (the same file)");
	if (grow((void **)&outputs, &cap_outputs, n_outputs,
		 sizeof(*outputs)) == 0 &&
	    (outputs[n_outputs] = strdup(canon)) != NULL)
		n_outputs++;
	return STRAY_OK;
}
