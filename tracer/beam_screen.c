/*
 * beam_screen.c - which angles of the sweep light a point: the test of
 * tracer_beam_covers (the line from p along the source direction d meets
 * the aperture plane inside the beam's disk) for a block of angles at a
 * time, by a loop the compiler vectorises.
 *
 * With v = c - p (c the disk's centre, N its normal), a = d.v, dn = d.N and
 * t = v.N / dn the distance along d to the plane, the meeting point is
 * q = d t - v and |q|^2 = t^2 - 2 t a + |v|^2: a few products an angle
 * (multiplied through by dn^2, no division), against a call of
 * tracer_beam_covers for every angle the old screen (the line's distance
 * from c, a necessary condition) let through.  Where the sum is within a
 * margin far above its rounding of the radius (or t of 0), the angle is
 * left to tracer_beam_covers itself: every decision is the exact test's,
 * so the rays and their bits are those of testing every angle exactly.
 * And only one arc of the angles is screened at all (tracer_screen_range,
 * below).
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
	double nmin = n ? -1e-9 : -1.0;
	size_t k;

	for (k = 0; k < m; k++) {
		double a = dx[k] * v.x + dy[k] * v.y + dz[k] * v.z;
		double dn = dx[k] * N.x + dy[k] * N.y + dz[k] * N.z;
		double cn = dx[k] * nx + dy[k] * ny + dz[k] * nz;
		double c = classify(okj[k], an, dn, a, l2, r2, an_margin);

		/* branch-free, so the loop vectorises */
		keep[k] = (cn > nmin ? 1.0 : 0.0) * c;
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
	double nmin = n ? -1e-9 : -1.0;
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

		keep[k] = (cn > nmin ? 1.0 : 0.0) * c;
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

/*
 * The arc of source angles that can light p.  d(theta) = (0, sin, cos), so
 * d.v = rho cos(theta - psi), rho and psi the polar form of (v.z, v.y).  The
 * line from p along d passes c no further than the meeting point q, so
 * |v|^2 - (d.v)^2 <= |q|^2 <= R^2; and d.v = t - d.q >= -R (t >= 0).  With
 * |v|^2 > 2 R^2 the two give d.v >= sqrt(|v|^2 - R^2) > R: one arc,
 * |theta - psi| <= acos(kappa), kappa = sqrt(|v|^2 - R^2) / rho.  Widened
 * by RANGE_MARGIN (kappa's rounding moves acos by at most sqrt(2e-12)
 * near kappa = 1); an arc that would wrap past +-180 deg: all angles.
 */
#define RANGE_MARGIN 1e-5	/* rad */

static size_t first_at_least(const double *th, size_t n, double x)
{
	size_t lo = 0, hi = n;

	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;

		if (th[mid] < x)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

void tracer_screen_setup(struct worker_ctx *w)
{
	const struct tracer_trace_opts *o = w->o;
	size_t j;

	w->angles_sorted = 1;
	w->n_shifts = 0;
	for (j = 0; j < o->n_theta; j++) {
		double z = o->beam_shift_z ? o->beam_shift_z[j] : 0.0;
		int k;

		if (!(fabs(o->theta_deg[j]) <= 180.0) ||
		    (j > 0 && o->theta_deg[j] < o->theta_deg[j - 1]))
			w->angles_sorted = 0;
		for (k = 0; k < w->n_shifts && w->shifts[k] != z; k++)
			;
		if (w->n_shifts < 0 || k < w->n_shifts)
			continue;	/* too many already, or seen */
		if (k == TRACER_RANGE_SHIFTS) {
			w->n_shifts = -1;	/* the range: all angles */
			continue;
		}
		w->shifts[k] = z;
		w->n_shifts = k + 1;
	}
}

/* The arc for the beam centred at c, [*a, *z] deg; 0: none, 1: an arc,
 * -1: all angles may. */
static int arc(const struct tracer_beam *b, struct vec3 c, struct vec3 p,
	       double *a, double *z)
{
	struct vec3 v = v3_sub(c, p);
	double l2 = v3_dot(v, v), r2 = b->radius_mm * b->radius_mm;
	double rho = sqrt(v.y * v.y + v.z * v.z), kappa, half, psi;

	if (!(l2 > 2.1 * r2))
		return -1;
	kappa = rho > 0.0 ? sqrt(l2 - r2) / rho : INFINITY;
	if (kappa > 1.0 + 1e-12)	/* no direction reaches the disk */
		return 0;
	half = acos(fmin(kappa, 1.0)) + RANGE_MARGIN;
	psi = atan2(v.y, v.z);
	*a = (psi - half) * (180.0 / M_PI);
	*z = (psi + half) * (180.0 / M_PI);
	return *a < -180.0 || *z > 180.0 ? -1 : 1;
}

void tracer_screen_range(const struct worker_ctx *w, struct vec3 p,
			 size_t *lo, size_t *hi)
{
	const struct tracer_beam *b = &w->s->beam;
	const double *th = w->o->theta_deg;
	size_t n = w->o->n_theta;
	double a = INFINITY, z = -INFINITY;
	int k, m = w->o->beam_shift_z ? w->n_shifts : 1;

	*lo = 0;
	*hi = n;
	if (!w->angles_sorted || m < 0)
		return;
	for (k = 0; k < m; k++) {	/* the union of every centre's arc */
		/* the centre as trace.c's beam_center puts it */
		struct vec3 c = !w->o->beam_shift_z || w->shifts[k] == 0.0 ?
			b->center : v3_sub(b->center,
					   v3_scale(b->normal, w->shifts[k]));
		double ak, zk;
		int r = arc(b, c, p, &ak, &zk);

		if (r < 0)
			return;
		if (r > 0) {
			a = fmin(a, ak);
			z = fmax(z, zk);
		}
	}
	if (a > z) {		/* no centre's arc: no angle */
		*hi = 0;
		return;
	}
	*lo = first_at_least(th, n, a);
	*hi = first_at_least(th, n, z);
	while (*hi < n && th[*hi] <= z)	/* equal to z: inside */
		++*hi;
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
