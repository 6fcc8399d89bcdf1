/*
 * bench_trace.c - the tracer's speed on ref4, as ratios against baselines
 * measured in the same run: raw incoherent Embree casts/s in the same
 * scene (the hardware limit), and the full default curve (127 angles) to
 * sigma/alpha <= 1 % at every angle: wall time, paths/s, casts/s and the
 * fraction of the raw rate.  With --peer, also the agreement with the
 * Mitsuba 3 reference curve (../shared/peers/ref4_mitsuba.csv) in
 * combined standard errors; Mitsuba's own timing is run by peer-check
 * when it is installed (see ../shared/peers/README.md).  Every ratio
 * comes from alternating runs (baseline, figure, baseline, ...; ours,
 * Mitsuba, ours, ...: bench_alt.h), printed as the median and min-max of
 * the pairs: on a shared machine one-shot ratios move by 1.5x.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cJSON.h>
#include <sys/stat.h>

#include "bench_alt.h"
#include "stray/curve_io.h"
#include "tracer/angles.h"
#include "tracer/obj_export.h"
#include "tracer/integrator.h"
#include "tracer/rng.h"
#include "tracer/scene_load.h"

#define PEER_CSV "../shared/peers/ref4_mitsuba.csv"
#define PEER_SCRIPT "../shared/peers/mitsuba_ref4.py"
#define RACE_DIR "build/bench/ref4_mesh"

static double cpu_s(void)
{
	return (double)clock() / CLOCKS_PER_SEC;
}

#define now_s bench_now

/* A random ray inside the baffle: uniform over its cross-section and
 * length, isotropic direction (the raw rates' incoherent rays). */
static void random_ray(struct tracer_rng *r, struct vec3 *o, struct vec3 *d)
{
	double rr = 19.0 * sqrt(tracer_rng_uniform(r));
	double ph = 2.0 * M_PI * tracer_rng_uniform(r);
	double z = -39.0 * tracer_rng_uniform(r);
	double cz = 2.0 * tracer_rng_uniform(r) - 1.0;
	double p2 = 2.0 * M_PI * tracer_rng_uniform(r);
	double sz = sqrt(1.0 - cz * cz);

	*o = v3(rr * cos(ph), rr * sin(ph), z);
	*d = v3(sz * cos(p2), sz * sin(p2), cz);
}

/* Raw incoherent casts: random origins in the baffle, random directions. */
static double raw_casts_per_s(const struct tracer_scene *s, long n)
{
	struct tracer_rng r;
	struct tracer_hit h;
	double t0 = now_s();
	long i, hits = 0;

	tracer_rng_init(&r, 3, 0);
	for (i = 0; i < n; i++) {
		struct vec3 o, d;

		random_ray(&r, &o, &d);
		hits += tracer_scene_intersect(s, o, d, &h);
	}
	if (hits < 0)
		puts("");
	return n / (now_s() - t0);
}

/* Raw incoherent occlusion rays (rtcOccluded1), same origins/directions. */
static double raw_occluded_per_s(const struct tracer_scene *s, long n)
{
	struct tracer_rng r;
	double t0 = now_s();
	long i, hits = 0;

	tracer_rng_init(&r, 3, 0);
	for (i = 0; i < n; i++) {
		struct vec3 o, d;

		random_ray(&r, &o, &d);
		hits += tracer_scene_occluded(s, o, d, INFINITY);
	}
	if (hits < 0)
		puts("");
	return n / (now_s() - t0);
}

/*
 * The tracer's shadow rays: scatter vertices of real paths (first hits of
 * random rays from the detector side), each connected to every angle of
 * the default sweep after the integrator's culling (source above the
 * surface, aperture covers the vertex), as fans (packets) and, the same
 * rays, one by one.  Shadow rays/s on one thread; *same = one by one.
 */
