/*
 * path_report.c - turn the (angle, group sequence) tallies into shares of
 * alpha with standard errors, sorted per angle.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/path_report.h"

char *tracer_path_name(const struct tracer_scene *s, uint64_t seq,
		       char *buf, size_t size)
{
	int g[TRACER_SEQ_MAX], n = tracer_seq_unpack(seq, g), i;
	size_t len = 0;

	buf[0] = '\0';
	for (i = 0; i < n && len + 1 < size; i++)
		len += (size_t)snprintf(buf + len, size - len, "%s%s",
					i ? ">" : "",
					s->mesh.group_name[g[i]]);
	if ((seq & TRACER_SEQ_TRUNCATED) && len + 5 < size)
		strcat(buf, ">...");
	return buf;
}

void tracer_path_item_of(const struct tracer_result *r,
			 const struct tracer_scene *s,
			 const struct tracer_path_entry *e, size_t ref,
			 struct tracer_path_item *it)
{
	int g[TRACER_SEQ_MAX], n = tracer_seq_unpack(e->seq, g), i;
	double rho = 1.0, p0, s0, nb = r->n_batches, var;

	for (i = 0; i < n; i++)
		rho *= s->material[g[i]].rho;
	tracer_result_power(r, ref, -1, &p0, &s0);
	it->theta_index = e->theta_index;
	it->seq = e->seq;
	it->n_scatter = n;
	it->geom = e->value / (double)r->n_paths / p0;
	it->alpha = it->geom * rho;
	/* spread of the per-batch sums around their mean */
	var = (e->value_b2 - e->value * e->value / nb) * nb / (nb - 1.0);
	it->sigma = sqrt(var > 0.0 ? var : 0.0) * rho / (double)r->n_paths / p0;
}

static int cmp_item(const void *a, const void *b)
{
	const struct tracer_path_item *x = a, *y = b;

	if (x->theta_index != y->theta_index)
		return x->theta_index < y->theta_index ? -1 : 1;
	return (x->alpha < y->alpha) - (x->alpha > y->alpha);
}

/* All items sorted by angle, then by decreasing share. */
static struct tracer_path_item *sorted_items(const struct tracer_result *r,
					     const struct tracer_scene *s,
					     size_t *n)
{
	struct tracer_path_item *it = malloc((r->paths.n + 1) * sizeof(*it));
	size_t i, k = 0;

	if (!it)
		return NULL;
	for (i = 0; i < r->paths.cap; i++)
		if (r->paths.e[i].used)
			tracer_path_item_of(r, s, &r->paths.e[i], 0, &it[k++]);
	qsort(it, k, sizeof(*it), cmp_item);
	*n = k;
	return it;
}

int tracer_paths_write_csv(const struct tracer_result *r,
			   const struct tracer_scene *s, const char *path,
			   struct stray_error *err)
{
	struct tracer_path_item *it;
	size_t n, i;
	char name[512];
	struct stray_file_out out;
	FILE *f;

	it = sorted_items(r, s, &n);
	if (!it)
		return stray_error_set(err, STRAY_ENOMEM, "paths",
				       "out of memory");
	if (stray_file_open_atomic(&out, path, err) != STRAY_OK) {
		free(it);
		return stray_error_set(err, STRAY_EIO, "--paths-out",
				       "cannot open for writing");
	}
	f = out.f;
	fprintf(f, "# alpha_part: share of alpha(theta) carried by the path "
		"(source side first)\n# alpha_per_rho: alpha_part / product of "
		"the path's reflectances (re-weight with new ones)\n"
		"theta_deg,path,n_scatter,alpha_part,sigma,alpha_per_rho\n");
	for (i = 0; i < n; i++)
		fprintf(f, "%.10g,%s,%d,%.6g,%.3g,%.6g\n",
			r->theta_deg[it[i].theta_index],
			tracer_path_name(s, it[i].seq, name, sizeof(name)),
			it[i].n_scatter, it[i].alpha, it[i].sigma,
			it[i].geom);
	free(it);
	return stray_file_commit(&out, err);
}

void tracer_paths_print_top(const struct tracer_result *r,
			    const struct tracer_scene *s, size_t first, int n,
			    FILE *out)
{
	struct tracer_path_item *it;
	size_t cnt, i;
	char name[512];
	int shown = 0;

	it = sorted_items(r, s, &cnt);
	if (!it)
		return;
	for (i = 0; i < cnt; i++) {
		if (i == 0 || it[i].theta_index != it[i - 1].theta_index)
			shown = 0;
		if (it[i].theta_index < first || shown++ >= n)
			continue;
		fprintf(out, "%6.2f  %-44s alpha %.3e +- %.1e\n",
			r->theta_deg[it[i].theta_index],
			tracer_path_name(s, it[i].seq, name, sizeof(name)),
			it[i].alpha, it[i].sigma);
	}
	free(it);
}
