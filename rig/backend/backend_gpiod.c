/*
 * backend_gpiod.c - GPIO ops of the real backend, on libgpiod 1.6 (the
 * Debian 12 API): lines are found by name on a chip and requested as
 * outputs at the initial level the lines driver asks for (its safe
 * level), so no glitch turns a lamp on while the daemon starts.
 */
#include <gpiod.h>
#include <stdlib.h>

#include "backend.h"
#include "rig/status.h"

#define CONSUMER "strayrigd"

struct gpio_dev {
	struct gpiod_chip *chip;
	struct gpiod_line *line;
};

int rig_real_gpio_open(void *self, const struct rig_gpio_id *id, void **dev)
{
	struct gpio_dev *g;
	int rc;

	(void)self;
	g = calloc(1, sizeof(*g));
	if (!g)
		return RIG_ENOMEM;
	g->chip = gpiod_chip_open_lookup(id->chip);
	if (!g->chip)
		goto out_free;
	g->line = gpiod_chip_find_line(g->chip, id->line);
	if (!g->line)
		goto out_close;
	rc = id->output ? gpiod_line_request_output(g->line, CONSUMER,
						    id->initial)
			: gpiod_line_request_input(g->line, CONSUMER);
	if (rc != 0)
		goto out_close;
	*dev = g;
	return RIG_OK;
out_close:
	gpiod_chip_close(g->chip);
out_free:
	free(g);
	return RIG_EDISCONNECT;
}

int rig_real_gpio_set(void *self, void *dev, int value)
{
	struct gpio_dev *g = dev;

	(void)self;
	return gpiod_line_set_value(g->line, value) == 0 ? RIG_OK : RIG_EIO;
}

int rig_real_gpio_get(void *self, void *dev, int *value)
{
	struct gpio_dev *g = dev;
	int v;

	(void)self;
	v = gpiod_line_get_value(g->line);
	if (v < 0)
		return RIG_EIO;
	*value = v;
	return RIG_OK;
}

void rig_real_gpio_close(void *self, void *dev)
{
	struct gpio_dev *g = dev;

	(void)self;
	gpiod_line_release(g->line);
	gpiod_chip_close(g->chip);
	free(g);
}
