/*
 * expo.c - automatic exposure and ND selection (thesis §3.2: "exposure is
 * raised until the brightest region is just below saturation; ND filters
 * are stacked on axis and removed one by one off axis").  The peak is
 * scaled proportionally (bias included, so each step undershoots a
 * little and the search converges from below).
 */
#include <math.h>

#include "rig/sweep.h"

#define GUARD_FRAC 0.95		/* above this the frame counts as saturated */
#define ACCEPT_FRAC 0.5

double rig_image_peak3(const struct rig_image *img)
{
	double peak = 0;
	int r, c;

	for (r = 0; r < img->n_rows; r++) {
		const uint16_t *p = img->px + (size_t)r * img->n_cols;

		for (c = 1; c + 1 < img->n_cols; c++) {
			double m = (p[c - 1] + p[c] + p[c + 1]) / 3.0;

			if (m > peak)
				peak = m;
		}
	}
	return peak;
}

static double quantize_us(double t)
{
	return round(t * 1e6) * 1e-6;
}

/* New exposure aiming the peak at target; steps the slot when the
 * exposure leaves [t_min, t_max].  Returns 1 when nothing can change. */
static int retarget(const struct rig_lab *lab, double peak, double *t,
		    int *slot)
{
	const struct rig_sweep_cfg *s = &lab->cfg->sweep;
	const struct rig_wheel_cfg *w = &lab->cfg->wheel;
	double target = s->peak_target * lab->cfg->camera.sat_dn;
	double t_new = *t * target / fmax(peak, 1.0);

	if (t_new > s->t_max_s && *slot > 0) {
		t_new *= w->trans[*slot] / w->trans[*slot - 1];
		--*slot;
	} else if (t_new < s->t_min_s && *slot + 1 < w->n_slots) {
		t_new *= w->trans[*slot] / w->trans[*slot + 1];
		++*slot;
	}
	t_new = quantize_us(fmin(s->t_max_s, fmax(s->t_min_s, t_new)));
	if (t_new == *t)
		return 1;
	*t = t_new;
	return 0;
}

int rig_expo_step(struct rig_lab *lab, struct rig_image *img,
		  double *t_exp_s, int *slot, int *done, struct rig_error *err)
{
	const struct rig_sweep_cfg *s = &lab->cfg->sweep;
	double sat = lab->cfg->camera.sat_dn, peak;
	int rc, last_slot = *slot;

	*done = 0;
	rc = rig_lab_wheel(lab, *slot, err);
	if (rc == RIG_OK)
		rc = rig_lab_capture(lab, *t_exp_s, img, err);
	if (rc != RIG_OK)
		return rc;
	peak = rig_image_peak3(img);
	if (peak >= GUARD_FRAC * sat) {
		if (*t_exp_s > s->t_min_s)
			*t_exp_s = quantize_us(fmax(s->t_min_s, *t_exp_s / 10));
		else if (*slot + 1 < lab->cfg->wheel.n_slots)
			++*slot;
		else
			return rig_error_set(err, RIG_ERANGE,
				"exposure: saturated (peak %.0f DN) at %g s "
				"with the densest ND", peak, *t_exp_s);
		return RIG_OK;
	}
	if (peak >= ACCEPT_FRAC * sat)
		*done = 1;
	else if (retarget(lab, peak, t_exp_s, slot) && last_slot == *slot)
		*done = 1;	/* at t_max with the clearest slot */
	return RIG_OK;
}

int rig_expo_search(struct rig_lab *lab, struct rig_image *img,
		    double *t_exp_s, int *slot, struct rig_error *err)
{
	int it, rc, done = 0;

	for (it = 0; it < RIG_EXPO_ITER_MAX && !done; it++) {
		rc = rig_expo_step(lab, img, t_exp_s, slot, &done, err);
		if (rc != RIG_OK)
			return rc;
	}
	return RIG_OK;
}
