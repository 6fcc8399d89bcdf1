/*
 * beam_screen.h - private to the tracer: which angles of the sweep light a
 * point, a block of angles at a time (beam_screen.c).
 */
#ifndef TRACER_BEAM_SCREEN_H
#define TRACER_BEAM_SCREEN_H

#include <stdbool.h>
#include <stddef.h>

#include "worker.h"

#define TRACER_SCREEN_BLOCK 64	/* angles screened at once */

/* What keep[] says of an angle. */
#define TRACER_SCREEN_NO 0.0	/* surely not lit from p */
#define TRACER_SCREEN_ASK 0.5	/* too near the rim: ask tracer_screen_covers */
#define TRACER_SCREEN_YES 1.0	/* surely lit: tracer_beam_covers says yes */

/*
 * keep[k] for angle j0 + k (k < m <= TRACER_SCREEN_BLOCK) seen from p, ok[j]
 * 1 where the angle may light anything at all (worker_ctx beam_ok or
 * direct_ok); with n, p is on a surface of that normal and an angle below
 * it is NO.  YES and NO are what tracer_beam_covers decides, ASK where
 * rounding could make them differ.
 */
void tracer_screen(const struct worker_ctx *w, const double *ok, size_t j0,
		   size_t m, struct vec3 p, const struct vec3 *n,
		   double *keep);

/* Before a pass: w->angles_sorted and the beam shifts' distinct values
 * (w->shifts, w->n_shifts), from w->o. */
void tracer_screen_setup(struct worker_ctx *w);

/*
 * [*lo, *hi): the angles outside which none can light p (one beam, the
 * angles sorted: w->angles_sorted), a necessary condition with a margin;
 * else all of them.  Only the angles inside need the screen.
 */
void tracer_screen_range(const struct worker_ctx *w, struct vec3 p,
			 size_t *lo, size_t *hi);

/* tracer_beam_covers with angle j's beam (its own centre with
 * opts.beam_shift_z). */
bool tracer_screen_covers(const struct worker_ctx *w, size_t j,
			  struct vec3 d, struct vec3 p);

#endif /* TRACER_BEAM_SCREEN_H */
