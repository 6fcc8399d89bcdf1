/*
 * test_focal_map.c - the focal-plane stray-light map (issue 13 item 2)
 * and the per-pixel factor k_px = A_cs / (n_px A_px) from first
 * principles: a Lambertian disk of uniform radiance seen through an ideal
 * lens gives, per pixel, the camera equation E_px = L A_ov cos^4(phi) /
 * f^2 (A_ov: the part of the pupil that sees the disk in that direction),
 * not the power argument of issue 13; its mean over the detector over the
 * traced power ratio alpha = P(theta) / P(0) must be A_cs / A_det.
 */
#include <stdlib.h>
#include <string.h>

#include "tracer/baffle.h"
#include "tracer/focal.h"
#include "tracer/source.h"
#include "tracer_test.h"

/* st16-like (ref4-baffle.md): 2592 x 1944 px of 2.2 um, fov 10 deg over
 * the half-diagonal; f = 3.564 mm / tan(10 deg). */
#define HALF_W_MM (0.5 * 2592 * 2.2e-3)
#define HALF_H_MM (0.5 * 1944 * 2.2e-3)

static struct tracer_focal st16_focal(int nx, int ny, size_t theta_index)
{
	struct tracer_focal fp;

	fp.half_w_mm = HALF_W_MM;
	fp.half_h_mm = HALF_H_MM;
	fp.f_mm = hypot(HALF_W_MM, HALF_H_MM) / tan(10.0 * M_PI / 180.0);
	fp.nx = nx;
	fp.ny = ny;
	fp.theta_index = theta_index;
	return fp;
}

/* Configuration factor, disk a to coaxial parallel disk b at distance h
 * (Siegel and Howell, Thermal Radiation Heat Transfer, app. C). */
static double coaxial_disks_f(double a, double b, double h)
{
	double ra = a / h, rb = b / h;
	double x = 1.0 + (1.0 + rb * rb) / (ra * ra);

	return 0.5 * (x - sqrt(x * x - 4.0 * rb * rb / (ra * ra)));
}

/* The scene: pupil (radius a, z = 0, facing +z, acceptance cone) under a
 * Lambertian disk (radius R, z = h, reflectance rho).  lit_from_below: the
 * beam comes from theta = 180 deg (the disk glows, the pupil sees no
 * direct light); else the disk is moved far aside and the beam comes
 * from above: the open pupil, whose P(0) is the reference power. */
struct glow {
	double a, R, h, rho, cone_deg;
};

