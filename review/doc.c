/*
 * doc.c - the report's text model written twice, as HTML and as
 * Markdown, and a JSON object as tables (a nested object or list of
 * objects is a table of its own, every number with its unit).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "review_int.h"

void doc_text(struct review_doc *d, const char *t)
{
	for (; *t; t++) {
		if (d->html && strchr("&<>\"'", *t))
			fprintf(d->f, "&#%d;", *t);
		else if (!d->html && strchr("|*_`\\", *t))
			fprintf(d->f, "\\%c", *t);
		else
			fputc(*t, d->f);
	}
}

void doc_h2(struct review_doc *d, const char *title, const char *id)
{
	if (d->html) {
		fprintf(d->f, "<section id=\"%s\"><h2>", id);
		doc_text(d, title);
		fputs("</h2>\n", d->f);
	} else {
		fputs("## ", d->f);
		doc_text(d, title);
		fputs("\n\n", d->f);
	}
}

void doc_end_section(struct review_doc *d)
{
	if (d->html)
		fputs("</section>\n", d->f);
}

void doc_p(struct review_doc *d, const char *fmt, ...)
{
	char buf[2048];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(buf, sizeof(buf), fmt, ap);
	va_end(ap);
	fputs(d->html ? "<p>" : "", d->f);
	doc_text(d, buf);
	fputs(d->html ? "</p>\n" : "\n\n", d->f);
}

void doc_table(struct review_doc *d, int ncol, const char *const *head)
{
	int i;

	fputs(d->html ? "<table><tr>" : "|", d->f);
	for (i = 0; i < ncol; i++) {
		fputs(d->html ? "<th>" : " ", d->f);
		doc_text(d, head[i]);
		fputs(d->html ? "</th>" : " |", d->f);
	}
	fputs(d->html ? "</tr>\n" : "\n|", d->f);
	for (i = 0; !d->html && i < ncol; i++)
		fputs(" --- |", d->f);
	if (!d->html)
		fputc('\n', d->f);
}

void doc_row(struct review_doc *d, int ncol, const char *const *cells)
{
	int i;

	fputs(d->html ? "<tr>" : "|", d->f);
	for (i = 0; i < ncol; i++) {
		fputs(d->html ? "<td>" : " ", d->f);
		doc_text(d, cells[i] ? cells[i] : "");
		fputs(d->html ? "</td>" : " |", d->f);
	}
	fputs(d->html ? "</tr>\n" : "\n", d->f);
}

void doc_table_end(struct review_doc *d)
{
	fputs(d->html ? "</table>\n" : "\n", d->f);
}

void doc_fig(struct review_doc *d, const char *src, const char *alt)
{
	if (d->html) {
		fprintf(d->f, "<figure><img src=\"%s\" alt=\"", src);
		doc_text(d, alt);
		fputs("\"><figcaption>", d->f);
		doc_text(d, alt);
		fputs("</figcaption></figure>\n", d->f);
	} else {
		fputs("![", d->f);
		doc_text(d, alt);
		fprintf(d->f, "](%s)\n\n", src);
	}
}

/* The unit of a key of the toolkit's JSON outputs. */
const char *review_unit(const char *key)
{
	static const char *const flux[] = { "sun", "moon", "zero_mag", "vega",
		"drs", "flux", "source_flux", NULL };
	size_t n = strlen(key);
	int i;

	for (i = 0; flux[i]; i++)
		if (strcmp(key, flux[i]) == 0)
			return "ph s^-1 m^-2";
#define ENDS(s) (n >= sizeof(s) - 1 && strcmp(key + n - (sizeof(s) - 1), s) == 0)
	if (ENDS("_deg") || strcmp(key, "deg_lo") == 0 || strcmp(key, "deg_hi") == 0)
		return "deg";
	if (ENDS("_mag"))
		return "mag";
	if (ENDS("_per_s"))
		return "s^-1";
	if (ENDS("_s") || strcmp(key, "seconds") == 0)
		return "s";
	if (ENDS("_km"))
		return "km";
	if (ENDS("_e"))
		return "e-";
	if (ENDS("_frac"))
		return "fraction of the time";
	if (ENDS("_bytes"))
		return "bytes";
	if (strncmp(key, "rms", 3) == 0)
		return "log10 alpha";
	if (strcmp(key, "rate") == 0 || strncmp(key, "fdr", 3) == 0 ||
	    strncmp(key, "false_stars", 11) == 0)
		return "false stars per image";
	if (strncmp(key, "alpha", 5) == 0 || strcmp(key, "k_px") == 0 ||
	    strstr(key, "albedo") || strcmp(key, "factor") == 0 ||
	    strcmp(key, "reflectance") == 0)
		return "1 (ratio)";
	if (ENDS("_mm") || ENDS("radius") || strcmp(key, "z") == 0 ||
	    strcmp(key, "wall") == 0 || strcmp(key, "vane_thickness") == 0 ||
	    strcmp(key, "beam_margin") == 0 || strcmp(key, "scale_mm") == 0)
		return "mm";	/* the scene files' lengths (docs/scene.md) */
	if (strcmp(key, "sigma") == 0 || strcmp(key, "noise_floor") == 0 ||
	    ENDS("rel_sigma") || ENDS("rel_power") || strcmp(key, "direct") == 0 ||
	    strncmp(key, "order", 5) == 0)
		return "1 (ratio)";
	if (strcmp(key, "column") == 0 || strcmp(key, "row") == 0)
		return "px";
	if (ENDS("frames") || ENDS("_count") || ENDS("_samples") ||
	    ENDS("_pixels") || strcmp(key, "rows") == 0 ||
	    strcmp(key, "columns") == 0 || strcmp(key, "visits") == 0 ||
	    ENDS("epochs") || ENDS("outages") || ENDS("_gaps") ||
	    strcmp(key, "n") == 0 || strcmp(key, "paths") == 0 ||
	    strcmp(key, "casts") == 0 || strcmp(key, "connections") == 0 ||
	    strcmp(key, "angles") == 0 || strcmp(key, "threads") == 0 ||
	    strncmp(key, "n_", 2) == 0 || strcmp(key, "candidates") == 0 ||
	    strcmp(key, "segments") == 0 || strcmp(key, "arc_segments") == 0)
		return "count";
#undef ENDS
	return "1 (dimensionless)";
}

