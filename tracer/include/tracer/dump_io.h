/*
 * dump_io.h - CSV files of a trace's optional extras: sample paths for a
 * plot of where stray light goes (thesis fig. 5.6) and the detector's
 * irradiance map at one angle.
 */
#ifndef TRACER_DUMP_IO_H
#define TRACER_DUMP_IO_H

#include "tracer/integrator.h"

/* path,vertex,x_mm,y_mm,z_mm,group (vertex 0 lies on the detector). */
int tracer_dump_write_csv(const struct tracer_result *r,
			  const struct tracer_scene *s, const char *path,
			  struct stray_error *err);

/* x_mm,y_mm,irradiance_rel: pixel centres in the detector frame and the
 * irradiance there over the beam irradiance. */
int tracer_map_write_csv(const struct tracer_result *r, const char *path,
			 struct stray_error *err);

#endif /* TRACER_DUMP_IO_H */
