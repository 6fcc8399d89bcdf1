/*
 * file.c - whole-file reads and atomic writes (hosted).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/file.h"

int stray_file_read(const char *path, char **buf, size_t *len,
		    struct stray_error *err)
{
	FILE *f = fopen(path, "rb");
	size_t cap = 65536, n = 0;
	char *b;

	*buf = NULL;
	*len = 0;
	if (!f)		/* a missing input is the caller's mistake: bad input */
		return stray_error_at(err, errno == ENOENT ? STRAY_ENOTFOUND
							   : STRAY_EIO,
				      path, 0, 0, strerror(errno));
	b = malloc(cap);
	while (b) {
		n += fread(b + n, 1, cap - n - 1, f);
		if (n < cap - 1)
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
	if (ferror(f)) {
		free(b);
		fclose(f);
		return stray_error_at(err, STRAY_EIO, path, 0, 0, "read error");
	}
	fclose(f);
	b[n] = '\0';
	*buf = b;
	*len = n;
	return STRAY_OK;
}

int stray_file_open_atomic(struct stray_file_out *out, const char *path,
			   struct stray_error *err)
{
	int n = snprintf(out->tmp, sizeof(out->tmp), "%s.tmp.%ld", path,
			 (long)getpid());

	out->path = path;
	out->f = NULL;
	if (n < 0 || (size_t)n >= sizeof(out->tmp))
		return stray_error_at(err, STRAY_EINVAL, path, 0, "path",
				      "too long");
	out->f = fopen(out->tmp, "wb");
	if (!out->f)
		return stray_error_at(err, STRAY_EIO, path, 0, 0, strerror(errno));
	return STRAY_OK;
}

int stray_file_commit(struct stray_file_out *out, struct stray_error *err)
{
	int bad = ferror(out->f) || fflush(out->f) != 0 ||
		  fsync(fileno(out->f)) != 0;
	int saved = errno;

	if (fclose(out->f) != 0 && !bad) {
		bad = 1;
		saved = errno;
	}
	out->f = NULL;
	if (!bad && rename(out->tmp, out->path) == 0)
		return STRAY_OK;
	if (!bad)
		saved = errno;
	remove(out->tmp);
	return stray_error_at(err, STRAY_EIO, out->path, 0, 0,
			      saved ? strerror(saved) : "write error");
}

void stray_file_abort(struct stray_file_out *out)
{
	if (out->f)
		fclose(out->f);
	out->f = NULL;
	remove(out->tmp);
}
