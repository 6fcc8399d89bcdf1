/*
 * frame_file.c - a frame file read whole into a reused buffer (sweep_store.h):
 * the bytes the reduction hashes are the bytes cfitsio then decodes from
 * memory, so each frame is read from the disk once.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/sweep_store.h"

/* cfitsio's memory driver reads whole 2880-byte FITS blocks. */
static size_t padded(size_t len)
{
	size_t p = (len + 2879) / 2880 * 2880;

	return p ? p : 2880;
}

static int grow(struct stray_sweep_buf *b, size_t need)
{
	unsigned char *p;

	if (need <= b->cap)
		return STRAY_OK;
	p = realloc(b->data, need);
	if (!p)
		return STRAY_ENOMEM;
	b->data = p;
	b->cap = need;
	return STRAY_OK;
}

int stray_sweep_file_load(const char *path, struct stray_sweep_buf *b,
			  struct stray_error *err)
{
	struct stat st;
	size_t len = 0;
	/* No symlink followed, no wait on a FIFO: the manifest's check
	 * (stray_sweep_manifest_check_files) again at the open itself. */
	int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK), ok;

	if (fd < 0 && errno == ENOENT)	/* the manifest lists it: exit 2 */
		return stray_error_at(err, STRAY_ENOTFOUND, path, 0, "file",
			"listed in manifest.csv but missing from the folder");
	if (fd < 0 && errno == ELOOP)
		return stray_error_at(err, STRAY_EINVAL, path, 0, "file",
			"is a symbolic link: frames must be plain files in "
			"the sweep folder");
	if (fd < 0)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      "cannot open the frame file");
	if (fstat(fd, &st) == 0 && !S_ISREG(st.st_mode)) {
		close(fd);
		return stray_error_at(err, STRAY_EINVAL, path, 0, "file",
			"is not a regular file (a FIFO, device or folder)");
	}
	ok = fstat(fd, &st) == 0 && st.st_size >= 0;
	if (ok && grow(b, padded((size_t)st.st_size + 1)) != STRAY_OK) {
		close(fd);
		return stray_error_at(err, STRAY_ENOMEM, path, 0, "file",
				      "no memory for the frame");
	}
	while (ok) {		/* to the end, whatever fstat said */
		ssize_t n;

		if (len == b->cap && grow(b, padded(2 * b->cap)) != STRAY_OK)
			ok = 0;
		n = ok ? read(fd, b->data + len, b->cap - len) : -1;
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0) {
			ok = n == 0;
			break;
		}
		len += (size_t)n;
	}
	close(fd);
	if (!ok)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      "cannot read the frame file");
	b->len = len;
	if (grow(b, padded(len)) != STRAY_OK)
		return stray_error_at(err, STRAY_ENOMEM, path, 0, "file",
				      "no memory for the frame");
	memset(b->data + len, 0, padded(len) - len);
	return STRAY_OK;
}

void stray_sweep_buf_free(struct stray_sweep_buf *b)
{
	free(b->data);
	memset(b, 0, sizeof(*b));
}
