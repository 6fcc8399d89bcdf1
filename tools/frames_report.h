/*
 * frames_report.h - what `stray frames` prints (frames_report.c).
 */
#ifndef STRAY_TOOLS_FRAMES_REPORT_H
#define STRAY_TOOLS_FRAMES_REPORT_H

#include <cJSON.h>

#include "frames/frames_lost.h"

/* "lost_stars": per detector, the bins with stars. */
void frames_lost_json(const struct frames_lost *l, cJSON *o);

/* The same as text lines (bins of >= 20 stars). */
void frames_lost_print(const struct frames_lost *l);

#endif /* STRAY_TOOLS_FRAMES_REPORT_H */
