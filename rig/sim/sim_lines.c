/*
 * sim_lines.c - device side of the GPIO lines (shutter, beam block,
 * lamp): physical levels, set and read back.  A stall fault makes the
 * line driver ignore a write, which the driver's read-back catches.
 */
#include <string.h>

#include "rig/sim_devices.h"
#include "rig/status.h"

void rig_sim_lines_init(struct sim_lines *l, const struct rig_sim_core *core)
{
	int i;

	/* Power-on levels: every line inactive... which for an active-low
	 * line means physically high. */
	for (i = 0; i < RIG_LINE_COUNT; i++)
		l->level[i] = core->cfg->lines[i].active_low ? 1 : 0;
}

int rig_sim_lines_open(struct sim_lines *l, struct rig_sim_core *core,
		       const struct rig_gpio_id *id, int *line)
{
	const struct rig_line_cfg *lc = core->cfg->lines;
	int i, rc;

	for (i = 0; i < RIG_LINE_COUNT; i++)
		if (strcmp(id->line, lc[i].line) == 0 &&
		    strcmp(id->chip, lc[i].chip) == 0) {
			rc = rig_sim_core_open(core, RIG_DEV_GPIO);
			if (rc != RIG_OK)
				return rc;
			l->level[i] = id->initial ? 1 : 0;
			*line = i;
			return RIG_OK;
		}
	return RIG_EDISCONNECT;
}

int rig_sim_lines_set(struct sim_lines *l, struct rig_sim_core *core,
		      int line, int value)
{
	if (core->gone[RIG_DEV_GPIO])
		return RIG_EDISCONNECT;
	/* A stalled line driver ignores the write (read-back catches it). */
	if (rig_sim_core_event(core, RIG_DEV_GPIO, NULL) != RIG_FAULT_STALL)
		l->level[line] = value ? 1 : 0;
	return core->gone[RIG_DEV_GPIO] ? RIG_EDISCONNECT : RIG_OK;
}

int rig_sim_lines_get(const struct sim_lines *l,
		      const struct rig_sim_core *core, int line, int *value)
{
	if (core->gone[RIG_DEV_GPIO])
		return RIG_EDISCONNECT;
	*value = l->level[line];
	return RIG_OK;
}

int rig_sim_lines_logical(const struct sim_lines *l,
			  const struct rig_sim_core *core, int line)
{
	return l->level[line] ^ (core->cfg->lines[line].active_low ? 1 : 0);
}
