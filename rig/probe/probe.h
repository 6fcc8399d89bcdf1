/*
 * probe.h - strayrig-probe's parts: one line per device (probe.c) and the
 * INDI lab's check (probe_indi.c).
 */
#ifndef RIG_PROBE_H
#define RIG_PROBE_H

#include "rig/config.h"
#include "rig/status.h"

/* "<dev> ok: <what>" or "<dev> FAILED: <err>", counted. */
void probe_result(const char *dev, int rc, const struct rig_error *err,
		  const char *what);

/* The lab of an "indi" config, device by device, nothing moved. */
void probe_indi(const struct rig_config *cfg);

#endif /* RIG_PROBE_H */
