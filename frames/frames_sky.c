/*
 * frames_sky.c - the real sky for `stray frames` (frames_sky.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "frames/frames_sky.h"
#include "stray/aem.h"
#include "stray/colour.h"
#include "stray/file.h"
#include "stray/sensor_geom.h"
#include "stray/starcat.h"

#define DEG (3.14159265358979323846 / 180.0)

int frames_sky_stars(const char *path, const struct stray_sensor *s,
		     const double q_ib[4], double epoch_jyear, int col0,
		     int row0, int cols, int rows, double mag_max, double f0_e,
		     struct stray_star *out, size_t max, size_t *n,
		     struct stray_error *err)
{
	struct stray_starcat c;
	struct stray_colour col;
	struct stray_camera cam;
	struct stray_cat_star *cone;
	size_t n_cone;
	int rc;

	*n = 0;
	if ((rc = stray_starcat_load(path, &c, err)) != STRAY_OK)
		return rc;
	if ((rc = stray_colour_for_qe(&col, s->qe, err)) != STRAY_OK ||
	    !(cone = malloc(max * sizeof(*cone)))) {
		stray_starcat_free(&c);
		return rc ? rc : stray_error_set(err, STRAY_ENOMEM, "frames",
						 "out of memory");
	}
	stray_q_dcm(q_ib, cam.m_ih);
	cam.f_px = stray_sensor_focal_length_mm(s) / (s->pixel_pitch_um * 1e-3);
	cam.cx = 0.5 * s->pixels_x - col0;
	cam.cy = 0.5 * s->pixels_y - row0;
	stray_starcat_cone(&c, epoch_jyear, cam.m_ih[2],
			   atan(0.5 * hypot(s->pixels_x, s->pixels_y) /
				cam.f_px) / DEG + 0.5,
			   mag_max, cone, max, &n_cone);
	stray_colour_apply(&col, cone, n_cone);
	*n = stray_camera_stars(&cam, cone, n_cone, cols, rows, 8.0, f0_e,
				out, max);
	free(cone);
	stray_starcat_free(&c);
	return STRAY_OK;
}

int frames_sky_truth_write(const char *path, const struct stray_star *st,
			   size_t n, int frames, struct stray_error *err)
{
	struct stray_file_out o;
	size_t i;
	int k, rc;

	if ((rc = stray_file_open_atomic(&o, path, err)) != STRAY_OK)
		return rc;
	fprintf(o.f, "frame,x_px,y_px,v_mag,electrons\n");
	for (k = 0; k < frames; k++)
		for (i = 0; i < n; i++)
			fprintf(o.f, "%d,%.4f,%.4f,%.4f,%.6g\n", k, st[i].x,
				st[i].y, st[i].mag, st[i].photons_e);
	return stray_file_commit(&o, err);
}
