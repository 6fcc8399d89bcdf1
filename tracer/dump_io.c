/*
 * dump_io.c - write the sample-path dump and the detector map as CSV.
 */
#include <stdio.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/dump_io.h"

/* Every output through the one atomic path: a temporary renamed whole. */
static FILE *open_out(struct stray_file_out *out, const char *path,
		      const char *field, struct stray_error *err)
{
	if (stray_file_open_atomic(out, path, err) != STRAY_OK) {
		stray_error_set(err, STRAY_EIO, field, "cannot open for writing");
		return NULL;
	}
	return out->f;
}

static int finish(struct stray_file_out *out, struct stray_error *err)
{
	return stray_file_commit(out, err);
}

int tracer_dump_write_csv(const struct tracer_result *r,
			  const struct tracer_scene *s, const char *path,
			  struct stray_error *err)
{
	struct stray_file_out out;
	FILE *f = open_out(&out, path, "--dump-paths", err);
	uint64_t p;
	int v;

	if (!f)
		return err ? err->code : STRAY_EIO;
	fprintf(f, "# sample paths from the detector (vertex 0) into the "
		"scene; the trace is adjoint\npath,vertex,x_mm,y_mm,z_mm,"
		"group\n");
	for (p = 0; p < r->n_dump; p++)
		for (v = 0; v < r->dump_len[p]; v++) {
			const struct tracer_vertex *x =
				&r->dump[p * TRACER_DUMP_DEPTH + v];

			fprintf(f, "%llu,%d,%.6g,%.6g,%.6g,%s\n",
				(unsigned long long)p, v, x->x, x->y, x->z,
				x->group < 0 ? "detector_point" :
				s->mesh.group_name[x->group]);
		}
	return finish(&out, err);
}

int tracer_map_write_csv(const struct tracer_result *r, const char *path,
			 struct stray_error *err)
{
	struct stray_file_out out;
	FILE *f = open_out(&out, path, "--map", err);
	int i, j, n = r->map_n;

	if (!f)
		return err ? err->code : STRAY_EIO;
	fprintf(f, "# detector irradiance over beam irradiance at theta_deg "
		"%.10g, %d x %d pixels\nx_mm,y_mm,irradiance_rel\n",
		r->map_theta_deg, n, n);
	for (i = 0; i < n; i++)
		for (j = 0; j < n; j++)
			fprintf(f, "%.6g,%.6g,%.6g\n",
				r->map_half_w_mm * (2.0 * (j + 0.5) / n - 1.0),
				r->map_half_h_mm * (2.0 * (i + 0.5) / n - 1.0),
				r->map[i * n + j]);
	return finish(&out, err);
}
