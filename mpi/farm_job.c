/*
 * farm_job.c - the job description sent to every rank: the scene as the
 * command line gave it (name, --set list, lens path, edits after
 * loading: tracer/runner.h) and the trace's
 * options, so that each rank builds the same scene itself.
 */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "farm_proto.h"

struct job_head {
	uint64_t n_paths, seed;
	double rr_weight;
	double beam_shift_z, abg_g;	/* the scene's edits after loading */
	int32_t n_batches, rr_depth, max_depth, guide;
	int32_t n_theta, n_sets, has_lens, record_paths;
	int32_t has_shifts;	/* opts.beam_shift_z follows theta_deg */
	int32_t id;		/* the trace's number in its set */
	int32_t light_paths, light_weights;	/* strategy B (light.h) */
};

static size_t str_size(const char *s)
{
	return s ? strlen(s) + 1 : 1;
}

char *farm_job_pack(const struct tracer_scene_spec *spec,
		    const struct tracer_trace_opts *o, int id, size_t *len)
{
	struct job_head h;
	size_t angles = (o->beam_shift_z ? 2 : 1) * o->n_theta * sizeof(double);
	size_t n = sizeof(h) + angles, k;
	char *buf, *p;
	int i;

	memset(&h, 0, sizeof(h));
	h.n_paths = o->n_paths;
	h.seed = o->seed;
	h.rr_weight = o->rr_weight;
	h.beam_shift_z = spec->beam_shift_z;
	h.abg_g = spec->abg_g;
	h.n_batches = o->n_batches;
	h.rr_depth = o->rr_depth;
	h.max_depth = o->max_depth;
	h.guide = o->guide;
	h.n_theta = (int32_t)o->n_theta;
	h.n_sets = spec->n_sets;
	h.has_lens = spec->lens != NULL;
	h.record_paths = o->record_paths != 0;
	h.has_shifts = o->beam_shift_z != NULL;
	h.id = id;
	h.light_paths = o->light_paths != 0;
	h.light_weights = o->light_weights;
	n += str_size(spec->scene) + str_size(spec->lens);
	for (i = 0; i < spec->n_sets; i++)
		n += str_size(spec->sets[i]);
	buf = malloc(n);
	if (!buf)
		return NULL;
	memcpy(buf, &h, sizeof(h));
	memcpy(buf + sizeof(h), o->theta_deg, o->n_theta * sizeof(double));
	if (o->beam_shift_z)
		memcpy(buf + sizeof(h) + o->n_theta * sizeof(double),
		       o->beam_shift_z, o->n_theta * sizeof(double));
	p = buf + sizeof(h) + angles;
	k = str_size(spec->scene);
	memcpy(p, spec->scene ? spec->scene : "", k);
	p += k;
	k = str_size(spec->lens);
	memcpy(p, spec->lens ? spec->lens : "", k);
	p += k;
	for (i = 0; i < spec->n_sets; i++) {
		k = str_size(spec->sets[i]);
		memcpy(p, spec->sets[i], k);
		p += k;
	}
	*len = n;
	return buf;
}

/* The next NUL-terminated string in [*p, end), or NULL. */
static const char *next_str(char **p, const char *end)
{
	char *s = *p, *z = memchr(s, '\0', (size_t)(end - s));

	if (!z)
		return NULL;
	*p = z + 1;
	return s;
}

int farm_job_unpack(char *buf, size_t len, struct farm_job *j,
		    struct stray_error *err)
{
	struct job_head h;
	char *p, *end = buf + len;
	int i;

	if (len < sizeof(h))
		return stray_error_set(err, STRAY_EINVAL, "job", "truncated");
	memcpy(&h, buf, sizeof(h));
	if (h.n_theta < 1 || h.n_sets < 0 || h.n_sets > FARM_SETS_MAX ||
	    (h.has_shifts != 0 && h.has_shifts != 1) ||
	    (h.light_paths != 0 && h.light_paths != 1) ||
	    (size_t)h.n_theta > (len - sizeof(h)) / sizeof(double) /
				(h.has_shifts ? 2 : 1))
		return stray_error_set(err, STRAY_EINVAL, "job", "malformed");
	tracer_trace_defaults(&j->o);
	j->id = h.id;
	j->o.n_paths = h.n_paths;
	j->o.seed = h.seed;
	j->o.rr_weight = h.rr_weight;
	j->o.n_batches = h.n_batches;
	j->o.rr_depth = h.rr_depth;
	j->o.max_depth = h.max_depth;
	j->o.guide = h.guide;
	j->o.record_paths = h.record_paths;
	j->o.light_paths = h.light_paths;
	j->o.light_weights = h.light_weights;
	j->beam_shift_z = h.beam_shift_z;
	j->abg_g = h.abg_g;
	j->o.n_theta = (size_t)h.n_theta;
	/* the buffer is malloc'ed: suitably aligned for doubles */
	j->o.theta_deg = (const double *)(void *)(buf + sizeof(h));
	p = buf + sizeof(h) + (size_t)h.n_theta * sizeof(double);
	if (h.has_shifts) {
		j->o.beam_shift_z = (const double *)(void *)p;
		p += (size_t)h.n_theta * sizeof(double);
	}
	j->scene = next_str(&p, end);
	j->lens = j->scene ? next_str(&p, end) : NULL;
	if (!j->lens)
		return stray_error_set(err, STRAY_EINVAL, "job", "truncated");
	if (!h.has_lens)
		j->lens = NULL;
	j->n_sets = h.n_sets;
	for (i = 0; i < h.n_sets; i++)
		if (!(j->sets[i] = next_str(&p, end)))
			return stray_error_set(err, STRAY_EINVAL, "job",
					       "truncated");
	return STRAY_OK;
}

double farm_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void farm_nap(void)
{
	struct timespec ts = { 0, 1000000 };	/* 1 ms */

	nanosleep(&ts, NULL);
}
