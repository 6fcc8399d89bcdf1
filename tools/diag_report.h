/*
 * diag_report.h - `stray diagnose`'s presentation of the diagnosis
 * (diagnose/diag_result.h): in words (diag_report.c), as JSON
 * (diag_json.c, docs/cli.md) and as figures (plot_diag.c, PLplot).
 */
#ifndef STRAY_TOOLS_DIAG_REPORT_H
#define STRAY_TOOLS_DIAG_REPORT_H

#include "diagnose/diag_result.h"
#include "diagnose/diag_surfaces.h"

void diag_report_text(const struct diag_data *d, const struct diag_eval *e,
		      const struct diag_result *r);
/* The surface at fault (NULL: not run), in words and in the JSON. */
void diag_report_surfaces_text(const struct diag_surfaces *s,
			       const char *model);
int diag_report_json_surf(const struct diag_data *d,
			  const struct diag_eval *e,
			  const struct diag_result *r,
			  const struct diag_surfaces *s, const char *model);
int diag_report_json(const struct diag_data *d, const struct diag_eval *e,
		     const struct diag_result *r);
int diag_plot(const char *path, const struct diag_data *d,
	      const struct diag_result *r, struct stray_error *err);

#endif /* STRAY_TOOLS_DIAG_REPORT_H */
