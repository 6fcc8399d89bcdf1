/*
 * lab_check.c - the config checked against what the devices report, once
 * they are open and the lines safe, before anything moves (lab.h).  One
 * wrong value (a 14-bit saturation level on a 12-bit camera) otherwise
 * gives a whole sweep of clipped frames and a flat curve with no warning:
 * the exposure search aims at a level the ADC never reaches.
 */
#include <stdio.h>
#include <stdlib.h>

#include "rig/lab.h"

/* The wheel's own slot count must cover every transmission listed. */
static int check_wheel(struct rig_lab *lab, struct rig_error *err)
{
	int n = 0, rc = lab->ops->wheel_count(lab, &n, err);

	if (rc != RIG_OK)
		return rc;
	if (n < lab->cfg->wheel.n_slots)
		return rig_error_set(err, RIG_EINVAL,
			"%s: wheel.trans: lists %d slots but the wheel "
			"reports %d; list one transmission per slot the "
			"wheel has", lab->cfg->path[0] ? lab->cfg->path
						       : "config",
			lab->cfg->wheel.n_slots, n);
	return RIG_OK;
}

/* One dark frame (shutter closed) at an exposure of the plan: its
 * header gives the ADC width, and the camera must echo the exposure and
 * the window asked for. */
static int test_frame(struct rig_lab *lab, double t_s, struct rig_image *img,
		      const char *key, struct rig_error *err)
{
	const char *name = lab->cfg->path[0] ? lab->cfg->path : "config";
	int rc = lab->ops->capture(lab, t_s, img, err);

	if (rc == RIG_EPROTO)
		return rig_error_set(err, RIG_EINVAL,
			"%s: camera: a %g s test frame did not come back as "
			"asked (window %d rows x %d columns from column %d, "
			"sweep.%s %g s): the camera does not support it; "
			"check camera.rows, camera.n_cols, camera.col0 and "
			"the exposure range", name, t_s, lab->cfg->camera.n_rows,
			lab->cfg->camera.n_cols, lab->cfg->camera.col0, key,
			t_s);
	return rc;
}

static int check_camera(struct rig_lab *lab, struct rig_error *err)
{
	const struct rig_config *cfg = lab->cfg;
	const char *name = cfg->path[0] ? cfg->path : "config";
	struct rig_image img;
	long max_dn;
	int rc;

	img.px = malloc((size_t)cfg->camera.n_rows * cfg->camera.n_cols *
			sizeof(*img.px));
	if (!img.px)
		return rig_error_set(err, RIG_ENOMEM, "camera: no memory");
	rc = test_frame(lab, cfg->sweep.t_min_s, &img, "t_min_s", err);
	if (rc == RIG_OK)
		rc = test_frame(lab, cfg->sweep.t_max_s, &img, "t_max_s", err);
	free(img.px);
	if (rc != RIG_OK)
		return rc;
	if (img.bits < 1 || img.bits > 16)
		return rig_error_set(err, RIG_EPROTO,
			"camera: reports a %d-bit ADC (expected 1-16)",
			img.bits);
	max_dn = (1L << img.bits) - 1;
	if (cfg->camera.sat_dn > max_dn)
		return rig_error_set(err, RIG_EINVAL,
			"%s: camera.sat_dn: %d DN is above what the camera's "
			"%d-bit ADC can give (%ld DN): frames would clip at "
			"%ld while their SATLEVEL says %d; set camera.sat_dn "
			"to at most %ld", name, cfg->camera.sat_dn, img.bits,
			max_dn, max_dn, cfg->camera.sat_dn, max_dn);
	return RIG_OK;
}

int rig_lab_check(struct rig_lab *lab, struct rig_error *err)
{
	int rc = check_wheel(lab, err);

	return rc == RIG_OK ? check_camera(lab, err) : rc;
}
