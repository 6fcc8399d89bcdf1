/*
 * focal_map_io.c - `stray trace --focal-map`: the sensor's focal geometry
 * for the tracer, and the map it returns as FITS (cfitsio) and PNG
 * (OpenCV false colour); see focal_map_io.h and tracer/README.md.  The
 * command's options and --json are tools/trace_focal.c.
 */
#include <fitsio.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frames/focal_map_io.h"
#include "frames/image_cv.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sweep_store.h"
#include "stray/sensor_geom.h"
#include "stray/sensor_io.h"
#include "stray/table.h"
#include "tracer/source.h"

void focal_map_defaults(struct focal_map_args *f)
{
	memset(f, 0, sizeof(*f));
	f->sensor = "st16-like";
	f->cell_px = 36;
}

int focal_map_wanted(const struct focal_map_args *f)
{
	return f->fits || f->png;
}

int focal_map_prepare(struct focal_map_args *f, size_t theta_index,
		      struct tracer_trace_opts *o, struct stray_error *err)
{
	struct stray_sensor *s = &f->sen;
	double pitch_mm;
	int rc = stray_sensor_load(f->sensor, s, err);

	if (rc)
		return rc;
	if (fmod(s->pixels_x, f->cell_px) != 0.0 ||
	    fmod(s->pixels_y, f->cell_px) != 0.0)
		return stray_error_set_value(err, STRAY_EINVAL, "--map-cell",
			"must divide the sensor's pixels_x and pixels_y",
			f->cell_px);
	pitch_mm = s->pixel_pitch_um * 1e-3;
	f->fp.half_w_mm = 0.5 * s->pixels_x * pitch_mm;
	f->fp.half_h_mm = 0.5 * s->pixels_y * pitch_mm;
	f->fp.f_mm = stray_sensor_focal_length_mm(s);
	f->fp.nx = (int)(s->pixels_x / f->cell_px);
	f->fp.ny = (int)(s->pixels_y / f->cell_px);
	f->fp.theta_index = theta_index;
	f->k_px = stray_sensor_k_px(s, STRAY_NORM_CONSISTENT);
	o->focal = &f->fp;
	return tracer_focal_check(&f->fp, err);
}

/* fraction,rel_alpha of a region map CSV (stray reduce --map). */
static int load_lens_map(const char *path, double **fr, double **rel,
			 size_t *n, struct stray_error *err)
{
	struct stray_table t;
	int cf, ca, rc = stray_table_read(path, &t, err);

	if (rc)
		return rc;
	cf = stray_table_find(&t, "fraction");
	ca = stray_table_find(&t, "rel_alpha");
	if (cf < 0 || ca < 0 || t.n_rows < 1) {
		rc = stray_error_at(err, STRAY_EPARSE, path, 0,
				    cf < 0 ? "fraction" : "rel_alpha",
				    "region map needs fraction,rel_alpha rows");
	} else {
		*fr = stray_table_column(&t, (size_t)cf);
		*rel = stray_table_column(&t, (size_t)ca);
		*n = t.n_rows;
		if (!*fr || !*rel)
			rc = stray_error_set(err, STRAY_ENOMEM, "--lens-map",
					     "out of memory");
	}
	stray_table_free(&t);
	return rc;
}

/* Where the spread's brightest cells go: the source direction's image. */
static void source_point(const struct focal_map_args *f,
			 const struct tracer_scene *s, double theta_deg,
			 struct tracer_focal_spread *sp)
{
	struct frame fr = frame_from_normal(s->det.normal);

	if (!tracer_focal_point(&f->fp, &fr, tracer_source_dir(theta_deg),
				&sp->src_x_mm, &sp->src_y_mm)) {
		sp->src_x_mm = 0.0;	/* behind the pupil: the +y side */
		sp->src_y_mm = 1e6;
	}
}

static int fits_failed(const char *path, int status, struct stray_error *err)
{
	char text[FLEN_STATUS] = "";

	fits_get_errstatus(status, text);
	fits_clear_errmsg();
	stray_error_at(err, STRAY_EIO, path, 0, "--focal-map",
		       "cannot write the FITS map");
	stray_error_text(err, text);
	return STRAY_EIO;
}

