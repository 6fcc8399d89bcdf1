/*
 * piece.c - run, pack and assemble the pieces of a distributed trace.
 */
#include <stdlib.h>
#include <string.h>

#include "piece.h"

size_t piece_payload_len(const struct piece *p)
{
	size_t n = (size_t)p->theta_n;

	return PIECE_HEAD + n * TRACER_ORDERS +
	       (p->pass == PIECE_PILOT ? n * TRACER_GUIDE_CELLS : 0);
}

static void pack(const struct piece *p, const struct tracer_result *r,
		 const double *s2, double *out)
{
	size_t n = (size_t)p->theta_n, b = (size_t)p->batch, c, j;

	out[0] = (double)r->batch_paths[b];
	out[1] = (double)r->casts;
	out[2] = (double)r->connections;
	memcpy(out + 3, r->energy + b * TRACER_ENERGY_N,
	       TRACER_ENERGY_N * sizeof(double));
	memcpy(out + PIECE_HEAD, r->power + b * n * TRACER_ORDERS,
	       n * TRACER_ORDERS * sizeof(double));
	if (p->pass != PIECE_PILOT)
		return;
	for (c = 0; c < TRACER_GUIDE_CELLS; c++)
		for (j = 0; j < n; j++)
			out[PIECE_HEAD + n * TRACER_ORDERS + c * n + j] =
				s2[(b * TRACER_GUIDE_CELLS + c) * n + j];
}

/* A batch's path records (r->paths: that batch alone) after the fixed
 * part; theta_index shifted from the piece's angles to the sweep's. */
static void pack_paths(const struct piece *p, const struct tracer_result *r,
		       double *out)
{
	const struct tracer_path_table *t = &r->paths;
	size_t i, m = 0;

	out[0] = (double)t->n;
	for (i = 0; i < t->cap; i++) {
		const struct tracer_path_entry *e = &t->e[i];
		double *q = out + 1 + m * PIECE_PATH_FIELDS;

		if (!e->used)
			continue;
		q[0] = (double)e->theta_index + p->theta_first;
		q[1] = (double)(e->seq >> 32);
		q[2] = (double)(e->seq & 0xffffffffu);
		q[3] = e->value;
		q[4] = e->n_paths;
		m++;
	}
}

static int run_into(const struct tracer_scene *s,
		    const struct tracer_trace_opts *po,
		    const struct tracer_guide *g, const struct piece *p,
		    double **out, size_t *len, double *fixed,
		    struct stray_error *err)
{
	struct tracer_trace_opts o = *po;
	struct tracer_result r;
	double *s2 = NULL;
	int rc;

	memset(&r, 0, sizeof(r));
	if (p->theta_first < 0 || p->theta_n < 1 ||
	    (size_t)p->theta_first + (size_t)p->theta_n > po->n_theta)
		return stray_error_set_value(err, STRAY_EINVAL, "piece",
			"angle range outside the sweep", p->theta_first);
	o.theta_deg = po->theta_deg + p->theta_first;
	if (po->beam_shift_z)
		o.beam_shift_z = po->beam_shift_z + p->theta_first;
	o.n_theta = (size_t)p->theta_n;
	o.threads = 1;		/* ranks, not threads, share the work */
	o.progress = NULL;
	if (p->pass == PIECE_PILOT) {
		s2 = calloc((size_t)o.n_batches * TRACER_GUIDE_CELLS *
			    o.n_theta, sizeof(double));
		if (!s2)
			return stray_error_set(err, STRAY_ENOMEM, "piece",
					       "out of memory");
	}
	rc = tracer_trace_batches(s, &o, p->pass == PIECE_PILOT ? NULL : g,
				  p->batch, 1, s2, &r, err);
	if (!rc && !fixed) {	/* piece_run_alloc: size the payload */
		size_t n = piece_payload_len(p) + (o.record_paths ?
			1 + r.paths.n * PIECE_PATH_FIELDS : 0);
		double *nb = realloc(*out, n * sizeof(double));

		if (!nb)
			rc = stray_error_set(err, STRAY_ENOMEM, "piece",
					     "out of memory");
		else {
			*out = fixed = nb;
			*len = n;
		}
	}
	if (!rc) {
		pack(p, &r, s2, fixed);
		if (o.record_paths && len)
			pack_paths(p, &r, fixed + piece_payload_len(p));
	}
	tracer_result_free(&r);
	free(s2);
	return rc;
}

int piece_run(const struct tracer_scene *s,
	      const struct tracer_trace_opts *po,
	      const struct tracer_guide *g, const struct piece *p,
	      double *out, struct stray_error *err)
{
	struct tracer_trace_opts o = *po;

	o.record_paths = 0;	/* a fixed payload has no room for them */
	return run_into(s, &o, g, p, NULL, NULL, out, err);
}