static void scalar(const cJSON *v, char *buf, size_t size)
{
	if (cJSON_IsNumber(v))
		snprintf(buf, size, "%.4g", v->valuedouble);
	else if (cJSON_IsString(v))
		snprintf(buf, size, "%s", v->valuestring);
	else if (cJSON_IsBool(v))
		snprintf(buf, size, "%s", cJSON_IsTrue(v) ? "yes" : "no");
	else if (cJSON_IsNull(v))
		snprintf(buf, size, "none");
	else
		buf[0] = '\0';
}

static int is_scalar(const cJSON *v)
{
	return !cJSON_IsObject(v) && !cJSON_IsArray(v);
}

/* A list of scalars on one line (the first 12). */
static void list_line(const cJSON *a, char *buf, size_t size)
{
	const cJSON *x;
	size_t k = 0;
	int i = 0;

	buf[0] = '\0';
	cJSON_ArrayForEach(x, a) {
		char one[64];

		if (i++ == 12) {
			snprintf(buf + k, size - k, ", ...");
			return;
		}
		scalar(x, one, sizeof(one));
		k += (size_t)snprintf(buf + k, size - k, "%s%s", i > 1 ? ", " : "", one);
		if (k >= size)
			return;
	}
}

/* A list of objects: one row each, columns of the first's scalars. */
static void object_list(struct review_doc *d, const cJSON *a, const char *title)
{
	const char *head[12], *cells[12], *title_of[12];
	char buf[12][96], th[12][96];
	const cJSON *x, *first = a->child;
	int n = 0, i;

	cJSON_ArrayForEach(x, first)
		if (n < 12 && (is_scalar(x) || cJSON_IsArray(x)))
			head[n++] = x->string;
	if (!n)
		return;
	for (i = 0; i < n; i++) {
		const cJSON *v = cJSON_GetObjectItemCaseSensitive(first, head[i]);

		/* the unit once, in the heading */
		if (cJSON_IsNumber(v))
			snprintf(th[i], sizeof(th[i]), "%s [%s]", head[i], review_unit(head[i]));
		else
			snprintf(th[i], sizeof(th[i]), "%s", head[i]);
		title_of[i] = th[i];
	}
	doc_p(d, "%s:", title);
	doc_table(d, n, title_of);
	cJSON_ArrayForEach(x, a) {
		for (i = 0; i < n; i++) {
			const cJSON *v = cJSON_GetObjectItemCaseSensitive(x, head[i]);

			if (cJSON_IsArray(v))
				list_line(v, buf[i], sizeof(buf[i]));
			else
				scalar(v, buf[i], sizeof(buf[i]));
			cells[i] = buf[i];
		}
		doc_row(d, n, cells);
	}
	doc_table_end(d);
}

void review_json_tables(struct review_doc *d, const cJSON *o, const char *title,
			const char *const *skip)
{
	static const char *const head[3] = { "quantity", "value", "unit" };
	const cJSON *v;
	char val[512], sub[160];
	const char *cells[3];
	int rows = 0, i;

	cJSON_ArrayForEach(v, o) {
		for (i = 0; skip && skip[i] && strcmp(skip[i], v->string); i++)
			;
		if ((skip && skip[i]) || strcmp(v->string, "provenance") == 0)
			continue;
		if (!is_scalar(v) && !(cJSON_IsArray(v) && (!v->child || is_scalar(v->child))))
			continue;
		if (!rows++)
			doc_table(d, 3, head);
		if (cJSON_IsArray(v))
			list_line(v, val, sizeof(val));
		else
			scalar(v, val, sizeof(val));
		cells[0] = v->string;
		cells[1] = val;
		cells[2] = cJSON_IsNumber(v) || (cJSON_IsArray(v) && cJSON_IsNumber(v->child)) ?
			   review_unit(v->string) : "";
		doc_row(d, 3, cells);
	}
	if (rows)
		doc_table_end(d);
	cJSON_ArrayForEach(v, o) {
		for (i = 0; skip && skip[i] && strcmp(skip[i], v->string); i++)
			;
		if ((skip && skip[i]) || strcmp(v->string, "provenance") == 0)
			continue;
		snprintf(sub, sizeof(sub), "%s%s%s", title, title[0] ? ": " : "", v->string);
		if (cJSON_IsObject(v) && v->child) {
			doc_p(d, "%s:", sub);
			review_json_tables(d, v, sub, skip);
		} else if (cJSON_IsArray(v) && cJSON_IsObject(v->child)) {
			object_list(d, v, sub);
		}
	}
}
