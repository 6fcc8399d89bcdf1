/*
 * sizes.h - one rule for counts read from a file (hosted).
 *
 * Every count a file declares (NAXISn, triangles, pixels, rows, records)
 * is multiplied out in overflow-checked arithmetic and held against the
 * bytes the file really has and the documented limit (docs/limits.md)
 * before any memory is taken: a 6 KB FITS header claiming 2^32 x 2^30
 * pixels is refused in microseconds, never allocated or wrapped to 0.
 */
#ifndef STRAY_SIZES_H
#define STRAY_SIZES_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

/* *out = a * b; 0 on success, -1 when the product overflows size_t. */
static inline int stray_size_mul(size_t a, size_t b, size_t *out)
{
	return __builtin_mul_overflow(a, b, out) ? -1 : 0;
}

/*
 * The payload of count elements of elem_bytes each: refused (STRAY_EINVAL,
 * naming file and field) when the product overflows, exceeds limit, or
 * needs more than have bytes (the data the file really holds; pass
 * SIZE_MAX where the data is not in the file, e.g. a buffer to fill).
 * *bytes (may be NULL) gets the product.
 */
int stray_size_check(size_t count, size_t elem_bytes, size_t limit,
		     size_t have, const char *file, const char *field,
		     size_t *bytes, struct stray_error *err);

/* count = n1 * n2 (e.g. NAXIS1 * NAXIS2), overflow-checked, then as above. */
int stray_size_check2(size_t n1, size_t n2, size_t elem_bytes, size_t limit,
		      size_t have, const char *file, const char *field,
		      size_t *bytes, struct stray_error *err);

#endif /* STRAY_SIZES_H */
