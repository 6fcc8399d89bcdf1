/*
 * piece.c - run, pack and assemble the pieces of a distributed trace.
 */
#include <stdlib.h>
#include <string.h>

#include "piece.h"

/* The doubles before a pilot's encoded s2 (the whole of a main piece's
 * payload without path records). */
static size_t fixed_len(const struct piece *p)
{
	size_t n = (size_t)p->theta_n;

	return PIECE_HEAD + n * TRACER_ORDERS +
	       (p->light ? n * TRACER_LIGHT_STATS : 0);
}

size_t piece_payload_len(const struct piece *p)
{
	return fixed_len(p) + (p->pass == PIECE_PILOT ?
		1 + (size_t)p->theta_n * TRACER_GUIDE_CELLS : 0);
}

/*
 * A pilot piece's s2 tallies ([cell][angle], most of them zero: a cell
 * scores only at the angles its paths reach) as runs of nonzero values:
 * n_runs, then per run its start, length and values; or, when that is
 * not shorter, PIECE_S2_DENSE and every value.  The same doubles either
 * way, so the guide's bits do not change; at 1.5 M paths (127 angles)
 * about 17 % of the values are nonzero.
 */
#define PIECE_S2_DENSE (-1.0)

static size_t pack_s2(const double *s2, size_t b, size_t n, double *out)
{
	size_t total = n * TRACER_GUIDE_CELLS, i = 0, k = 1, runs = 0;
	const double *v = s2 + b * total;

	while (i < total) {
		size_t j;

		for (; i < total && v[i] == 0.0; i++)
			;
		for (j = i; j < total && v[j] != 0.0; j++)
			;
		if (j > i) {
			if (k + 2 + (j - i) >= 1 + total)
				break;	/* not shorter than dense */
			out[k++] = (double)i;
			out[k++] = (double)(j - i);
			memcpy(out + k, v + i, (j - i) * sizeof(double));
			k += j - i;
			runs++;
		}
		i = j;
	}
	if (i < total) {
		out[0] = PIECE_S2_DENSE;
		memcpy(out + 1, v, total * sizeof(double));
		return 1 + total;
	}
	out[0] = (double)runs;
	return k;
}

/* Doubles of an encoded s2 of total values in [q, q + avail), or 0 when
 * malformed (runs out of order, out of range, or past the end). */
static size_t s2_encoded_len(const double *q, size_t avail, size_t total)
{
	size_t k = 1, r, runs, end = 0;

	if (avail < 1)
		return 0;
	if (q[0] == PIECE_S2_DENSE)
		return avail >= 1 + total ? 1 + total : 0;
	if (!(q[0] >= 0.0 && q[0] <= (double)total) || q[0] != (size_t)q[0])
		return 0;
	runs = (size_t)q[0];
	for (r = 0; r < runs; r++) {
		double start, len;

		if (k + 2 > avail)
			return 0;
		start = q[k];
		len = q[k + 1];
		if (!(start >= (double)end && len >= 1.0 &&
		      start + len <= (double)total) ||
		    start != (size_t)start || len != (size_t)len ||
		    k + 2 + (size_t)len > avail)
			return 0;
		end = (size_t)start + (size_t)len;
		k += 2 + (size_t)len;
	}
	return k;
}

/* Decode into s2's rows of batch b at the piece's angles. */
static void unpack_s2(const double *q, size_t b, size_t f, size_t n,
		      size_t nt, double *s2)
{
	size_t total = n * TRACER_GUIDE_CELLS, i, r, k = 1;
	double *row = s2 + b * TRACER_GUIDE_CELLS * nt;

	if (q[0] == PIECE_S2_DENSE) {
		for (i = 0; i < total; i++)
			row[(i / n) * nt + f + i % n] = q[1 + i];
		return;
	}
	for (r = 0; r < (size_t)q[0]; r++) {
		size_t start = (size_t)q[k], len = (size_t)q[k + 1];

		for (i = 0; i < len; i++)
			row[((start + i) / n) * nt + f + (start + i) % n] =
				q[k + 2 + i];
		k += 2 + len;
	}
}

