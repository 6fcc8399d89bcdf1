/*
 * vlab.c - the virtual lab (vlab.h).  Deterministic given the frame seed:
 * a splitmix64 stream per frame drives the shot and read noise, and hot
 * pixels come from a hash of (seed, row, column), so they stay put from
 * frame to frame as real ones do.
 */
#include <math.h>
#include <stddef.h>

#include "rig/vlab.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define DETECTOR_COLS 2592

void rig_vlab_defaults(struct rig_vlab_cfg *c)
{
	static const double bias[RIG_VLAB_CHANNELS] = {
		100, 104, 98, 102, 110, 96, 106, 101
	};
	int i;

	c->lamp_rate_dn_s = 4.0e5;
	c->lamp_drift_per_h = 0.0;
	c->lens_scale_deg = 6.0;
	c->lens_floor = 2e-3;
	c->gradient = 0.3;
	c->n_ghosts = 1;
	c->ghost[0] = (struct rig_ghost){ 2e-3, 1000, 8.0, 12.0, 12.0, 6.0 };
	c->ambient_dn_s = 20.0;
	c->atmos_frac = 1e-5;
	c->dark_dn_s = 2.0;
	for (i = 0; i < RIG_VLAB_CHANNELS; i++)
		c->bias_dn[i] = bias[i];
	c->read_noise_dn = 1.5;
	c->gain_e_per_dn = 2.0;
	c->hot_frac = 2e-3;
	c->hot_dn_s = 300.0;
	c->sat_dn = 4095;
	c->seed = 7;
}

int rig_vlab_channel(int row, int col)
{
	return (row & 1) * 4 + (col & 3);
}

static uint64_t splitmix(uint64_t *s)
{
	uint64_t z = (*s += 0x9E3779B97F4A7C15ull);

	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

static double uniform(uint64_t *s)
{
	return ((splitmix(s) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double gauss(uint64_t *s)
{
	/* Box-Muller; one of the pair is enough here. */
	return sqrt(-2.0 * log(uniform(s))) * cos(2 * PI * uniform(s));
}

/* Poisson deviate: Knuth's product method for small means, the normal
 * approximation (eq. 2.4-2.6) above 30. */
static double poisson(uint64_t *s, double mean)
{
	double l, p = 1.0;
	int k = 0;

	if (mean <= 0)
		return 0;
	if (mean > 30)
		return fmax(0.0, floor(mean + sqrt(mean) * gauss(s) + 0.5));
	l = exp(-mean);
	do {
		k++;
		p *= uniform(s);
	} while (p > l && k < 1000);
	return k - 1;
}

static int is_hot(const struct rig_vlab_cfg *c, int row, int col)
{
	uint64_t s = c->seed ^ ((uint64_t)row << 32) ^ (uint64_t)col;

	return uniform(&s) < c->hot_frac;
}

/* Lens response on axis of the beam: cos(theta) projected aperture times
 * a falling scatter law with a floor. */
static double lens_base(const struct rig_vlab_cfg *c, double theta_deg)
{
	double a = fabs(theta_deg);

	return cos(a * DEG) * ((1 - c->lens_floor) *
			       exp(-a / c->lens_scale_deg) + c->lens_floor);
}

double rig_vlab_direct_rate(const struct rig_vlab_cfg *c, double theta_deg,
			    int row, int col)
{
	double x = (col - DETECTOR_COLS / 2.0) / (DETECTOR_COLS / 2.0);
	double r = lens_base(c, theta_deg) *
		   (1 + c->gradient * sin(theta_deg * DEG) * x);
	int g;

	(void)row;	/* off-axis gradients run along rows (thesis §3.3) */
	for (g = 0; g < c->n_ghosts; g++) {
		const struct rig_ghost *gh = &c->ghost[g];
		double dt = (theta_deg - gh->theta_c_deg) / gh->theta_w_deg;
		double dc = (col - gh->col_at0 - gh->px_per_deg * theta_deg) /
			    gh->sigma_px;

		r += gh->amp * exp(-0.5 * (dt * dt + dc * dc));
	}
	return c->lamp_rate_dn_s * r;
}

double rig_vlab_lens_alpha(const struct rig_vlab_cfg *c, double theta_deg,
			   const uint16_t *rows, int n_rows, int col0,
			   int n_cols)
{
	double p = 0, p0 = 0;
	int r, col;

	for (r = 0; r < n_rows; r++)
		for (col = col0; col < col0 + n_cols; col++) {
			p += rig_vlab_direct_rate(c, theta_deg, rows[r], col);
			p0 += rig_vlab_direct_rate(c, 0, rows[r], col);
		}
	return p / p0;	/* eq. 3.12 */
}

double rig_vlab_lamp_factor(const struct rig_vlab_cfg *c, double t_s)
{
	return 1 + c->lamp_drift_per_h * t_s / 3600.0;
}

/* Light rate of one pixel in DN/s, before the ND and shutter. */
static double light_rate(const struct rig_vlab_cfg *c,
			 const struct rig_vlab_state *st, int row, int col)
{
	double lamp = rig_vlab_lamp_factor(c, st->t_s);
	double r;

	if (!st->lamp_on)
		return 0;
	/* eq. 3.2: I_amb = f(theta, t_exp, alpha_nd), the beam blocked */
	r = c->ambient_dn_s + c->atmos_frac * c->lamp_rate_dn_s * lamp;
	/* eq. 3.1: I_ful = f(theta, t_exp, alpha_nd), direct light added */
	if (!st->beam_blocked)
		r += lamp * rig_vlab_direct_rate(c, st->theta_deg, row, col);
	return r;
}

void rig_vlab_render(const struct rig_vlab_cfg *c,
		     const struct rig_vlab_state *st, const uint16_t *rows,
		     int n_rows, int col0, int n_cols, uint64_t frame_seed,
		     uint16_t *px)
{
	uint64_t s = frame_seed * 0x2545F4914F6CDD1Dull + c->seed;
	int r, k;

	for (r = 0; r < n_rows; r++)
		for (k = 0; k < n_cols; k++) {
			int row = rows[r], col = col0 + k;
			double rate = c->dark_dn_s, e, dn; /* eq. 3.3: D */

			if (st->shutter_open)
				rate += st->nd_trans * light_rate(c, st, row,
								   col);
			if (is_hot(c, row, col))
				rate += c->hot_dn_s;
			e = poisson(&s, rate * st->t_exp_s * c->gain_e_per_dn);
			dn = e / c->gain_e_per_dn +
			     c->bias_dn[rig_vlab_channel(row, col)] +
			     c->read_noise_dn * gauss(&s);
			dn = floor(dn + 0.5);
			if (dn < 0)
				dn = 0;
			if (dn > c->sat_dn)
				dn = c->sat_dn;
			px[(size_t)r * n_cols + k] = (uint16_t)dn;
		}
}
