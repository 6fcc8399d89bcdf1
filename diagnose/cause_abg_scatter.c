/*
 * cause_abg_scatter.c - the coating scatters forward (ABg, Harvey) rather
 * than uniformly (Lambertian).  Same reflectance, a lobe around the
 * specular direction: re-traced on a grid of slopes g (B fixed, A set so
 * the normal-incidence integrated scatter equals the Lambertian rho).
 */
#include "diagnose/diag_cause.h"

static const double nodes[] = { 0.0, 1.0, 2.0, 3.0 };

static void apply(const double *p, struct diag_state *s)
{
	s->geo[DIAG_GEO_ABG_G] = p[0];
}

const struct diag_cause diag_cause_abg_scatter = {
	.name = "abg_scatter",
	.kind = DIAG_RETRACE,
	.explanation =
	"The interior surfaces scatter preferentially around the specular "
	"direction (an ABg lobe, BSDF = A / (B + |beta - beta0|^g)) instead "
	"of uniformly. Worn or glossy anodise does this. Light grazing the "
	"vanes and the tube then continues forward instead of being spread, "
	"which redistributes stray light between angles: more where a "
	"specular-like bounce leads to the pupil, less elsewhere. g = 0 is "
	"the Lambertian design; B = 0.01.",
	.n_params = 1,
	.param = { { "g", "1", 0.0, 0.0, 3.0, 3 } },
	.k_bic = 1,
	.apply = apply,
	.geo_axis = DIAG_GEO_ABG_G,
	.nodes = nodes,
	.n_nodes = (int)(sizeof(nodes) / sizeof(nodes[0])),
	.needs_baffle = 0,
};
