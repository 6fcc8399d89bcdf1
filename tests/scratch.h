/*
 * scratch.h - a test's scratch folder, removed with all in it by the
 * group teardown (the tests that write files make one with mkdtemp).
 */
#ifndef STRAY_TEST_SCRATCH_H
#define STRAY_TEST_SCRATCH_H

#include <stdio.h>
#include <stdlib.h>

/* rm -rf dir: 0, or -1 (a failed teardown, so cmocka reports it). */
static inline int scratch_remove(const char *dir)
{
	char cmd[4200];

	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd) == 0 ? 0 : -1;
}

#endif /* STRAY_TEST_SCRATCH_H */
