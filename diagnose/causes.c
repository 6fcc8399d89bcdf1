/*
 * causes.c - the registry of model extensions, in the order of
 * ../shared/docs/cli.md; a new cause is one file plus one line here.
 */
#include <math.h>
#include <string.h>

#include "diagnose/diag_cause.h"

extern const struct diag_cause diag_cause_reflectance,
	diag_cause_knife_edge_radius, diag_cause_abg_scatter,
	diag_cause_acceptance_cone, diag_cause_angle_offset,
	diag_cause_pivot_offset, diag_cause_floor, diag_cause_light_leak,
	diag_cause_bevel_face, diag_cause_scale,
	diag_cause_spectral_slope, diag_cause_beam_divergence,
	diag_cause_beam_profile, diag_cause_lens_scale, diag_cause_lens_ghost;

const struct diag_cause *const diag_causes[] = {
	&diag_cause_reflectance,
	&diag_cause_knife_edge_radius,
	&diag_cause_abg_scatter,
	&diag_cause_acceptance_cone,
	&diag_cause_angle_offset,
	&diag_cause_pivot_offset,
	&diag_cause_floor,
	&diag_cause_light_leak,
	&diag_cause_bevel_face,
	&diag_cause_scale,
	&diag_cause_spectral_slope,
	&diag_cause_beam_divergence,
	&diag_cause_beam_profile,
	&diag_cause_lens_scale,
	&diag_cause_lens_ghost,
	NULL
};

const struct diag_cause *diag_cause_find(const char *name)
{
	int i;

	for (i = 0; diag_causes[i]; i++)
		if (strcmp(diag_causes[i]->name, name) == 0)
			return diag_causes[i];
	return NULL;
}

void diag_state_nominal(struct diag_state *s)
{
	memset(s, 0, sizeof(*s));
	s->reflectance = NAN;
	s->geo[DIAG_GEO_EDGE_RADIUS] = NAN;	/* the scene's own */
	s->geo[DIAG_GEO_ACCEPT] = NAN;
	s->geo[DIAG_GEO_BEVEL_UPPER] = NAN;
	s->geo[DIAG_GEO_ABG_G] = NAN;
	s->geo[DIAG_GEO_PIVOT] = NAN;
	s->leak_log10 = -INFINITY;
	s->ghost_log10 = -INFINITY;
}
