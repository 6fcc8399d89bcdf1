/*
 * curve_io.h - attenuation curves in the CSV format of docs/formats.md
 * (hosted): `theta_deg,alpha[,sigma][,more...]`, metadata comments kept.
 */
#ifndef STRAY_CURVE_IO_H
#define STRAY_CURVE_IO_H

#include <stddef.h>

#include "stray/curve.h"
#include "stray/error.h"

#define STRAY_CURVE_EXTRA_MAX 16

struct stray_curve {
	size_t n;
	double *theta_deg;
	double *alpha;
	double *sigma;		/* NULL when the file has no sigma column */
	/* Further named columns, kept on rewrite (order1, noise_floor, ...). */
	size_t n_extra;
	char *extra_name[STRAY_CURVE_EXTRA_MAX];
	double *extra[STRAY_CURVE_EXTRA_MAX];
	char **meta;		/* comment lines, without '#' */
	size_t n_meta;
};

/* Load and validate a curve file; errors name file, line and column. */
int stray_curve_load(const char *path, struct stray_curve *c,
		     struct stray_error *err);

/* As stray_curve_load, from text already in memory. */
int stray_curve_parse(const char *name, const char *text, size_t len,
		      struct stray_curve *c, struct stray_error *err);

/* Allocate an empty curve of n rows (sigma when with_sigma); 0 on success. */
int stray_curve_alloc(struct stray_curve *c, size_t n, int with_sigma,
		      struct stray_error *err);

/* Add a named extra column of n values (copied). */
int stray_curve_add_column(struct stray_curve *c, const char *name,
			   const double *values, struct stray_error *err);

/* Add a `# key: value` metadata line. */
int stray_curve_add_meta(struct stray_curve *c, const char *key,
			 const char *value, struct stray_error *err);

/* Write atomically (temporary file, then rename); %.10g numbers. */
int stray_curve_save(const char *path, const struct stray_curve *c,
		     struct stray_error *err);

/* A view for the freestanding functions of curve.h. */
struct stray_curve_view stray_curve_view_of(const struct stray_curve *c);

void stray_curve_free(struct stray_curve *c);

#endif /* STRAY_CURVE_IO_H */
