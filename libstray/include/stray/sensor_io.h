/*
 * sensor_io.h - sensors by name or from a JSON file (hosted, cJSON).
 *
 * A sensor file is a JSON object whose keys are the fields of struct
 * stray_sensor (sensor.h); keys left out keep the `st16-like` values, so a
 * file states only what differs.  Spectrum paths are taken relative to the
 * file's folder.  An unknown key is an error, not silently ignored.
 */
#ifndef STRAY_SENSOR_IO_H
#define STRAY_SENSOR_IO_H

#include <stddef.h>

#include "stray/error.h"
#include "stray/sensor.h"

/* "st16-like" (built in) or a path to a JSON sensor file. */
int stray_sensor_load(const char *spec, struct stray_sensor *s,
		      struct stray_error *err);

/* Parse JSON text; name is for messages, base_dir resolves spectra. */
int stray_sensor_parse(const char *name, const char *text,
		       const char *base_dir, struct stray_sensor *s,
		       struct stray_error *err);

#endif /* STRAY_SENSOR_IO_H */
