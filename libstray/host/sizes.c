/*
 * sizes.c - counts declared by a file checked before memory is taken
 * (stray/sizes.h).
 */
#include "stray/errfmt.h"
#include "stray/sizes.h"

static int overflow(const char *file, const char *field,
		    struct stray_error *err)
{
	return stray_error_at(err, STRAY_EINVAL, file, 0, field,
			      "size overflows: the file's counts cannot be "
			      "right");
}

int stray_size_check(size_t count, size_t elem_bytes, size_t limit,
		     size_t have, const char *file, const char *field,
		     size_t *bytes, struct stray_error *err)
{
	size_t n;

	if (stray_size_mul(count, elem_bytes, &n))
		return overflow(file, field, err);
	if (n > limit)
		return stray_error_at(err, STRAY_EINVAL, file, 0, field,
				      "larger than its limit "
				      "(docs/limits.md)");
	if (n > have)
		return stray_error_at(err, STRAY_EINVAL, file, 0, field,
				      "claims more data than the file holds "
				      "(truncated or a corrupt header)");
	if (bytes)
		*bytes = n;
	return STRAY_OK;
}

int stray_size_check2(size_t n1, size_t n2, size_t elem_bytes, size_t limit,
		      size_t have, const char *file, const char *field,
		      size_t *bytes, struct stray_error *err)
{
	size_t count;

	if (stray_size_mul(n1, n2, &count))
		return overflow(file, field, err);
	return stray_size_check(count, elem_bytes, limit, have, file, field,
				bytes, err);
}
