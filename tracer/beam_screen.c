/*
 * beam_screen.c - which angles of the sweep light a point: the test of
 * tracer_beam_covers (the line from p along the source direction d meets
 * the aperture plane inside the beam's disk) for a block of angles at a
 * time, by a loop the compiler vectorises.
 *
 * With v = c - p (c the disk's centre, N its normal), a = d.v, dn = d.N and
 * t = v.N / dn the distance along d to the plane, the meeting point is
 * q = d t - v and |q|^2 = t^2 - 2 t a + |v|^2: one division and a few
 * products an angle, against a call of tracer_beam_covers for every
 * angle the old screen (the line's distance from c, a necessary
 * condition) let through.  Where the sum is within a margin far above
 * its rounding of the radius (or t of 0), the angle is left to
 * tracer_beam_covers itself: every decision is the exact test's, so the
 * rays and their bits are those of testing every angle exactly.
 */
#include <math.h>

#include "beam_screen.h"
#include "tracer/source.h"

#define MARGIN 1e-9	/* relative; the sums' rounding is ~1e-15 */
#define DN_MIN 1e-6	/* grazing the aperture plane: t too large */

/*
 * The class of one angle, okk 0 or 1.  Multiplied through by dn^2 (dn > 0:
 * no division): |q|^2 dn^2 = an^2 - 2 an a dn + |v|^2 dn^2 against
 * R^2 dn^2, an = v.N giving t's sign.  YES and NO exclude each other, so
 * ASK + yes - no is one of the three; every test is a select (the file is
 * built without trapping math), so the loops that call it vectorise.
 */
static inline double classify(double okk, double an, double dn, double a,
			      double l2, double r2, double an_margin)
{
	double dn2 = dn * dn;
	double q2 = an * an - 2.0 * an * a * dn + l2 * dn2, r2n = r2 * dn2;
	double m = MARGIN * (an * an + 2.0 * fabs(an * a * dn) +
			     (l2 + r2 + 1.0) * dn2);
	double yes = (dn > DN_MIN) & (an > an_margin) & (q2 < r2n - m) ?
		     0.5 : 0.0;
	double no = (dn > DN_MIN) & ((an < -an_margin) | (q2 > r2n + m)) ?
		    0.5 : 0.0;

	return okk > 0.0 ? TRACER_SCREEN_ASK + yes - no : TRACER_SCREEN_NO;
}

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
/* 4 doubles a lane where the CPU has AVX2 (chosen at load time) */
__attribute__((target_clones("avx2", "default")))
#endif
static void screen_one_beam(const struct worker_ctx *w, const double *ok,
			    size_t j0, size_t m, struct vec3 p,
			    const struct vec3 *n, double *restrict keep)
{
	const struct tracer_beam *b = &w->s->beam;
	const double *restrict dx = w->dir_x + j0, *restrict dy = w->dir_y + j0,
		     *restrict dz = w->dir_z + j0, *restrict okj = ok + j0;
	struct vec3 v = v3_sub(b->center, p), N = b->normal;
	double l2 = v3_dot(v, v), an = v3_dot(v, N);
	double r2 = b->radius_mm * b->radius_mm;
	double an_margin = MARGIN * (sqrt(l2) + 1.0);
	double nx = n ? n->x : 0.0, ny = n ? n->y : 0.0, nz = n ? n->z : 0.0;
	double nmin = n ? -1e-9 : -1.0, *kp = keep;
	size_t k;

	for (k = 0; k < m; k++) {
		double a = dx[k] * v.x + dy[k] * v.y + dz[k] * v.z;
		double dn = dx[k] * N.x + dy[k] * N.y + dz[k] * N.z;
		double cn = dx[k] * nx + dy[k] * ny + dz[k] * nz;
		double c = classify(okj[k], an, dn, a, l2, r2, an_margin);

		/* branch-free, so the loop vectorises */
		kp[k] = (cn > nmin ? 1.0 : 0.0) * c;
	}
}

/* The same with a beam centre per angle (opts.beam_shift_z). */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
static void screen_shifted(const struct worker_ctx *w, const double *ok,
			   size_t j0, size_t m, struct vec3 p,
			   const struct vec3 *n, double *restrict keep)
{
	const struct tracer_beam *b = &w->s->beam;
	const double *restrict dx = w->dir_x + j0, *restrict dy = w->dir_y + j0,
		     *restrict dz = w->dir_z + j0, *restrict okj = ok + j0,
		     *restrict cx = w->beam_cx + j0, *restrict cy = w->beam_cy + j0,
		     *restrict cz = w->beam_cz + j0;
	struct vec3 N = b->normal;
	double r2 = b->radius_mm * b->radius_mm;
	double nx = n ? n->x : 0.0, ny = n ? n->y : 0.0, nz = n ? n->z : 0.0;
	double nmin = n ? -1e-9 : -1.0, *kp = keep;
	size_t k;

	for (k = 0; k < m; k++) {
		/* v: p to the angle's beam centre */
		double vx = cx[k] - p.x, vy = cy[k] - p.y, vz = cz[k] - p.z;
		double l2 = vx * vx + vy * vy + vz * vz;
		double an = vx * N.x + vy * N.y + vz * N.z;
		double a = dx[k] * vx + dy[k] * vy + dz[k] * vz;
		double dn = dx[k] * N.x + dy[k] * N.y + dz[k] * N.z;
		double cn = dx[k] * nx + dy[k] * ny + dz[k] * nz;
		/* |v| <= sqrt(l2) < l2 + 1: no root a lane */
		double c = classify(okj[k], an, dn, a, l2, r2,
				    MARGIN * (l2 + 1.0));

		kp[k] = (cn > nmin ? 1.0 : 0.0) * c;
	}
}

void tracer_screen(const struct worker_ctx *w, const double *ok, size_t j0,
		   size_t m, struct vec3 p, const struct vec3 *n,
		   double *keep)
{
	if (w->o->beam_shift_z)
		screen_shifted(w, ok, j0, m, p, n, keep);
	else
		screen_one_beam(w, ok, j0, m, p, n, keep);
}

bool tracer_screen_covers(const struct worker_ctx *w, size_t j,
			  struct vec3 d, struct vec3 p)
{
	struct tracer_beam b;

	if (!w->o->beam_shift_z)
		return tracer_beam_covers(&w->s->beam, d, p);
	b = w->s->beam;
	b.center = v3(w->beam_cx[j], w->beam_cy[j], w->beam_cz[j]);
	return tracer_beam_covers(&b, d, p);
}
