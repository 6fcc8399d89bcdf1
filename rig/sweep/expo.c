/*
 * expo.c - automatic exposure and ND selection (thesis §3.2: "exposure is
 * raised until the brightest region is just below saturation; ND filters
 * are stacked on axis and removed one by one off axis").  The peak is
 * scaled proportionally (bias included, so each step undershoots a
 * little and the search converges from below).
 */
#include <math.h>

#include "rig/sweep.h"

#define EXPO_ITER_MAX 24
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

int rig_expo_search(struct rig_lab *lab, struct rig_image *img,
		    double *t_exp_s, int *slot, struct rig_error *err)
{
	const struct rig_sweep_cfg *s = &lab->cfg->sweep;
	double sat = lab->cfg->camera.sat_dn, t = *t_exp_s, peak = 0;
	int k = *slot, it, rc, last_slot;

	for (it = 0; it < EXPO_ITER_MAX; it++) {
		rc = rig_lab_wheel(lab, k, err);
		if (rc == RIG_OK)
			rc = rig_lab_capture(lab, t, img, err);
		if (rc != RIG_OK)
			return rc;
		peak = rig_image_peak3(img);
		if (peak >= GUARD_FRAC * sat) {
			if (t > s->t_min_s)
				t = quantize_us(fmax(s->t_min_s, t / 10));
			else if (k + 1 < lab->cfg->wheel.n_slots)
				k++;
			else
				return rig_error_set(err, RIG_ERANGE,
					"exposure: saturated (peak %.0f DN) at "
					"%g s with the densest ND", peak, t);
			continue;
		}
		if (peak >= ACCEPT_FRAC * sat)
			break;
		last_slot = k;
		if (retarget(lab, peak, &t, &k) && last_slot == k)
			break;	/* at t_max with the clearest slot */
	}
	*t_exp_s = t;
	*slot = k;
	return RIG_OK;
}
