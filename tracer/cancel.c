/*
 * cancel.c - the process's trace-cancel flag (tracer/cancel.h).
 */
#include <signal.h>

#include "tracer/cancel.h"

/* sig_atomic_t and volatile: set from any thread (or a signal handler),
 * read by the workers without a lock; a late read costs one more group
 * of paths, never a wrong result, since a cancelled trace fails. */
static volatile sig_atomic_t cancel_flag;

void tracer_cancel_set(int on)
{
	cancel_flag = on != 0;
}

int tracer_cancelled(void)
{
	return cancel_flag != 0;
}