#define FAN_VERTS 20000
static double fan_per_s(const struct tracer_scene *s, double *same,
			long *n_rays)
{
	struct vec3 *dir, *fan, *org;
	unsigned char *occ;
	struct tracer_rng r;
	double *th, t0, t_fan, t_one;
	size_t n, nv = 0, k, j, *cnt;
	long rays = 0, agree = 0;

	*same = 0.0;
	*n_rays = 0;
	if (tracer_angles_parse(TRACER_ANGLES_DEFAULT, &th, &n, NULL))
		return 0.0;
	dir = malloc(n * sizeof(*dir));
	fan = malloc((size_t)FAN_VERTS * n * sizeof(*fan));
	org = malloc(FAN_VERTS * sizeof(*org));
	occ = malloc(n);
	cnt = calloc(FAN_VERTS, sizeof(*cnt));
	for (j = 0; j < n; j++) {
		dir[j] = tracer_source_dir(th[j]);
	}
	tracer_rng_init(&r, 5, 0);
	while (nv < FAN_VERTS) {
		struct tracer_hit h;
		double u = tracer_rng_uniform(&r), v = tracer_rng_uniform(&r);
		double ct = sqrt(1.0 - u), st = sqrt(u), ph = 2.0 * M_PI * v;
		struct vec3 x = tracer_detector_sample_point(&s->det,
			tracer_rng_uniform(&r), tracer_rng_uniform(&r));
		struct vec3 d = v3(st * cos(ph), st * sin(ph), ct);

		if (!tracer_scene_intersect(s, tracer_offset_origin(x,
				s->det.normal), d, &h))
			continue;
		org[nv] = tracer_offset_origin(h.p, h.ng);
		for (j = 0; j < n; j++)
			if (v3_dot(dir[j], h.ng) > 0.0 &&
			    tracer_beam_covers(&s->beam, dir[j], h.p))
				fan[nv * n + cnt[nv]++] = dir[j];
		rays += (long)cnt[nv];
		nv++;
	}
	t0 = now_s();
	for (k = 0; k < nv; k++) {
		tracer_scene_occluded_fan(s, org[k], fan + k * n, cnt[k], occ);
		for (j = 0; j < cnt[k]; j++)
			agree += occ[j];
	}
	t_fan = now_s() - t0;
	t0 = now_s();
	for (k = 0; k < nv; k++)
		for (j = 0; j < cnt[k]; j++)
			agree -= tracer_scene_occluded(s, org[k],
						       fan[k * n + j], INFINITY);
	t_one = now_s() - t0;
	if (agree != 0)
		printf("  fan and single rays DISAGREE (%ld)\n", agree);
	free(dir), free(fan), free(org), free(occ), free(cnt), free(th);
	*same = rays / t_one;
	*n_rays = rays;
	return rays / t_fan;
}

static double worst_rel_sigma(const struct tracer_result *r, double *at)
{
	double worst = 0.0, a, sg;
	size_t j;

	for (j = 1; j < r->n_theta; j++) {
		tracer_result_alpha(r, j, 0, -1, &a, &sg);
		if (a > 0.0 && sg / a > worst) {
			worst = sg / a;
			*at = r->theta_deg[j];
		}
	}
	return worst;
}

static int trace(const struct tracer_scene *s, const double *th, size_t n,
		 uint64_t paths, int threads, struct tracer_result *r)
{
	struct tracer_trace_opts o;
	struct stray_error err;

	stray_error_clear(&err);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = n;
	o.n_paths = paths;
	o.threads = threads;
	/* the light-side samples where the pilot finds they pay (MIS,
	 * tracer/light.h); BENCH_LIGHT=0: the detector-side paths alone */
	o.light_paths = !getenv("BENCH_LIGHT") || atoi(getenv("BENCH_LIGHT"));
	return tracer_trace(s, &o, r, &err);
}

/* The default curve to 1 %: a pilot run sizes the final one, then the
 * raw cast rate and the curve alternate, pairs times. */
