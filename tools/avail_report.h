/*
 * avail_report.h - what `stray availability` prints and plots of a
 * mission flown by libmission (mission/avail_mission.h): avail_report.c.
 */
#ifndef STRAY_TOOLS_AVAIL_REPORT_H
#define STRAY_TOOLS_AVAIL_REPORT_H

#include "mission/avail_mission.h"

/* The plots of --plot PREFIX: timeline, false stars, a sky plot per head. */
int mission_plot(const struct mission_args *a, const struct mission *m,
		 struct stray_error *err);

/* The summary on stdout, text or --json; the exit code. */
int mission_summary(const struct mission_args *a, const struct mission *m);

#endif /* STRAY_TOOLS_AVAIL_REPORT_H */
