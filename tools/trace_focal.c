/*
 * trace_focal.c - the options and --json of `stray trace --focal-map`
 * (trace_focal.h); the map itself is libframes (frames/focal_map_io.c).
 */
#include <string.h>

#include "cli.h"
#include "trace_focal.h"

/* OpenCV picks the encoder by the name's ending. */
static int is_png(const char *name)
{
	size_t n = strlen(name);

	return n >= 4 && strcmp(name + n - 4, ".png") == 0;
}

int focal_map_option(int opt, char *text, struct focal_map_args *f, int *rc)
{
	double v;

	switch (opt) {
	case 1100:	/* a .png name: the PNG instead of FITS */
		*(is_png(text) ? &f->png : &f->fits) = text;
		return 0;
	case 1101:
		f->png = text;
		if (!is_png(text))
			*rc = cli_usage_error("trace", "--focal-map-png '%s' "
					      "must end in .png", text);
		return 0;
	case 1102: f->sensor = text; return 0;
	case 1104: f->lens_map = text; return 0;
	case 1103:
		*rc = cli_parse_count("trace", "map-cell", text, 1, 4096, &v);
		f->cell_px = (int)v;
		return 0;
	default:
		return 1;
	}
}

void focal_map_json(const struct focal_map_args *f, cJSON *o)
{
	cJSON *m;

	if (!f->has_result)
		return;
	m = cJSON_AddObjectToObject(o, "focal_map");
	if (f->fits)
		cJSON_AddStringToObject(m, "path", f->fits);
	if (f->png)
		cJSON_AddStringToObject(m, "png", f->png);
	cJSON_AddItemToObject(m, "theta_deg", cli_json_number(f->theta_deg));
	cJSON_AddItemToObject(m, "alpha", cli_json_number(f->alpha));
	cJSON_AddItemToObject(m, "alpha_sigma", cli_json_number(f->sigma));
	cJSON_AddItemToObject(m, "k_px", cli_json_number(f->k_px));
	cJSON_AddItemToObject(m, "mean", cli_json_number(f->mean));
	cJSON_AddStringToObject(m, "normalisation", "consistent");
	cJSON_AddStringToObject(m, "spread",
				f->lens_map ? "lensmap" : "uniform");
	cJSON_AddItemToObject(m, "in_field_fraction",
			      cli_json_number(f->in_field));
	cJSON_AddNumberToObject(m, "cells_x", f->fp.nx);
	cJSON_AddNumberToObject(m, "cells_y", f->fp.ny);
	cJSON_AddNumberToObject(m, "cell_px", f->cell_px);
	cJSON_AddItemToObject(m, "focal_mm", cli_json_number(f->fp.f_mm));
	cJSON_AddStringToObject(m, "sensor", f->sen.name);
}