static int bench_curve(const struct tracer_scene *s, int threads,
		       uint64_t *need_out)
{
	struct tracer_result r;
	double *th, worst = 0.0, at = 0.0, cpu0, lo, hi;
	double raw[BENCH_MAX_PAIRS], rate[BENCH_MAX_PAIRS];
	double wall[BENCH_MAX_PAIRS], cpu[BENCH_MAX_PAIRS];
	double paths[BENCH_MAX_PAIRS];
	size_t n;
	uint64_t need;
	int i, pairs = bench_pairs();

	if (tracer_angles_parse(TRACER_ANGLES_DEFAULT, &th, &n, NULL))
		return 1;
	if (trace(s, th, n, 500000, threads, &r))
		return 1;
	worst = worst_rel_sigma(&r, &at);
	/* sigma falls as 1/sqrt(N); aim a little under 1 % */
	need = (uint64_t)(500000 * pow(worst / 0.0098, 2.0));
	*need_out = need;
	tracer_result_free(&r);
	for (i = 0; i < pairs; i++) {
		raw[i] = raw_casts_per_s(s, 1000000) * threads;
		cpu0 = cpu_s();
		if (trace(s, th, n, need, threads, &r))
			return 1;
		cpu[i] = cpu_s() - cpu0;
		wall[i] = r.seconds;
		rate[i] = r.casts / r.seconds;
		paths[i] = need / r.seconds;
		worst = worst_rel_sigma(&r, &at);
		tracer_result_free(&r);
	}
	printf("ref4 default curve (%zu angles), %d threads, %llu paths, "
	       "light-side MIS %s,\n  worst sigma/alpha %.2f %% (at %.1f deg);"
	       " median (min-max) of %d alternating\n  pairs (raw casts, "
	       "curve):\n", n, threads, (unsigned long long)need,
	       !getenv("BENCH_LIGHT") || atoi(getenv("BENCH_LIGHT")) ? "on" :
	       "off", 100 * worst, at, pairs);
	/* one median per statement: lo and hi are shared */
	printf("  wall %.2f s", bench_median(wall, pairs, &lo, &hi));
	printf(" (%.2f-%.2f)", lo, hi);
	printf(", cpu %.2f s", bench_median(cpu, pairs, &lo, &hi));
	printf(", %.3g paths/s\n", bench_median(paths, pairs, &lo, &hi));
	bench_ratio("  casts/s against the raw incoherent rate x threads:",
		    rate, raw, pairs, 6, 3);
	printf("  Mitsuba 3 (peers/README.md, reciprocal, same machine class):"
	       " 0.5-1.6 s per angle for 1 %%,\n  i.e. %.0f-%.0f s for this "
	       "curve: ratio %.1f-%.1f x (median wall)\n", 0.5 * n, 1.6 * n,
	       0.5 * n / bench_median(wall, pairs, &lo, &hi),
	       1.6 * n / bench_median(wall, pairs, &lo, &hi));
	free(th);
	return 0;
}

/* Agreement with the peer curve, in combined standard errors. */
static int peer_check(const struct tracer_scene *s, int threads,
		      uint64_t paths)
{
	struct stray_curve c;
	struct tracer_result r;
	struct stray_error err;
	double worst = 0.0, worst_at = 0.0;
	size_t j;

	stray_error_clear(&err);
	if (stray_curve_load(PEER_CSV, &c, &err)) {
		printf("peer curve %s not readable: agreement not checked\n",
		       PEER_CSV);
		return 0;
	}
	if (trace(s, c.theta_deg, c.n, paths, threads, &r))
		return 1;
	printf("agreement with Mitsuba 3 (%s), %llu paths:\n", PEER_CSV,
	       (unsigned long long)paths);
	for (j = 0; j < c.n; j++) {
		double a, sg, z;

		tracer_result_alpha(&r, j, 0, -1, &a, &sg);
		z = (a - c.alpha[j]) / hypot(sg, c.sigma ? c.sigma[j] : 0.0);
		if (j == 0)
			z = 0.0;
		printf("  %5.1f deg  alpha %.4e +- %.1e  peer %.4e +- %.1e"
		       "  %+5.2f sigma\n", c.theta_deg[j], a, sg, c.alpha[j],
		       c.sigma ? c.sigma[j] : 0.0, z);
		if (fabs(z) > worst) {
			worst = fabs(z);
			worst_at = c.theta_deg[j];
		}
	}
	printf("  worst %.2f combined sigma at %.1f deg (target <= 3): %s\n",
	       worst, worst_at, worst <= 3.0 ? "agrees" : "DISAGREES");
	tracer_result_free(&r);
	stray_curve_free(&c);
	return worst <= 3.0 ? 0 : 2;
}

