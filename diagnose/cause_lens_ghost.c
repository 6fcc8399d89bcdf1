/*
 * cause_lens_ghost.c - a ghost of the lens that its table does not hold:
 * a bump in the lens curve over a range of incidence angles (a
 * reflection between lens surfaces reaching the detector only for those
 * angles, thesis §3.4.4).  Post-processing (diagnose/lens.c): the light
 * arriving at the pupil at incidences inside the window - the direct beam
 * when the source is there, scattered light from the vanes whatever the
 * source angle - times the bump, from the per-incidence-bin traces
 * (1 deg bins beyond the lens's field: a ghost inside the field is not
 * resolved).  Only with `--lens`.
 */
#include "diagnose/diag_cause.h"

#define LEVELS 9	/* log10 bump 0.125 to 1.125 */

/* Windows: runs of 1 to 6 consecutive measured angles inside the direct
 * range of the curve, edges half-way to the neighbours. */
static int starts(const double *theta, size_t n,
		  double (*out)[DIAG_PARAMS_MAX], int max)
{
	size_t i, j;
	int k = 0, l;

	for (i = 0; i < n; i++)
		for (j = i; j < n && j < i + 6; j++)
			for (l = 0; l < LEVELS && k < max; l++, k++) {
				out[k][0] = 0.125 + 0.125 * l;
				out[k][1] = i == 0 ? theta[0] - 0.5 :
					0.5 * (theta[i - 1] + theta[i]);
				out[k][2] = j == n - 1 ? theta[n - 1] + 0.5 :
					0.5 * (theta[j] + theta[j + 1]);
			}
	return k;
}

static void apply(const double *p, struct diag_state *s)
{
	s->ghost_log10 = p[0];
	s->ghost_lo_deg = p[1];
	s->ghost_hi_deg = p[2];
}

const struct diag_cause diag_cause_lens_ghost = {
	.name = "lens_ghost",
	.kind = DIAG_POSTPROC,
	.explanation =
	"The lens has a ghost its measured table lacks: for a range of "
	"incidence angles a reflection between its surfaces reaches the "
	"detector, a bump in the lens curve. The system curve rises where "
	"the direct beam still passes the baffle with its angle inside the "
	"range, and wherever scattered light reaches the lens at such "
	"angles (the vanes seen from the pupil), in proportion to how much "
	"does. A lens cause, not the baffle's.",
	.n_params = 3,
	.param = { { "log10_bump", "log10(factor)", 0.0, -1.0, 2.0, 0 },
		   { "theta_lo_deg", "deg", 0.0, -1.0, 91.0, 0 },
		   { "theta_hi_deg", "deg", 0.0, -1.0, 91.0, 0 } },
	.k_bic = 3,
	.apply = apply,
	.start_grid = starts,
	.needs_lens = 1,
};
