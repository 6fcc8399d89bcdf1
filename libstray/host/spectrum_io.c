/*
 * spectrum_io.c - spectra from CSV files and from the built-in blobs.
 */
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/spectrum_io.h"
#include "stray/table.h"

#define BLOB_DECL(sym) extern const char sym##_start[], sym##_end[]
BLOB_DECL(stray_blob_sun_e490);
BLOB_DECL(stray_blob_sun_g173);
BLOB_DECL(stray_blob_vega);
BLOB_DECL(stray_blob_qe);
BLOB_DECL(stray_blob_bessell_v);
#define BLOB(sym) sym##_start, sym##_end

static const struct stray_builtin_spectrum builtins[] = {
	{ "sun_am0_astm_e490", "Sun, ASTM E490-00a AM0 at 1 au",
	  BLOB(stray_blob_sun_e490) },
	{ "sun_am0_astm_g173_etr", "Sun, ASTM G173-03 extraterrestrial",
	  BLOB(stray_blob_sun_g173) },
	{ "vega_calspec_alpha_lyr_stis_011", "Vega, HST CALSPEC",
	  BLOB(stray_blob_vega) },
	{ "qe_mt9p031_approx",
	  "APPROXIMATE MT9P031-class monochrome QE (not vendor data)",
	  BLOB(stray_blob_qe) },
	{ "bessell_v_passband", "Johnson-Cousins V (Bessell 1990), energy response",
	  BLOB(stray_blob_bessell_v) },
};

#define N_BUILTINS (sizeof(builtins) / sizeof(builtins[0]))

const struct stray_builtin_spectrum *stray_builtin_spectra(size_t *n)
{
	*n = N_BUILTINS;
	return builtins;
}

const struct stray_builtin_spectrum *stray_builtin_find(const char *name)
{
	size_t i;

	for (i = 0; i < N_BUILTINS; i++)
		if (strcmp(builtins[i].name, name) == 0)
			return &builtins[i];
	return NULL;
}

/* Check the two columns row by row, so errors carry line numbers. */
static int check_rows(const char *name, const struct stray_table *t,
		      struct stray_error *err)
{
	size_t i;
	int is_qe;

	if (t->n_cols != 2 || strcmp(t->col[0], "wavelength_nm") != 0)
		return stray_error_at(err, STRAY_EPARSE, name, 0, "header",
			"a spectrum needs the columns wavelength_nm,<quantity>");
	is_qe = strcmp(t->col[1], "qe") == 0;	/* a fraction: <= 1 */
	if (t->n_rows < 2)
		return stray_error_at(err, STRAY_EPARSE, name, 0,
			"wavelength_nm", "a spectrum needs at least 2 rows");
	for (i = 0; i < t->n_rows; i++) {
		const double *row = t->cell + 2 * i;

		if (!(row[0] > 0.0) ||
		    (i > 0 && !(row[0] > t->cell[2 * (i - 1)])))
			return stray_error_at(err, STRAY_EPARSE, name,
				t->line[i], "wavelength_nm",
				"wavelengths must be > 0 and strictly increasing");
		if (row[1] < 0.0 || (is_qe && row[1] > 1.0)) {
			char text[32];

			stray_error_at(err, STRAY_EPARSE, name, t->line[i],
				       NULL, row[1] < 0.0 ? "must be >= 0"
				       : "a quantum efficiency must be <= 1");
			stray_error_column(err, t->col[1]);
			snprintf(text, sizeof(text), "%.6g", row[1]);
			stray_error_text(err, text);
			return STRAY_EPARSE;
		}
	}
	return STRAY_OK;
}

static int from_text(const char *name, const char *text, size_t len,
		     struct stray_spectrum_data *d, struct stray_error *err)
{
	struct stray_table t;
	int rc = stray_table_parse(name, text, len, &t, err);

	if (rc != STRAY_OK)
		return rc;
	rc = check_rows(name, &t, err);
	if (rc == STRAY_OK) {
		d->wavelength_nm = stray_table_column(&t, 0);
		d->value = stray_table_column(&t, 1);
		if (!d->wavelength_nm || !d->value)
			rc = stray_error_set(err, STRAY_ENOMEM, 0, 0);
	}
	if (rc == STRAY_OK) {
		strncpy(d->quantity, t.col[1], sizeof(d->quantity) - 1);
		d->s.n = t.n_rows;
		d->s.wavelength_nm = d->wavelength_nm;
		d->s.value = d->value;
	}
	stray_table_free(&t);
	if (rc != STRAY_OK)
		stray_spectrum_data_free(d);
	return rc;
}

int stray_spectrum_load(const char *source, struct stray_spectrum_data *d,
			struct stray_error *err)
{
	size_t plen = strlen(STRAY_BUILTIN_PREFIX), len;
	char *buf;
	int rc;

	memset(d, 0, sizeof(*d));
	if (strncmp(source, STRAY_BUILTIN_PREFIX, plen) == 0) {
		const struct stray_builtin_spectrum *b =
			stray_builtin_find(source + plen);

		if (!b) {
			stray_error_set(err, STRAY_ENOTFOUND, "spectrum",
					"no such built-in spectrum");
			stray_error_text(err, source);
			return STRAY_ENOTFOUND;
		}
		return from_text(source, b->text, (size_t)(b->end - b->text),
				 d, err);
	}
	rc = stray_file_read(source, &buf, &len, err);
	if (rc != STRAY_OK)
		return rc;
	rc = from_text(source, buf, len, d, err);
	free(buf);
	return rc;
}

void stray_spectrum_data_free(struct stray_spectrum_data *d)
{
	free(d->wavelength_nm);
	free(d->value);
	memset(d, 0, sizeof(*d));
}
