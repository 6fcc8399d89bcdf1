/*
 * design_sweep.h - what `stray sweep` knows of each design once traced:
 * its Sun exclusion angle (thesis §5.1, fig. 5.1) with the interval from
 * alpha -/+ sigma, and alpha at the chosen angles; and the outputs
 * (text table, CSV, JSON, plot) built from them (design_report.c).
 */
#ifndef STRAY_TOOLS_DESIGN_SWEEP_H
#define STRAY_TOOLS_DESIGN_SWEEP_H

#include <stddef.h>

#include "tracer/design_sweep.h"
#include "stray/error.h"

struct sweep_summary {
	const struct design_result *d;
	size_t n;
	const double *at_deg;
	int n_at;
	double alpha_req;
	const char *sensor;
	const char *normalisation;	/* eq. 2.3's k_px: its name, value */
	double k_px;
	/* the detector whose failure modes set alpha_req, and which binds
	 * (docs/detectors.md) */
	const char *detector, *binding;
};

/* Best (smallest finite Sun exclusion angle) and worst; -1 when none. */
void design_best_worst(const struct sweep_summary *s, long *best,
		       long *worst, long *second);

int design_write_csv(const struct sweep_summary *s, const char *path,
		     struct stray_error *err);
void design_print_text(const struct sweep_summary *s);
int design_print_json(const struct sweep_summary *s);
int design_plot(const struct sweep_summary *s, const char *path,
		struct stray_error *err);

#endif /* STRAY_TOOLS_DESIGN_SWEEP_H */