/*
 * The ref4 mesh as the peer script wants it: three OBJ files, interior
 * (Lambertian groups), exterior (mirror) and detector, from our export.
 */
static int export_for_peer(const struct tracer_scene *s)
{
	static const char *const cls[3] = { "interior", "exterior", "detector" };
	int k;

	mkdir(RACE_DIR, 0755);
	for (k = 0; k < 3; k++) {
		struct tracer_mesh m;
		char path[256];
		size_t i;
		int g, rc = 0;

		tracer_mesh_init(&m);
		g = tracer_mesh_group(&m, cls[k], NULL);
		for (i = 0; i < s->mesh.n_vert && !rc; i++) {
			uint32_t idx;
			const float *v = s->mesh.vert + 3 * i;

			rc = tracer_mesh_add_vertex(&m, v[0], v[1], v[2], &idx,
						    NULL);
		}
		for (i = 0; i < s->mesh.n_tri && !rc; i++) {
			const struct tracer_brdf *b =
				&s->material[s->mesh.group[i]];
			int c = !b->ops ? 2 : b->ops ==
				&tracer_brdf_mirror_ops ? 1 : 0;

			if (c == k)
				rc = tracer_mesh_add_triangle(&m,
					s->mesh.tri[3 * i], s->mesh.tri[3 * i + 1],
					s->mesh.tri[3 * i + 2], g, NULL);
		}
		snprintf(path, sizeof(path), RACE_DIR "/ref4_%s.obj", cls[k]);
		if (!rc)
			rc = tracer_obj_export(&m, path, NULL);
		tracer_mesh_free(&m);
		if (rc)
			return rc;
	}
	return 0;
}

/* Mitsuba's warm sampling time to rel_err at one angle (-1: failed). */
static double mitsuba_time(double theta, double rel_err)
{
	char cmd[512], line[8192];
	double t = -1.0;
	FILE *p;

	snprintf(cmd, sizeof(cmd), "python3 " PEER_SCRIPT " target --mode "
		 "reciprocal --thetas %g --rel-err %g --mesh-dir " RACE_DIR
		 " 2>/dev/null", theta, rel_err);
	p = popen(cmd, "r");
	if (!p)
		return -1.0;
	while (fgets(line, sizeof(line), p)) {
		cJSON *j = cJSON_Parse(line);
		const cJSON *w = cJSON_GetObjectItem(j, "wall_s_warm");

		if (!w)
			w = cJSON_GetObjectItem(j, "wall_s_required");
		if (cJSON_IsNumber(w))
			t = w->valuedouble;
		cJSON_Delete(j);
	}
	pclose(p);
	return t;
}

/* Time to 1 % at 30/45/60/80 deg: Mitsuba per angle vs ours at once,
 * and Mitsuba's time scaled to 127 angles vs our 127-angle curve to
 * 1 % (need paths), alternating (theirs, ours, theirs, ...). */
