/*
 * fuzz_heads.c - libFuzzer target for the heads file of `stray
 * availability` (mission/avail_heads.c): arbitrary bytes parsed, and the
 * frames of a file that parses checked orthonormal.  Tables are named,
 * never opened.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "mission/avail_heads.h"
#include "stray/errfmt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct avail_head_spec spec[AVAIL_HEADS_MAX];
	struct stray_error err;
	char line[1024];
	size_t n, i;
	int a, b, k;

	stray_error_clear(&err);
	if (avail_heads_parse((const char *)data, size, "dir/heads.json", spec,
			      &n, &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	if (n < 1 || n > AVAIL_HEADS_MAX)
		abort();
	for (i = 0; i < n; i++)
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++) {
				double d = 0.0;

				for (k = 0; k < 3; k++)
					d += spec[i].m_bs[a][k] * spec[i].m_bs[b][k];
				if (!(fabs(d - (a == b)) < 1e-9))
					abort();
			}
	return 0;
}
