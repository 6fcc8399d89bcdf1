/*
 * cancel.h - stop a running trace from another thread (issue 32: Ctrl-C
 * in Python).  One flag for the process: the tracer's workers poll it
 * between small groups of paths and the trace then fails ("interrupted")
 * within a fraction of a second.  `stray` never sets it (a signal ends
 * the process); a library caller sets it, and clears it before the next
 * call.
 */
#ifndef TRACER_CANCEL_H
#define TRACER_CANCEL_H

/* Ask every running and later trace to stop (1), or allow them (0). */
void tracer_cancel_set(int on);

/* Nonzero once tracer_cancel_set(1) was called and not cleared. */
int tracer_cancelled(void);

#endif /* TRACER_CANCEL_H */
