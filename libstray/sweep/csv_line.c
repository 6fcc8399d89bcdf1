/*
 * csv_line.c - one CSV line of a sweep folder's files split into cells
 * (csv_line.h), for the manifest and the import log alike.
 */
#include <csv.h>
#include <string.h>

#include "csv_line.h"
#include "stray/errfmt.h"

static void on_field(void *data, size_t len, void *ctx)
{
	struct csv_line *r = ctx;

	if (r->n >= CSV_LINE_FIELDS_MAX || len >= CSV_LINE_FIELD_LEN_MAX) {
		r->overflow = 1;
		return;
	}
	memcpy(r->f[r->n], data ? data : "", len);
	r->f[r->n][len] = '\0';
	r->n++;
}

static void on_row(int c, void *ctx)
{
	(void)c;
	(void)ctx;
}

int csv_line_split(const char *name, long line, const char *s, size_t len,
		   struct csv_line *r, struct stray_error *err)
{
	struct csv_parser p;
	int bad;

	r->n = 0;
	r->overflow = 0;
	if (csv_init(&p, CSV_STRICT | CSV_STRICT_FINI) != 0)
		return stray_error_at(err, STRAY_ENOMEM, name, line, 0, 0);
	bad = csv_parse(&p, s, len, on_field, on_row, r) != len ||
	      csv_fini(&p, on_field, on_row, r) != 0;
	if (bad)
		stray_error_at(err, STRAY_EPARSE, name, line, "csv",
			       csv_strerror(csv_error(&p)));
	csv_free(&p);
	if (bad)
		return STRAY_EPARSE;
	if (r->overflow)
		return stray_error_at(err, STRAY_EPARSE, name, line, "csv",
				      "too many or too long fields");
	return STRAY_OK;
}
