/*
 * bench_diagnose.c - a full diagnosis of a 90-angle curve (issue 5: "takes
 * minutes, not hours, on 2 cores"): reflectance 0.08 and knife-edge
 * radius 0.05 mm hidden on ref4, `stray diagnose` run as a user would.
 * Reported as wall time and as a ratio to one nominal trace of the same
 * angles and paths measured in the same run (the unit the diagnosis is
 * made of), and against issue 27's target of 10 s wall on 2 cores as a
 * figure, not a verdict: on a shared machine the wall clock counts the
 * other processes too, so the cpu seconds are printed beside it.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/resource.h>

#include <cJSON.h>

#include "stray/error.h"
#include "tools/run_cli.h"
#include "tracer/integrator.h"
#include "tracer/scene_load.h"
#include "truth.h"

#define N_ANGLES 90
#define RAYS 200000
#define TARGET_WALL_S 10.0	/* issue 27: "<= 10 s wall on 2 cores" */

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double tv_s(struct timeval t)
{
	return t.tv_sec + 1e-6 * t.tv_usec;
}

/* One nominal trace of the angles with path recording, seconds. */
static double one_trace_s(const double *theta)
{
	struct tracer_scene s;
	struct tracer_trace_opts o;
	struct tracer_result r;
	struct stray_error err;
	double t0;

	stray_error_clear(&err);
	tracer_scene_init(&s);
	memset(&r, 0, sizeof(r));
	if (tracer_scene_load("ref4", NULL, 0, &s, &err) ||
	    tracer_scene_commit(&s, &err))
		return -1.0;
	tracer_trace_defaults(&o);
	o.theta_deg = theta;
	o.n_theta = N_ANGLES;
	o.n_paths = RAYS;
	o.threads = 2;
	o.record_paths = 1;
	t0 = now_s();
	if (tracer_trace(&s, &o, &r, &err))
		t0 = now_s() + 1.0;
	t0 = now_s() - t0;
	tracer_result_free(&r);
	tracer_scene_free(&s);
	return t0;
}

int main(void)
{
	static struct cli_run run;
	double theta[N_ANGLES], t_trace, t_diag;
	char path[] = "/tmp/stray_bench_diag_XXXXXX.csv";
	char rays[32];
	char *argv[] = { "stray", "diagnose", path, "--scene", "ref4",
			 "--rays", rays, "--threads", "2", "--json", NULL };
	struct truth_config c;
	cJSON *j, *it;
	struct rusage ru0, ru1;
	int i, fd = mkstemps(path, 4);

	if (fd < 0)
		return 1;
	close(fd);
	for (i = 0; i < N_ANGLES; i++)
		theta[i] = i;
	snprintf(rays, sizeof(rays), "%d", RAYS);
	truth_defaults(&c, theta, N_ANGLES);
	c.sets[c.n_sets++] = "reflectance=0.08";
	c.sets[c.n_sets++] = "edge_radius=0.05";
	if (truth_write(&c, path))
		return 1;
	t_trace = one_trace_s(theta);
	getrusage(RUSAGE_CHILDREN, &ru0);
	t_diag = now_s();
	run_stray(&run, argv);
	t_diag = now_s() - t_diag;
	getrusage(RUSAGE_CHILDREN, &ru1);
	unlink(path);
	j = cJSON_Parse(run.out);
	if (run.status || !j) {
		fprintf(stderr, "bench_diagnose: stray diagnose failed: %s\n",
			run.err);
		return 1;
	}
	printf("diagnose, %d angles, %d paths per trace, 2 threads: %.1f s "
	       "wall = %.1f x one nominal trace (%.2f s); %g traces\n",
	       N_ANGLES, RAYS, t_diag, t_diag / t_trace, t_trace,
	       cJSON_GetObjectItem(j, "traces")->valuedouble);
	/* on a shared machine the wall clock counts other processes too */
	printf("  cpu of stray diagnose: %.1f s user + %.1f s system; "
	       "%.1f s of tracing\n",
	       tv_s(ru1.ru_utime) - tv_s(ru0.ru_utime),
	       tv_s(ru1.ru_stime) - tv_s(ru0.ru_stime),
	       cJSON_GetObjectItem(j, "trace_seconds")->valuedouble);
	printf("  wall %.1f s against the %.0f s target: %.2f x the target\n",
	       t_diag, TARGET_WALL_S, t_diag / TARGET_WALL_S);
	printf("  named (before and after a change must agree):");
	cJSON_ArrayForEach(it, cJSON_GetObjectItem(j, "causes")) {
		const cJSON *p, *ci = cJSON_GetObjectItem(it, "intervals");

		printf(" %s", cJSON_GetObjectItem(it, "name")->valuestring);
		cJSON_ArrayForEach(p, cJSON_GetObjectItem(it, "params")) {
			const cJSON *iv = cJSON_GetObjectItem(ci, p->string);

			printf(" %s %.6g", p->string, p->valuedouble);
			if (cJSON_GetArraySize(iv) == 2)
				printf(" [%.6g, %.6g]",
				       cJSON_GetArrayItem(iv, 0)->valuedouble,
				       cJSON_GetArrayItem(iv, 1)->valuedouble);
		}
		printf(";");
	}
	printf(" rms %.4f -> %.4f\n",
	       cJSON_GetObjectItem(j, "rms_before")->valuedouble,
	       cJSON_GetObjectItem(j, "rms_after")->valuedouble);
	cJSON_Delete(j);
	return 0;
}
