/*
 * cause_light_leak.c - light entering by a path the model does not have
 * (a gap, a hole, a translucent part) over a limited range of angles
 * (thesis §4: the second baffle's raised floor between 20 and 35 deg).
 * Post-processing: an additive level inside an angle window with soft
 * edges.
 */
#include "diagnose/diag_cause.h"

/* Starting windows: every run of consecutive measured angles i..j short
 * of the whole curve (that would be a floor), edges half-way to the
 * neighbours; levels on a quarter-decade grid, refined by the fit. */
#define LEVELS 17	/* log10 level -7 to -3, quarter decades */

static int starts(const double *theta, size_t n,
		  double (*out)[DIAG_PARAMS_MAX], int max)
{
	size_t i, j, stride = n / 24 + 1;
	int k = 0, l;

	for (i = 0; i < n; i += stride)
		for (j = i; j < n; j += stride) {
			size_t jj = j + stride - 1 < n ? j + stride - 1 : n - 1;

			if (i == 0 && jj == n - 1)
				continue;
			for (l = 0; l < LEVELS && k < max; l++, k++) {
				out[k][0] = -7.0 + 0.25 * l;
				out[k][1] = i == 0 ? theta[0] - 0.5 :
					0.5 * (theta[i - 1] + theta[i]);
				out[k][2] = jj == n - 1 ? theta[n - 1] + 0.5 :
					0.5 * (theta[jj] + theta[jj + 1]);
			}
		}
	return k;
}

static void apply(const double *p, struct diag_state *s)
{
	s->leak_log10 = p[0];
	s->leak_lo_deg = p[1];
	s->leak_hi_deg = p[2];
}

const struct diag_cause diag_cause_light_leak = {
	.name = "light_leak",
	.kind = DIAG_POSTPROC,
	.explanation =
	"Light reaches the detector by a path the model does not contain - "
	"a gap between tube and mount, an unsealed screw hole, a "
	"translucent part - open only for a range of source angles. It "
	"adds a roughly constant level inside that window and nothing "
	"outside it.",
	.n_params = 3,
	.param = { { "log10_level", "log10(alpha)", -12.0, -9.0, -3.0, 4 },
		   { "theta_lo_deg", "deg", 0.0, -1.0, 91.0, 0 },
		   { "theta_hi_deg", "deg", 0.0, -1.0, 91.0, 0 } },
	.k_bic = 3,
	.apply = apply,
	.start_grid = starts,
};