static void fits_keys(fitsfile *fp, const struct focal_map_args *f,
		      const struct tracer_trace_opts *o, int *st)
{
	const struct stray_sensor *s = &f->sen;
	const char *spread = f->lens_map ? "lensmap" : "uniform";
	double theta = o->theta_deg[f->fp.theta_index];
	long paths = (long)o->n_paths, seed = (long)o->seed;
	long npx = (long)s->pixels_x, npy = (long)s->pixels_y;
	int cell = f->cell_px;

	fits_write_key(fp, TSTRING, "BUNIT", "E_px/E_src",
		       "pixel irradiance / source irradiance", st);
	stray_sweep_fits_provenance(fp, st);
	fits_write_key(fp, TDOUBLE, "THETA", &theta, "source angle, deg", st);
	fits_write_key(fp, TDOUBLE, "ALPHA", (void *)&f->alpha,
		       "alpha(theta) = P(theta)/P(0)", st);
	fits_write_key(fp, TDOUBLE, "ALPHASIG", (void *)&f->sigma,
		       "standard error of ALPHA", st);
	fits_write_key(fp, TDOUBLE, "KPX", (void *)&f->k_px,
		       "A_cs / (n_px A_px)", st);
	fits_write_key(fp, TSTRING, "NORM", "consistent",
		       "image mean = KPX * ALPHA; P(0) = E_src A_cs", st);
	fits_write_key(fp, TDOUBLE, "MEAN", (void *)&f->mean,
		       "mean of the image", st);
	fits_write_key(fp, TINT, "CELLPX", &cell, "pixels per cell side", st);
	fits_write_key(fp, TLONG, "NPIXX", &npx, "detector pixels, x", st);
	fits_write_key(fp, TLONG, "NPIXY", &npy, "detector pixels, y", st);
	fits_write_key(fp, TDOUBLE, "PITCHUM", (void *)&s->pixel_pitch_um,
		       "pixel pitch, um", st);
	fits_write_key(fp, TDOUBLE, "FOCALMM", (void *)&f->fp.f_mm,
		       "ideal lens focal length, mm", st);
	fits_write_key(fp, TDOUBLE, "APERTMM", (void *)&s->aperture_diameter_mm,
		       "aperture diameter (A_cs), mm", st);
	fits_write_key(fp, TSTRING, "SPREAD", (void *)spread,
		       "out-of-field light: uniform or lens region map", st);
	fits_write_key(fp, TDOUBLE, "INFIELD", (void *)&f->in_field,
		       "share of P(theta) imaged in the field", st);
	fits_write_key(fp, TSTRING, "SENSOR", (void *)s->name, "sensor", st);
	fits_write_key(fp, TLONG, "PATHS", &paths, "traced paths", st);
	fits_write_key(fp, TLONG, "SEED", &seed, "random seed", st);
}

/*
 * The map built in memory and written through stray_file_open_atomic:
 * cfitsio never sees the path (its "(", "[" and "!" syntax would turn
 * 'map[compress].fits' into 'map'), and a failed write leaves nothing.
 */
static int write_fits(const struct focal_map_args *f, const float *img,
		      const struct tracer_trace_opts *o,
		      struct stray_error *err)
{
	struct stray_file_out out;
	fitsfile *fp = NULL;
	long naxes[2] = { f->fp.nx, f->fp.ny };
	size_t size = 2880;
	void *buf = malloc(size);
	LONGLONG head = 0, data = 0, end = 0;
	int st = 0, rc;

	if (!buf)
		return stray_error_set(err, STRAY_ENOMEM, "--focal-map",
				       "out of memory");
	fits_create_memfile(&fp, &buf, &size, 0, realloc, &st);
	fits_create_img(fp, FLOAT_IMG, 2, naxes, &st);
	fits_keys(fp, f, o, &st);
	fits_write_img(fp, TFLOAT, 1, naxes[0] * naxes[1], (void *)img, &st);
	fits_get_hduaddrll(fp, &head, &data, &end, &st);	/* the length */
	if (fp) {
		int st2 = 0;

		fits_close_file(fp, st ? &st2 : &st);
	}
	if (!st && (end <= 0 || (size_t)end > size))
		st = WRITE_ERROR;
	if (st) {
		free(buf);
		return fits_failed(f->fits, st, err);
	}
	rc = stray_file_open_atomic(&out, f->fits, err);
	if (rc == STRAY_OK) {
		if (fwrite(buf, 1, (size_t)end, out.f) != (size_t)end) {
			stray_file_abort(&out);
			rc = stray_error_at(err, STRAY_EIO, f->fits, 0,
					    "--focal-map", "cannot write");
		} else {
			rc = stray_file_commit(&out, err);
		}
	}
	free(buf);
	return rc;
}

