/*
 * frames_plot.h - the validation figure of `stray frames` from the CSV
 * scripts/validate-frames.sh writes (columns model_fdr, measured_thesis,
 * sigma_thesis, extended_thesis, measured_threshold, sigma_threshold,
 * extended_threshold).
 */
#ifndef STRAY_TOOLS_FRAMES_PLOT_H
#define STRAY_TOOLS_FRAMES_PLOT_H

#include "stray/error.h"

int frames_plot_validation(const char *csv, const char *png,
			   struct stray_error *err);

#endif /* STRAY_TOOLS_FRAMES_PLOT_H */
