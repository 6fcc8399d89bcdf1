/*
 * spectrum_io.h - spectra and passbands from CSV files or the built-in set
 * (hosted).  A source is either a path or "builtin:NAME" with NAME one of
 * stray_builtin_spectra(); the CSV format is docs/formats.md's: a
 * `wavelength_nm,<quantity>` header and two columns.
 */
#ifndef STRAY_SPECTRUM_IO_H
#define STRAY_SPECTRUM_IO_H

#include <stddef.h>

#include "stray/error.h"
#include "stray/photometry.h"

#define STRAY_BUILTIN_PREFIX "builtin:"

struct stray_spectrum_data {
	struct stray_spectrum s;	/* view of the arrays below */
	double *wavelength_nm;
	double *value;
	char quantity[64];		/* the second column's name */
};

struct stray_builtin_spectrum {
	const char *name;
	const char *what;
	const char *text;		/* the CSV, NUL-terminated at end */
	const char *end;
};

/* The built-in spectra; *n receives their count. */
const struct stray_builtin_spectrum *stray_builtin_spectra(size_t *n);

/* The built-in spectrum called name, or NULL. */
const struct stray_builtin_spectrum *stray_builtin_find(const char *name);

/*
 * Load a spectrum from source ("builtin:NAME" or a path).  Errors name the
 * file and line: non-increasing wavelengths, negative or NaN values.
 */
int stray_spectrum_load(const char *source, struct stray_spectrum_data *d,
			struct stray_error *err);

void stray_spectrum_data_free(struct stray_spectrum_data *d);

#endif /* STRAY_SPECTRUM_IO_H */