/* The payload's doubles; the pilot's s2 part encoded (pack_s2). */
static size_t pack(const struct piece *p, const struct tracer_result *r,
		   const double *s2, const double *light, double *out)
{
	size_t n = (size_t)p->theta_n, b = (size_t)p->batch;

	out[0] = (double)r->batch_paths[b];
	out[1] = (double)r->casts;
	out[2] = (double)r->connections;
	memcpy(out + 3, r->energy + b * TRACER_ENERGY_N,
	       TRACER_ENERGY_N * sizeof(double));
	memcpy(out + PIECE_HEAD, r->power + b * n * TRACER_ORDERS,
	       n * TRACER_ORDERS * sizeof(double));
	if (p->light)	/* batch b's rows of this piece's angles */
		memcpy(out + PIECE_HEAD + n * TRACER_ORDERS,
		       light + b * n * TRACER_LIGHT_STATS,
		       n * TRACER_LIGHT_STATS * sizeof(double));
	if (p->pass != PIECE_PILOT)
		return fixed_len(p);
	return fixed_len(p) + pack_s2(s2, b, n, out + fixed_len(p));
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
	double *s2 = NULL, *light = NULL;
	int rc;

	memset(&r, 0, sizeof(r));
	if (p->light && (p->pass != PIECE_PILOT || !po->light_paths))
		return stray_error_set(err, STRAY_EINVAL, "piece",
			"B statistics asked of a pass without light_paths");
	if (p->theta_first < 0 || p->theta_n < 1 ||
	    (size_t)p->theta_first + (size_t)p->theta_n > po->n_theta)
		return stray_error_set_value(err, STRAY_EINVAL, "piece",
			"angle range outside the sweep", p->theta_first);
	o.theta_deg = po->theta_deg + p->theta_first;
	if (po->beam_shift_z)
		o.beam_shift_z = po->beam_shift_z + p->theta_first;
	if (po->light_ratio)	/* B's samples per path, per angle */
		o.light_ratio = po->light_ratio + p->theta_first;
	o.n_theta = (size_t)p->theta_n;
	o.threads = 1;		/* ranks, not threads, share the work */
	o.progress = NULL;
	if (p->pass == PIECE_PILOT) {
		s2 = calloc((size_t)o.n_batches * TRACER_GUIDE_CELLS *
			    o.n_theta, sizeof(double));
		if (p->light)
			light = calloc((size_t)o.n_batches * o.n_theta *
				       TRACER_LIGHT_STATS, sizeof(double));
		if (!s2 || (p->light && !light)) {
			free(s2);
			return stray_error_set(err, STRAY_ENOMEM, "piece",
					       "out of memory");
		}
	}
	rc = tracer_trace_batches_light(s, &o, p->pass == PIECE_PILOT ? NULL :
					g, p->batch, 1, s2, light, &r, err);
	if (!rc && !fixed) {	/* piece_run_alloc: room for the most */
		size_t n = piece_payload_len(p) + (o.record_paths ?
			1 + r.paths.n * PIECE_PATH_FIELDS : 0);
		double *nb = realloc(*out, n * sizeof(double));

		if (!nb)
			rc = stray_error_set(err, STRAY_ENOMEM, "piece",
					     "out of memory");
		else
			*out = fixed = nb;
	}
	if (!rc) {
		size_t used = pack(p, &r, s2, light, fixed);

		if (o.record_paths && len) {
			pack_paths(p, &r, fixed + used);
			used += 1 + r.paths.n * PIECE_PATH_FIELDS;
		}
		if (len)
			*len = used;
	}
	tracer_result_free(&r);
	free(s2);
	free(light);
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

	if (p->pass == PIECE_PILOT) {	/* s2 encoded: at most dense */
		size_t fixed = fixed_len(p);

		if (len < fixed + 1 || len > head)
			return 0;
		return !payload || fixed + s2_encoded_len(payload + fixed,
			len - fixed, (size_t)p->theta_n * TRACER_GUIDE_CELLS) ==
			len;
	}
	if (!record_paths)
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
		 struct tracer_result *r, double *s2, double *light)
{
	size_t n = (size_t)p->theta_n, b = (size_t)p->batch;
	size_t f = (size_t)p->theta_first, nt = r->n_theta;

	r->batch_paths[b] = (uint64_t)payload[0];
	/* a pilot's casts are its paths' (the same in every chunk: once)
	 * plus its connections (per angle): tracer_trace()'s count, which
	 * tracer_light_alloc reads; a main pass's count is only reported */
	if (p->pass == PIECE_PILOT)
		r->casts += (uint64_t)payload[2] +
			    (f == 0 ? (uint64_t)(payload[1] - payload[2]) : 0);
	else
		r->casts += (uint64_t)payload[1];
	r->connections += (uint64_t)payload[2];
	/* every chunk traces the same paths: the energy of one is the batch's */
	if (f == 0)
		memcpy(r->energy + b * TRACER_ENERGY_N, payload + 3,
		       TRACER_ENERGY_N * sizeof(double));
	memcpy(r->power + (b * nt + f) * TRACER_ORDERS, payload + PIECE_HEAD,
	       n * TRACER_ORDERS * sizeof(double));
	if (p->light && light)
		memcpy(light + (b * nt + f) * TRACER_LIGHT_STATS,
		       payload + PIECE_HEAD + n * TRACER_ORDERS,
		       n * TRACER_LIGHT_STATS * sizeof(double));
	if (p->pass == PIECE_PILOT && s2)
		unpack_s2(payload + fixed_len(p), b, f, n, nt, s2);
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
			out[k].light = 0;
			k++;
		}
	return k;
}
