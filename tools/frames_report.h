/*
 * frames_report.h - what `stray frames` prints (frames_report.c).
 */
#ifndef STRAY_TOOLS_FRAMES_REPORT_H
#define STRAY_TOOLS_FRAMES_REPORT_H

#include <cJSON.h>

#include "frames/frames_job.h"
#include "frames/frames_lost.h"

/* "lost_stars": per detector, the bins with stars. */
void frames_lost_json(const struct frames_lost *l, cJSON *o);

/* The same as text lines (bins of >= 20 stars). */
void frames_lost_print(const struct frames_lost *l);

/* The run's results on stdout as JSON: the top-level keys are the
 * thesis detector's (detector 1) or the threshold detector's (0). */
int frames_print_json(const struct frames_job *st, int detector);

/* The same as text lines. */
void frames_print_text(const struct frames_job *st);

#endif /* STRAY_TOOLS_FRAMES_REPORT_H */
