/*
 * path_report.h - the stray-light path report (thesis §5.3): detector
 * power per source angle by the sequence of surface groups it scattered
 * from, as a CSV for callers (diagnose re-weights it) and as the top-N
 * list for people.
 */
#ifndef TRACER_PATH_REPORT_H
#define TRACER_PATH_REPORT_H

#include <stdio.h>

#include "tracer/integrator.h"

struct tracer_path_item {
	size_t theta_index;
	uint64_t seq;
	int n_scatter;
	double alpha;		/* share of alpha(theta) carried */
	double sigma;		/* its standard error (batches) */
	double geom;		/* alpha / prod rho: re-weight by prod rho' */
};

/* Item of a table entry; ref is the angle index of theta = 0. */
void tracer_path_item_of(const struct tracer_result *r,
			 const struct tracer_scene *s,
			 const struct tracer_path_entry *e, size_t ref,
			 struct tracer_path_item *it);

/* "group>group>..." of a key; returns buf. */
char *tracer_path_name(const struct tracer_scene *s, uint64_t seq,
		       char *buf, size_t size);

/* CSV: theta_deg,path,n_scatter,alpha_part,sigma,alpha_per_rho. */
int tracer_paths_write_csv(const struct tracer_result *r,
			   const struct tracer_scene *s, const char *path,
			   struct stray_error *err);

/* The n strongest paths of every angle from index first on. */
void tracer_paths_print_top(const struct tracer_result *r,
			    const struct tracer_scene *s, size_t first, int n,
			    FILE *out);

#endif /* TRACER_PATH_REPORT_H */
