/*
 * reduce_report.h - what `stray reduce` writes besides the curve CSV: the
 * Zemax TABLE coating (COATING.DAT syntax), the --json object, the text
 * summary and the plots (figs. 3.7-3.9).
 */
#ifndef STRAY_TOOLS_REDUCE_REPORT_H
#define STRAY_TOOLS_REDUCE_REPORT_H

#include <cJSON.h>
#include <stdio.h>

#include "stray/error.h"
#include "stray/reduce_sweep.h"

/* Name of the ghost track i: "A", "B", ... (thesis fig. 3.9). */
const char *reduce_track_name(size_t i);

/*
 * The curve as an OpticStudio TABLE coating: one ANGL block per angle,
 * one WAVE line (Rs Rp Ts Tp = 0 0 alpha alpha).  name: up to 32 letters,
 * digits or '_'.
 */
int reduce_write_zemax(const char *path, const char *name, double wave_um,
		       const struct stray_reduce_sweep_result *r, struct stray_error *err);

/* The J image at r->image_theta_deg as an FDR region map CSV
 * (fraction,rel_alpha; `stray fdr --map`), n_regions quantile regions. */
int reduce_write_map(const char *path, unsigned n_regions,
		     const struct stray_reduce_sweep_result *r, struct stray_error *err);

/* The --json object (cli.md: `ghosts`, each with theta_deg and column). */
cJSON *reduce_json(const struct stray_reduce_sweep_result *r,
		   const char *out_path);

/* Human-readable summary on out. */
/* One line on out when the sweep in dir is live or unfinished
 * (reduce_partial.c); the reduction goes on. */
void reduce_warn_partial(const char *dir);

void reduce_print(FILE *out, const struct stray_reduce_sweep_result *r,
		  const char *out_path);

/* alpha.png (fig. 3.7), profiles.png (fig. 3.9), ghosts.png, j.png (fig.
 * 3.8, when r->image) under dir. */
int reduce_plots(const char *dir, const struct stray_reduce_sweep_result *r,
		 struct stray_error *err);

#endif /* STRAY_TOOLS_REDUCE_REPORT_H */