int piece_run_alloc(const struct tracer_scene *s,
		    const struct tracer_trace_opts *po,
		    const struct tracer_guide *g, const struct piece *p,
		    double **out, size_t *len, struct stray_error *err)
{
	return run_into(s, po, g, p, out, len, NULL, err);
}

int piece_payload_ok(const struct piece *p, int record_paths,
		     const double *payload, size_t len)
{
	size_t head = piece_payload_len(p);

	if (!record_paths || p->pass == PIECE_PILOT)
		return len == head;
	if (len < head + 1 || (len - head - 1) % PIECE_PATH_FIELDS)
		return 0;
	return !payload ||
	       payload[head] == (double)((len - head - 1) / PIECE_PATH_FIELDS);
}

int piece_apply_paths(const struct piece *p, const double *payload,
		      struct tracer_path_table *tables)
{
	const double *q = payload + piece_payload_len(p);
	size_t n = (size_t)q[0], i;
	struct tracer_path_table flat;
	int rc;

	if (!n)
		return STRAY_OK;
	flat.cap = flat.n = n;
	flat.e = calloc(n, sizeof(*flat.e));
	if (!flat.e)
		return STRAY_ENOMEM;
	for (i = 0; i < n; i++) {	/* a table merge reads slot by slot */
		const double *f = q + 1 + i * PIECE_PATH_FIELDS;

		flat.e[i].used = 1;
		flat.e[i].theta_index = (uint32_t)f[0];
		flat.e[i].seq = (uint64_t)f[1] << 32 | (uint64_t)f[2];
		flat.e[i].value = f[3];
		flat.e[i].n_paths = f[4];
	}
	rc = tracer_paths_merge(&tables[p->batch], &flat);
	free(flat.e);
	return rc;
}

int piece_result_alloc(const struct tracer_trace_opts *po,
		       struct tracer_result *r, double **s2)
{
	size_t nb = (size_t)po->n_batches, nt = po->n_theta;

	memset(r, 0, sizeof(*r));
	r->n_theta = nt;
	r->n_batches = po->n_batches;
	r->n_paths = po->n_paths;
	r->batch_paths = calloc(nb, sizeof(uint64_t));
	r->power = calloc(nb * nt * TRACER_ORDERS, sizeof(double));
	r->energy = calloc(nb * TRACER_ENERGY_N, sizeof(double));
	r->theta_deg = malloc(nt * sizeof(double));
	if (r->theta_deg)
		memcpy(r->theta_deg, po->theta_deg, nt * sizeof(double));
	if (s2)
		*s2 = calloc(nb * TRACER_GUIDE_CELLS * nt, sizeof(double));
	if (r->batch_paths && r->power && r->energy && r->theta_deg &&
	    (!s2 || *s2))
		return STRAY_OK;
	tracer_result_free(r);
	if (s2) {
		free(*s2);
		*s2 = NULL;
	}
	return STRAY_ENOMEM;
}

void piece_apply(const struct piece *p, const double *payload,
		 struct tracer_result *r, double *s2)
{
	size_t n = (size_t)p->theta_n, b = (size_t)p->batch;
	size_t f = (size_t)p->theta_first, nt = r->n_theta, c, j;

	r->batch_paths[b] = (uint64_t)payload[0];
	r->casts += (uint64_t)payload[1];
	r->connections += (uint64_t)payload[2];
	/* every chunk traces the same paths: the energy of one is the batch's */
	if (f == 0)
		memcpy(r->energy + b * TRACER_ENERGY_N, payload + 3,
		       TRACER_ENERGY_N * sizeof(double));
	memcpy(r->power + (b * nt + f) * TRACER_ORDERS, payload + PIECE_HEAD,
	       n * TRACER_ORDERS * sizeof(double));
	if (p->pass != PIECE_PILOT || !s2)
		return;
	for (c = 0; c < TRACER_GUIDE_CELLS; c++)
		for (j = 0; j < n; j++)
			s2[(b * TRACER_GUIDE_CELLS + c) * nt + f + j] =
				payload[PIECE_HEAD + n * TRACER_ORDERS +
					c * n + j];
}

size_t piece_plan(int pass, int n_batches, size_t n_theta, int n_chunks,
		  struct piece *out)
{
	size_t k = 0;
	int b, c;

	if (n_chunks < 1)
		n_chunks = 1;
	if ((size_t)n_chunks > n_theta)
		n_chunks = (int)n_theta;
	for (b = 0; b < n_batches; b++)
		for (c = n_chunks - 1; c >= 0; c--) {
			size_t lo = n_theta * (size_t)c / (size_t)n_chunks;
			size_t hi = n_theta * (size_t)(c + 1) / (size_t)n_chunks;

			out[k].pass = pass;
			out[k].batch = b;
			out[k].theta_first = (int)lo;
			out[k].theta_n = (int)(hi - lo);
			k++;
		}
	return k;
}
