/*
 * trace_beams.h - the pivot-offset nodes of one geometry traced in one
 * pass (trace_beams.c), for the trace cache (private to diagnose/).
 */
#ifndef DIAGNOSE_TRACE_BEAMS_H
#define DIAGNOSE_TRACE_BEAMS_H

#include "trace_scene.h"

/* The pivot-offset nodes of one geometry traced in one pass
 * (trace_beams.c): ts[0..K) set up by the cache, the same geometry but
 * for their DIAG_GEO_PIVOT. */
#define DIAG_PIVOT_NODES_MAX 16
int diag_trace_beams(struct diag_eval *e, struct diag_trace **ts, size_t K,
		     struct stray_error *err);

#endif /* DIAGNOSE_TRACE_BEAMS_H */
