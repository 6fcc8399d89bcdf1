/*
 * focal_map_io.h - `stray trace --focal-map M.fits [--focal-map-png P.png]`:
 * the focal-plane stray-light map of the sensor at --map-angle
 * (issue 13 item 2; physics and FITS format in tracer/README.md).
 * cmd_trace.c takes the options (tools/trace_focal.h), sets the tracer up
 * here before the trace and writes the map after it.
 */
#ifndef STRAY_FRAMES_FOCAL_MAP_IO_H
#define STRAY_FRAMES_FOCAL_MAP_IO_H

#include "stray/sensor.h"
#include "tracer/focal.h"
#include "tracer/integrator.h"

struct focal_map_args {
	const char *fits, *png;		/* outputs; NULL: not wanted */
	const char *sensor;		/* 'st16-like' or a sensor file */
	const char *lens_map;		/* region map CSV; NULL: uniform */
	int cell_px;			/* detector pixels per cell side */
	/* filled by focal_map_prepare / focal_map_write */
	struct stray_sensor sen;
	struct tracer_focal fp;
	double theta_deg, k_px, alpha, sigma, mean, in_field;
	int has_result;
};

void focal_map_defaults(struct focal_map_args *f);

int focal_map_wanted(const struct focal_map_args *f);

/* Sensor and cells into the focal geometry; o->focal points at it. */
int focal_map_prepare(struct focal_map_args *f, size_t theta_index,
		      struct tracer_trace_opts *o, struct stray_error *err);

/* The map from a finished trace, written as FITS and/or PNG. */
int focal_map_write(struct focal_map_args *f, const struct tracer_result *r,
		    const struct tracer_scene *s,
		    const struct tracer_trace_opts *o, struct stray_error *err);

/*
 * A focal map read back (focal_map_read.c), the one reader of the format:
 * `stray frames --map M.fits` and the tests.  Any 2-D float image of
 * relative weights will do; the keywords `stray trace` writes are read
 * when present (NaN or 0 when not).
 */
struct focal_map_file {
	long nx, ny;			/* cells: columns (x), rows (y) */
	long cell_px;			/* detector pixels per cell side; 0 */
	long npix_x, npix_y;		/* detector pixels; 0 if not given */
	double theta_deg, alpha, k_px, mean;	/* keywords, or NaN */
	double cell_mean;		/* mean of the cells as read */
	char spread[16];		/* "uniform", "lensmap" or "unknown" */
	float *cell;			/* [row][col], row 0 at -y */
};

/* Read a map; a missing file, a non-2-D image, a non-finite or negative
 * cell or a map with no light is an error naming the file and keyword. */
int focal_map_load(const char *path, struct focal_map_file *m,
		   struct stray_error *err);

/*
 * The map resampled to the window [col0, col0 + cols) x [row0, row0 +
 * rows) of a det_x x det_y detector, divided by div: bilinear between
 * cell centres (the map samples a smooth distribution, not steps),
 * extrapolated linearly past the outer centres, clamped at 0.
 */
void focal_map_resample(const struct focal_map_file *m, int det_x,
			int det_y, int col0, int row0, int cols, int rows,
			double div, float *out);

void focal_map_file_free(struct focal_map_file *m);

#endif /* STRAY_FRAMES_FOCAL_MAP_IO_H */