/* PNG with +y up (FITS row 1 is -y): flip the rows. */
static int write_png(const struct focal_map_args *f, const float *img,
		     struct stray_error *err)
{
	size_t nx = (size_t)f->fp.nx, ny = (size_t)f->fp.ny, i;
	float *up = malloc(nx * ny * sizeof(float));
	char msg[256] = "";
	int rc;

	if (!up)
		return stray_error_set(err, STRAY_ENOMEM, "--focal-map-png",
				       "out of memory");
	for (i = 0; i < ny; i++)
		memcpy(up + i * nx, img + (ny - 1 - i) * nx,
		       nx * sizeof(float));
	rc = image_cv_false_colour(f->png, up, ny, nx, 1, 648, msg,
				   sizeof(msg));
	free(up);
	if (rc) {
		stray_error_at(err, STRAY_EIO, f->png, 0, "--focal-map-png",
			       "cannot write");
		stray_error_text(err, msg);
		return STRAY_EIO;
	}
	return STRAY_OK;
}

/* The normalised map (tracer_focal_finish) into img, with the summary. */
static int make_map(struct focal_map_args *f, const struct tracer_result *r,
		    const struct tracer_scene *s, float *img,
		    struct stray_error *err)
{
	size_t n = (size_t)f->fp.nx * f->fp.ny, k, j = f->fp.theta_index;
	struct tracer_focal_spread sp = { 0, NULL, NULL, 0.0, 0.0 };
	double *fr = NULL, *rel = NULL, a_cs, sum = 0.0, p0, s0;
	double *map = malloc(n * sizeof(double));
	int rc = map ? STRAY_OK : STRAY_ENOMEM;

	if (!rc && f->lens_map)
		rc = load_lens_map(f->lens_map, &fr, &rel, &sp.n, err);
	sp.fraction = fr;
	sp.rel_alpha = rel;
	source_point(f, s, r->theta_deg[j], &sp);
	a_cs = M_PI * f->sen.aperture_diameter_mm *
	       f->sen.aperture_diameter_mm / 4.0;
	/* r->theta_deg[0] is 0: cmd_trace adds the reference angle */
	tracer_result_power(r, 0, -1, &p0, &s0);
	if (!rc)
		rc = tracer_focal_finish(&f->fp, r->focal, p0,
					 a_cs, &sp, map, &f->in_field, err);
	for (k = 0; !rc && k < n; k++) {
		img[k] = (float)map[k];
		sum += map[k];
	}
	f->mean = sum / (double)n;
	tracer_result_alpha(r, j, 0, -1, &f->alpha, &f->sigma);
	f->theta_deg = r->theta_deg[j];
	free(map);
	free(fr);
	free(rel);
	if (rc == STRAY_ENOMEM)
		stray_error_set(err, rc, "--focal-map", "out of memory");
	return rc;
}

int focal_map_write(struct focal_map_args *f, const struct tracer_result *r,
		    const struct tracer_scene *s,
		    const struct tracer_trace_opts *o, struct stray_error *err)
{
	size_t n = (size_t)f->fp.nx * f->fp.ny;
	float *img = malloc(n * sizeof(float));
	int rc = img ? STRAY_OK : stray_error_set(err, STRAY_ENOMEM,
				"--focal-map", "out of memory");

	if (!rc && !r->focal)
		rc = stray_error_set(err, STRAY_EINVAL, "--focal-map",
				     "the trace kept no focal-plane sums");
	if (!rc)
		rc = make_map(f, r, s, img, err);
	if (!rc && f->fits)
		rc = write_fits(f, img, o, err);
	if (!rc && f->png)
		rc = write_png(f, img, err);
	f->has_result = !rc;
	free(img);
	return rc;
}
