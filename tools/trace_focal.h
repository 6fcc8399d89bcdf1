/*
 * trace_focal.h - the options and --json of `stray trace --focal-map`
 * (the map: frames/focal_map_io.h).
 */
#ifndef STRAY_TOOLS_TRACE_FOCAL_H
#define STRAY_TOOLS_TRACE_FOCAL_H

#include "frames/focal_map_io.h"

struct cJSON;

/* The long options (codes 1100..1104) for trace_opts[]. */
#define FOCAL_MAP_LONG_OPTIONS \
	{ "focal-map", required_argument, NULL, 1100 }, \
	{ "focal-map-png", required_argument, NULL, 1101 }, \
	{ "sensor", required_argument, NULL, 1102 }, \
	{ "map-cell", required_argument, NULL, 1103 }, \
	{ "lens-map", required_argument, NULL, 1104 }

#define FOCAL_MAP_USAGE \
	"  --focal-map M.fits  focal-plane stray-light map at --map-angle:\n" \
	"                    per-pixel E_px/E_src, mean k_px*alpha (FITS;\n" \
	"                    a name ending in .png writes the PNG instead)\n" \
	"  --focal-map-png P.png  the map as false-colour PNG (log, +y up)\n" \
	"  --sensor S        sensor of the map (default st16-like)\n" \
	"  --map-cell PX     detector pixels per map cell (default 36)\n" \
	"  --lens-map R.csv  spread out-of-field light by this region map\n" \
	"                    (stray reduce --map); default uniform\n"

/* Take one of FOCAL_MAP_LONG_OPTIONS: 0 when it was one (*rc says
 * whether the value was good), 1 otherwise. */
int focal_map_option(int opt, char *text, struct focal_map_args *f,
		     int *rc);

/* Add "focal_map" to a --json summary (when a map was written). */
void focal_map_json(const struct focal_map_args *f, struct cJSON *o);

#endif /* STRAY_TOOLS_TRACE_FOCAL_H */