static int race_mitsuba(const struct tracer_scene *s, int threads,
			uint64_t need127)
{
	double th[] = { 0, 30, 45, 60, 80 }, worst, at = 0.0, lo, hi, *t127;
	double mi[BENCH_MAX_PAIRS], ours[BENCH_MAX_PAIRS];
	double mi127[BENCH_MAX_PAIRS], curve[BENCH_MAX_PAIRS];
	size_t n127;
	struct tracer_result r;
	uint64_t need;
	int i, k, pairs = bench_pairs();

	if (system("python3 -c 'import mitsuba' >/dev/null 2>&1") != 0 ||
	    export_for_peer(s)) {
		printf("Mitsuba 3 not installed (pip install mitsuba; apt-get "
		       "install libllvm19): race skipped\n");
		return 0;
	}
	if (tracer_angles_parse(TRACER_ANGLES_DEFAULT, &t127, &n127, NULL))
		return 1;
	if (trace(s, th, 5, 200000, threads, &r))
		return 1;
	worst = worst_rel_sigma(&r, &at);
	need = (uint64_t)(200000 * pow(worst / 0.0098, 2.0));
	tracer_result_free(&r);
	for (i = 0; i < pairs; i++) {
		mi[i] = 0.0;
		for (k = 1; k < 5; k++) {
			double t = mitsuba_time(th[k], 0.01);

			if (t < 0.0) {
				printf("Mitsuba run failed at %g deg: race "
				       "skipped\n", th[k]);
				free(t127);
				return 0;
			}
			printf("  pair %d: Mitsuba 3 reciprocal, %4.0f deg: "
			       "%.2f s to 1 %%\n", i + 1, th[k], t);
			mi[i] += t;
		}
		if (trace(s, th, 5, need, threads, &r))
			return 1;
		ours[i] = r.seconds;
		worst = worst_rel_sigma(&r, &at);
		tracer_result_free(&r);
		if (trace(s, t127, n127, need127, threads, &r))
			return 1;
		curve[i] = r.seconds;
		mi127[i] = mi[i] / 4.0 * (double)n127;
		tracer_result_free(&r);
		printf("  pair %d: Mitsuba %.2f s, stray trace %.2f s (worst "
		       "%.2f %%); 127-angle curve %.2f s\n", i + 1, mi[i],
		       ours[i], 100.0 * worst, curve[i]);
	}
	bench_ratio("race to 1 % at 30/45/60/80 deg on the exported mesh, "
		    "Mitsuba / stray trace:", mi, ours, pairs, 6, 1);
	printf("  Mitsuba for the 127-angle curve at its mean rate: %.0f s "
	       "(median)\n", bench_median(mi127, pairs, &lo, &hi));
	bench_ratio("127-angle curve to 1 %, Mitsuba (4 angles x 127/4) / "
		    "stray trace (target >= 50):", mi127, curve, pairs, 6, 1);
	free(t127);
	return 0;
}

int main(int argc, char **argv)
{
	struct tracer_scene s;
	struct stray_error err;
	double raw1;
	uint64_t need = 0;
	int peer_only = argc > 1 && strcmp(argv[1], "--peer") == 0, rc;

	stray_error_clear(&err);
	tracer_scene_init(&s);
	if (tracer_scene_load("ref4", NULL, 0, &s, &err) ||
	    tracer_scene_commit(&s, &err)) {
		fprintf(stderr, "bench_trace: cannot build ref4\n");
		return 1;
	}
	if (peer_only) {
		rc = peer_check(&s, 2, 4000000);
		tracer_scene_free(&s);
		return rc;
	}
	raw1 = raw_casts_per_s(&s, 2000000);
	printf("raw rtcIntersect1, incoherent, 1 thread: %.3g casts/s\n", raw1);
	{
		double occ[BENCH_MAX_PAIRS], fan[BENCH_MAX_PAIRS];
		double same[BENCH_MAX_PAIRS], lo, hi;
		long nr = 0;
		int i, pairs = bench_pairs();

		for (i = 0; i < pairs; i++) {
			occ[i] = raw_occluded_per_s(&s, 1000000);
			fan[i] = fan_per_s(&s, &same[i], &nr);
		}
		printf("shadow rays (%ld connections of %d path vertices to the "
		       "127 angles, culled), 1 thread,\n  median (min-max) of "
		       "%d alternating pairs (raw rtcOccluded1, fans):\n",
		       nr, FAN_VERTS, pairs);
		bench_ratio("  packets (rtcOccluded4/8/16) / raw single-ray "
			    "occlusion (target >= 1.5):", fan, occ, pairs, 6, 2);
		bench_ratio("  the same rays one by one / raw:               "
			    "              ", same, occ, pairs, 6, 2);
		printf("  raw rtcOccluded1 %.3g rays/s, packets %.3g rays/s "
		       "(medians)\n", bench_median(occ, pairs, &lo, &hi),
		       bench_median(fan, pairs, &lo, &hi));
	}
	rc = bench_curve(&s, 2, &need);
	if (!rc)
		rc = race_mitsuba(&s, 2, need);
	if (!rc)
		rc = peer_check(&s, 2, 2000000);
	tracer_scene_free(&s);
	return rc;
}
