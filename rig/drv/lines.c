/*
 * lines.c - shutter, beam block and lamp enable on GPIO lines.  The
 * active level comes from the config; every write is read back, because
 * a lamp that stays on when we think it is off breaks the interlock.
 */
#include <string.h>

#include "rig/devices.h"

static const char *const line_names[RIG_LINE_COUNT] = {
	"shutter", "beam_block", "lamp",
};

const char *rig_line_name(enum rig_line which)
{
	return (unsigned)which < RIG_LINE_COUNT ? line_names[which] : "?";
}

int rig_lines_open(struct rig_lines *l, const struct rig_hal *hal,
		   const struct rig_line_cfg cfg[RIG_LINE_COUNT],
		   struct rig_error *err)
{
	int i, rc;

	memset(l, 0, sizeof(*l));
	l->cfg = cfg;
	for (i = 0; i < RIG_LINE_COUNT; i++) {
		/* Requested at the safe level: only the beam block is on. */
		int safe_on = i == RIG_LINE_BEAM_BLOCK;
		struct rig_gpio_id id = { cfg[i].chip, cfg[i].line, 1,
					  safe_on ^ (cfg[i].active_low ? 1 : 0) };

		l->state[i] = -1;
		rc = rig_hal_gpio_open(hal, &id, &l->dev[i]);
		if (rc != RIG_OK) {
			rig_lines_close(l);
			return rig_error_set(err, rc,
				"gpio: %s line '%s' on '%s': cannot open: %s",
				line_names[i], cfg[i].line, cfg[i].chip,
				rig_status_text(rc));
		}
	}
	return RIG_OK;
}

int rig_lines_set(struct rig_lines *l, enum rig_line which, int on,
		  struct rig_error *err)
{
	int level = (on ? 1 : 0) ^ (l->cfg[which].active_low ? 1 : 0);
	int back = -1, rc;

	l->state[which] = -1;
	rc = rig_hal_gpio_set(&l->dev[which], level);
	if (rc == RIG_OK)
		rc = rig_hal_gpio_get(&l->dev[which], &back);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "gpio: %s: %s",
				     line_names[which], rig_status_text(rc));
	if (back != level)
		return rig_error_set(err, RIG_EDEVICE,
			"gpio: %s: set %d but read back %d",
			line_names[which], level, back);
	l->state[which] = on ? 1 : 0;
	return RIG_OK;
}

int rig_lines_safe(struct rig_lines *l, struct rig_error *err)
{
	int rc_lamp = rig_lines_set(l, RIG_LINE_LAMP, 0, err);
	int rc_beam = rig_lines_set(l, RIG_LINE_BEAM_BLOCK, 1, err);
	int rc_shut = rig_lines_set(l, RIG_LINE_SHUTTER, 0, err);

	if (rc_lamp != RIG_OK)
		return rc_lamp;
	return rc_beam != RIG_OK ? rc_beam : rc_shut;
}

void rig_lines_close(struct rig_lines *l)
{
	int i;

	for (i = 0; i < RIG_LINE_COUNT; i++)
		rig_hal_gpio_close(&l->dev[i]);
}