static void glow_scene(struct tracer_scene *s, const struct glow *gl,
		       int lit_from_below)
{
	int g;
	uint32_t i;

	tracer_scene_init(s);
	g = tracer_mesh_group(&s->mesh, "disk", NULL);
	test_band(&s->mesh, 0.0, gl->h, gl->R, gl->h, 512, g);
	if (!lit_from_below)	/* out of the way of the on-axis beam */
		for (i = 0; i < s->mesh.n_vert; i++)
			s->mesh.vert[3 * i] += 1000.0f;
	s->material[g].ops = &tracer_brdf_lambert_ops;
	s->material[g].rho = gl->rho;
	test_detector(s, gl->a, v3(0, 0, 0), v3(0, 0, 1));
	s->det.accept_half_angle_deg = gl->cone_deg;
	s->beam.center = v3(0, 0, 0);
	s->beam.normal = v3(0, 0, lit_from_below ? -1.0 : 1.0);
	s->beam.radius_mm = 100.0;
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

static void trace_focal(const struct tracer_scene *s, const double *theta,
			size_t n, uint64_t paths,
			const struct tracer_focal *fp, struct tracer_result *r)
{
	struct tracer_trace_opts o;
	struct stray_error err;

	stray_error_clear(&err);
	tracer_trace_defaults(&o);
	o.theta_deg = theta;
	o.n_theta = n;
	o.n_paths = paths;
	o.threads = 2;
	o.n_batches = 32;
	o.seed = 20261201;
	o.focal = fp;
	assert_int_equal(tracer_trace(s, &o, r, &err), 0);
	assert_non_null(r->focal);
	assert_int_equal(r->focal_slots, tracer_focal_slots(fp));
}

/*
 * Closed form of one cell: the mean over it of E_px / E_src =
 * (rho / pi) A_ov(h tan phi) cos^4(phi) / f^2 (camera equation for an
 * ideal lens: dw = cos^3 dA / f^2, dP = L cos A_ov dw, L = rho E / pi at
 * normal incidence), by a 12 x 12 midpoint rule.
 */
static double cell_closed_form(const struct tracer_focal *fp,
			       const struct glow *gl, int col, int row)
{
	double cw = 2.0 * fp->half_w_mm / fp->nx;
	double ch = 2.0 * fp->half_h_mm / fp->ny, sum = 0.0;
	int i, j, q = 12;

	for (i = 0; i < q; i++)
		for (j = 0; j < q; j++) {
			double x = -fp->half_w_mm + cw * (col + (i + 0.5) / q);
			double y = -fp->half_h_mm + ch * (row + (j + 0.5) / q);
			double t = hypot(x, y) / fp->f_mm;	/* tan phi */
			double c2 = 1.0 / (1.0 + t * t);	/* cos^2 phi */

			sum += disk_overlap(gl->a, gl->R, gl->h * t) * c2 * c2;
		}
	return gl->rho / M_PI * sum / (q * q) / (fp->f_mm * fp->f_mm);
}

/* Per-cell traced E_px / E_src and its standard error over batches:
 * sums / N_b are P_c / (E A_pupil) (integrator.h), times A_pupil / A_cell. */
static void cell_traced(const struct tracer_result *r, size_t cell,
			double scale, double *mean, double *sigma)
{
	double s1 = 0.0, s2 = 0.0;
	int b, nb = r->n_batches;

	for (b = 0; b < nb; b++) {
		double v = r->focal_batch[(size_t)b * r->focal_slots + cell] /
			   (double)r->batch_paths[b] * scale;

		s1 += v;
		s2 += v * v;
	}
	*mean = s1 / nb;
	*sigma = sqrt(fmax(s2 / nb - *mean * *mean, 0.0) / (nb - 1));
}

/*
 * k_px from first principles.  The traced map matches the camera
 * equation cell by cell; the camera equation's mean over the detector is
 * rho F(pupil -> disk) A_p / A_det (its integral is the configuration
 * factor, no k_px in it); and that mean over the traced alpha =
 * P(180) / P(0), with P(0) traced on the open pupil, is A_cs / A_det.
 */
static void test_focal_map_kpx_first_principles(void **state)
{
	const struct glow gl = { 1.0, 7.0, 100.0, 0.5, 6.0 };
	const double th_lit[] = { 180.0 }, th_ref[] = { 0.0 };
	struct tracer_focal fp = st16_focal(36, 27, 0);
	struct tracer_scene s;
	struct tracer_result r, r0;
	size_t n = (size_t)fp.nx * fp.ny, c;
	double a_p = M_PI * gl.a * gl.a, a_det = 4.0 * HALF_W_MM * HALF_H_MM;
	double scale = a_p / (a_det / n), e_cf = 0.0, e_tr = 0.0, var = 0.0;
	double p, sp, p0, sp0, alpha, s_alpha, worst = 0.0, peak;

	(void)state;
	glow_scene(&s, &gl, 1);
	trace_focal(&s, th_lit, 1, 2000000, &fp, &r);
	tracer_scene_free(&s);
	assert_true(r.focal[n] == 0.0);	/* the disk is in the field */
	peak = cell_closed_form(&fp, &gl, fp.nx / 2, fp.ny / 2);
	for (c = 0; c < n; c++) {
		double cf = cell_closed_form(&fp, &gl, (int)(c % fp.nx),
					     (int)(c / fp.nx)), m, sg, z;

		cell_traced(&r, c, scale, &m, &sg);
		e_cf += cf / n;
		e_tr += m / n;
		var += sg * sg / ((double)n * n);
		z = fabs(m - cf) / (sg + 2e-3 * peak);
		worst = fmax(worst, z);
	}
	if (getenv("TRACER_TEST_VERBOSE"))
		print_message("worst cell %.2f sigma\n", worst);
	assert_true(worst < 5.0);	/* every cell within 5 sigma */
	/* the camera equation integrates to the configuration factor */
	assert_near(e_cf, gl.rho * coaxial_disks_f(gl.a, gl.R, gl.h) * a_p /
		    a_det, 3e-4 * e_cf);
	assert_near(e_tr, e_cf, 4.0 * sqrt(var) + 3e-4 * e_cf);
	/* alpha = P(180) / P(0): P(0) from the open pupil under the beam */
	glow_scene(&s, &gl, 0);
	test_trace(&s, th_ref, 1, 20000, 2, &r0);
	tracer_scene_free(&s);
	tracer_result_power(&r, 0, -1, &p, &sp);
	tracer_result_power(&r0, 0, -1, &p0, &sp0);
	alpha = p / p0;
	s_alpha = alpha * hypot(sp / p, sp0 / p0);
	if (getenv("TRACER_TEST_VERBOSE"))
		print_message("alpha = %.6g +- %.2g\n", alpha, s_alpha);
	/* k_px: per-pixel irradiance ratio over power ratio = A_cs / A_det */
	assert_near(e_cf / alpha, a_p / a_det, 4.0 * s_alpha / alpha *
		    (a_p / a_det) + 3e-4 * a_p / a_det);
	/* and the traced map's own mean over the traced alpha */
	assert_near(e_tr / alpha, a_p / a_det, (4.0 * s_alpha / alpha +
		    4.0 * sqrt(var) / e_tr) * (a_p / a_det) +
		    3e-4 * a_p / a_det);
	tracer_result_free(&r);
	tracer_result_free(&r0);
}

static void ref4_scene(struct tracer_scene *s)
{
	struct tracer_baffle b;

	tracer_scene_init(s);
	tracer_baffle_ref4(&b);
	assert_int_equal(tracer_baffle_build(&b, s, NULL), 0);
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

/*
 * The map's mean is k_px alpha (issue 13): in the field (5 deg), beyond it
 * spread uniformly and by a lens region map (40 deg); the region map puts
 * its brightest level nearest the source side and conserves the power.
 */
static void test_focal_map_mean_is_kpx_alpha(void **state)
{
	const double th[] = { 0.0, 5.0, 40.0 };
	const double fr[] = { 0.5, 0.3, 0.2 }, rel[] = { 0.2, 1.0, 3.0 };
	const double a_cs = M_PI * 6.5 * 6.5;	/* st16-like, d = 13 mm */
	const double k_px = a_cs / (4.0 * HALF_W_MM * HALF_H_MM);
	struct tracer_scene s;
	size_t j, n, k;

	(void)state;
	ref4_scene(&s);
	for (j = 1; j < 3; j++) {
		struct tracer_focal fp = st16_focal(72, 54, j);
		struct tracer_focal_spread sp[2] = {
			{ 0, NULL, NULL, 0.0, 0.0 }, { 3, fr, rel, 0.0, 0.0 }
		};
		struct frame f = frame_from_normal(s.det.normal);
		struct tracer_result r;
		double *map, alpha, sg, in_field, p0, s0;
		int m;

		trace_focal(&s, th, 3, 200000, &fp, &r);
		n = (size_t)fp.nx * fp.ny;
		map = malloc(n * sizeof(double));
		assert_non_null(map);
		tracer_result_alpha(&r, j, 0, -1, &alpha, &sg);
		tracer_result_power(&r, 0, -1, &p0, &s0);
		assert_true(alpha > 0.0);
		assert_true(tracer_focal_point(&fp, &f,
			tracer_source_dir(th[j]), &sp[1].src_x_mm,
			&sp[1].src_y_mm));
		for (m = 0; m < 2; m++) {
			double mean = 0.0, near, far;

			assert_int_equal(tracer_focal_finish(&fp, r.focal,
				p0, a_cs, &sp[m], map,
				&in_field, NULL), 0);
			for (k = 0; k < n; k++)
				mean += map[k] / n;
			assert_near(mean, k_px * alpha, 1e-9 * k_px * alpha +
				    1e-3 * k_px * sg);
			if (j == 1)
				assert_true(in_field > 0.99);
			if (j != 2 || m == 0)
				continue;
			assert_true(in_field < 0.5);
			/* the source (40 deg) images above the detector:
			 * the top row outshines the bottom row */
			near = map[n - (size_t)fp.nx / 2];
			far = map[(size_t)fp.nx / 2];
			assert_true(near > 2.0 * far);
		}
		free(map);
		tracer_result_free(&r);
	}
	tracer_scene_free(&s);
}

/* A source inside the field lands where the ideal lens puts it:
 * y = f tan(theta) on the sweep axis, x = 0. */
static void test_focal_map_source_lands_at_f_tan(void **state)
{
	const double th[] = { 0.0, 2.5, 4.0 };
	struct tracer_scene s;
	size_t j;

	(void)state;
	ref4_scene(&s);
	for (j = 0; j < 3; j++) {
		struct tracer_focal fp = st16_focal(72, 54, j);
		struct tracer_result r;
		size_t n = (size_t)fp.nx * fp.ny, k, best = 0;
		double y = fp.f_mm * tan(th[j] * M_PI / 180.0), total = 0.0;
		long col, row;

		trace_focal(&s, th, 3, 20000, &fp, &r);
		for (k = 0; k < n; k++) {
			total += r.focal[k];
			if (r.focal[k] > r.focal[best])
				best = k;
		}
		/* cell of (0, f tan theta), computed here, not by focal.c */
		col = (long)floor(0.5 * fp.nx);
		row = (long)floor((y / fp.half_h_mm + 1.0) * 0.5 * fp.ny);
		assert_int_equal(best, (size_t)(row * fp.nx + col));
		assert_true(r.focal[best] > 0.99 * (total + r.focal[n]));
		tracer_result_free(&r);
	}
	tracer_scene_free(&s);
}

/* Direction to cell, and the outside slot past the detector's edge. */
static void test_focal_map_cells(void **state)
{
	struct tracer_focal fp = st16_focal(72, 54, 0);
	struct frame f = frame_from_normal(v3(0, 0, 1));
	size_t out = tracer_focal_slots(&fp) - 1;
	double t_edge = HALF_H_MM / fp.f_mm, x, y;

	(void)state;
	assert_int_equal(tracer_focal_check(&fp, NULL), 0);
	assert_int_equal(tracer_focal_cell(&fp, &f, v3(0, 0, 1)),
			 (size_t)(27 * 72 + 36));
	assert_int_equal(tracer_focal_cell(&fp, &f,
		v3_norm(v3(0, 0.999 * t_edge, 1))), (size_t)(53 * 72 + 36));
	assert_int_equal(tracer_focal_cell(&fp, &f,
		v3_norm(v3(0, 1.001 * t_edge, 1))), out);
	assert_int_equal(tracer_focal_cell(&fp, &f, tracer_source_dir(40.0)),
			 out);
	assert_int_equal(tracer_focal_cell(&fp, &f, v3(0, 0, -1)), out);
	assert_true(tracer_focal_point(&fp, &f, v3_norm(v3(1, 0, 10)),
				       &x, &y));
	assert_near(x, 0.1 * fp.f_mm, 1e-12);
	assert_near(y, 0.0, 1e-12);
	fp.f_mm = 0.0;
	assert_int_not_equal(tracer_focal_check(&fp, NULL), 0);
}

/* No P(0), no map: a named error, not a division by zero. */
static void test_focal_map_needs_p0(void **state)
{
	struct tracer_focal fp = st16_focal(2, 2, 0);
	double sums[5] = { 1, 1, 1, 1, 0 }, map[4], in_field;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(tracer_focal_finish(&fp, sums, 0.0, 1.0, NULL, map,
					     &in_field, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "P(0)");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_focal_map_cells),
		cmocka_unit_test(test_focal_map_needs_p0),
		cmocka_unit_test(test_focal_map_source_lands_at_f_tan),
		cmocka_unit_test(test_focal_map_mean_is_kpx_alpha),
		cmocka_unit_test(test_focal_map_kpx_first_principles),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
