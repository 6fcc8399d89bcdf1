/*
 * cmd_report.c - `stray report DIR`: the design-review report of a demo or
 * project folder, as HTML with its PNG figures and a Markdown twin.
 *
 * The report is assembled from the artifacts the other commands leave in
 * DIR (their --json output and --plot figures), section by section, so a
 * team can rerun any stage and rebuild the report.  A section whose
 * artifacts are missing says so instead of silently disappearing.
 */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "commands.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define FIGS_MAX 4
#define ROWS_MAX 12

struct section {
	const char *id, *title, *what;
	const char *json;		/* artifact, or NULL */
	const char *txt;		/* a text artifact shown as it is */
	const char *fig[FIGS_MAX];	/* figures, NULL-terminated */
};

static const struct section sections[] = {
	{ "photometry", "Reference fluxes (thesis table 2.1)",
	  "Photon fluxes of the bright sources and the designed reference star in the sensor's passband (eq. 2.1-2.2).",
	  "photometry.json", NULL, { NULL } },
	{ "fdr", "False-detection rate and the attenuation it requires (fig. 2.7)",
	  "False stars per image against system attenuation, the tolerated rate, and alpha_required where they cross (eq. 2.3-2.18). normalisation and k_px say how a power-ratio curve (eq. 3.11-3.12, a trace) meets eq. 2.3: consistent, I_px = alpha F t A_px k_px with k_px = A_cs / (n_tot A_px), or the thesis, k_px = 1 (docs/normalisation.md).",
	  "fdr_sun.json", NULL, { "fdr_sun.png", NULL } },
	{ "lens", "Lens attenuation curve, noise floor and ghosts (thesis ch. 3)",
	  "The lens curve reduced from the lab sweep with its image noise floor (eq. 3.13-3.15), the row-collapsed profiles over angle and the internal-reflection ghosts tracked across angles (figs 3.7-3.9).",
	  "reduce.json", "rig.txt", { "alpha.png", "profiles.png", "ghosts.png", "j.png" } },
	{ "system", "System attenuation and exclusion angles (fig. 5.1)",
	  "The traced system curve (baffle and measured lens) with its error bars and the Sun, Moon and Earth exclusion angles, for the design as drawn and for the design change the path analysis suggests.",
	  "exclusion.json", "exclusion.txt", { "exclusion.png", "exclusion_variant.png", NULL } },
	{ "paths", "Scatter orders and the top stray-light paths (thesis §5.3)",
	  "Detector power split by scatter order (fig. 5.5) and the surface sequences that carry most of it.",
	  "trace.json", "paths.txt", { "orders.png", NULL } },
	{ "diagnosis", "Diagnosis: what the model got wrong (thesis ch. 4)",
	  "Measured baffle curve against the nominal and the corrected model, the named causes with their intervals, the gain, and the Sun exclusion angle before and after.",
	  "diagnose.json", "diagnose.txt", { "diagnose.png", NULL } },
	{ "diagnosis_system", "Diagnosis of a system curve: baffle and lens apart (thesis §4.2)",
	  "A sweep of the baffle behind the lens (the flight unit of the lens, passing 1 % of the lab unit's light beyond its field, and the worn coating and edges of the baffle above), diagnosed with the lab unit's table by stray diagnose --lens: the lens's causes (its table's scale, a ghost) and the baffle's are named on their own sides, and the Sun exclusion angle of the system is given before and after.",
	  "diagnose_system.json", "diagnose_system.txt", { "diagnose_system.png", NULL } },
	{ "pixels", "What the thesis model gets wrong about pixels",
	  "Eq. 2.3 wants alpha as a per-pixel irradiance ratio; a traced or measured curve is a power ratio P(theta)/P(0) whose on-axis beam fills A_cs (eq. 3.11-3.12), so a pixel sees alpha F t A_px k_px with k_px = A_cs / (n_tot A_px). The thesis leaves k_px out (k_px = 1) and under-predicts the background; the table gives every demo curve's Sun exclusion angle both ways, with the stray light uniform and spread by the lab's region map, and (exclusion_by_model, stray exclusion --models) under every model: the thesis (k_px = 1), consistent, and each validated detector (window, threshold, tetra3 at k = 3 and 5), with the failure mode that sets it, false stars or lost stars (docs/detectors.md). The figures: where the variant's stray light lands at 40 deg (focal map, log scale), a rendered frame near the tolerated rate, and false stars counted on rendered frames by the thesis's window-sum detector and an open-tracker threshold detector against eq. 2.18 and its extension (docs/frames.md).",
	  "pixels.json", "pixels.txt",
	  { "validation.png", "frame_sample.png", "focal_map.png", NULL } },
	{ "firmware", "Flight module footprint",
	  "The on-board exclusion and false-star module on its Cortex-M4F target: code, data and stack, and its flight table.",
	  "firmware.json", "firmware.txt", { NULL } },
	{ "orbit", "A day in orbit",
	  "Predicted false stars and exclusion flags along a 550 km sun-synchronous orbit, tracker pointing anti-nadir, evaluated by the flight module frame by frame.",
	  "orbit.json", NULL, { "orbit.png", "orbit_fdr.png", NULL } },
	{ "availability", "Tracker availability over a mission",
	  "Three heads on a spacecraft in a 550 km sun-synchronous orbit, nadir pointing with yaw steering, its orbit and attitude written as CCSDS OEM/AEM and read back; each head assessed by the flight module at every epoch, the Earth's albedo by latitude and season fed to its Earth term. The table: the fraction of time each head is available and excluded by each body, its outages, and \"any head\". The figures: the availability timeline and each head's sky (Sun, Moon and nearest Earth limb in the head's frame, with its Sun exclusion cone).",
	  "availability.json", "availability.txt",
	  { "availability_timeline.png", "availability_sky_A.png", "availability_sky_B.png", "availability_sky_C.png" } },
	{ "flightcheck", "The tracker in orbit, seen from its own images (thesis §4.3)",
	  "Flight frames along an attitude sweep of the Sun offset angle (rendered here, with a hidden scale and a hidden coating reflectance), read with their AEM: per frame the Sun angle from time and attitude, a robust background, the catalogue stars placed by the attitude and refined on the matches; the stars calibrate the frames absolutely, so the background is alpha_px(theta) with no lab. The table: the scale over the model's k_px and the shape test; the text: the per-frame curve and what stray diagnose names on it (scale free). Stars from the synthetic catalogue.",
	  "flightcheck.json", "flightcheck.txt", { "flightcheck.png", "flightcheck_diagnose.png", NULL } },
};

#define N_SECTIONS (sizeof(sections) / sizeof(sections[0]))

static const char usage[] =
	"usage: stray report DIR [--title T]\n"
	"\n"
	"Write DIR/report.html (with DIR's PNG figures) and DIR/report.md from\n"
	"the artifacts the other commands left in DIR (their --json output,\n"
	"text output and --plot figures): photometry.json, fdr_sun.json,\n"
	"reduce.json, exclusion.json, trace.json, diagnose.json, pixels.json,\n"
	"firmware.json, orbit.json, availability.json, flightcheck.json, the\n"
	"matching .txt files and\n"
	"figures.  scripts/demo.sh\n"
	"shows which command leaves which file.\n";

static int exists(const char *dir, const char *name)
{
	char path[4096];
	struct stat st;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	return stat(path, &st) == 0 && st.st_size > 0;
}

static void html_escaped(FILE *f, const char *s)
{
	for (; *s; s++) {
		switch (*s) {
		case '<': fputs("&lt;", f); break;
		case '>': fputs("&gt;", f); break;
		case '&': fputs("&amp;", f); break;
		case '"': fputs("&quot;", f); break;
		default: fputc(*s, f);
		}
	}
}

/*
 * User-supplied text in report.md (the title, values of the stages'
 * files): a raw "<script>" or "](javascript:" would reach any Markdown
 * viewer that passes HTML through, and a '|' or a newline breaks the
 * table.  HTML's three specials become entities, Markdown's inline
 * punctuation is backslash-escaped, line breaks become spaces.
 */
static void md_escaped(FILE *f, const char *s)
{
	for (; *s; s++) {
		switch (*s) {
		case '<': fputs("&lt;", f); break;
		case '>': fputs("&gt;", f); break;
		case '&': fputs("&amp;", f); break;
		case '\n': case '\r': fputc(' ', f); break;
		case '\\': case '`': case '*': case '_': case '[': case ']':
		case '|': case '#': case '!':
			fputc('\\', f);
			fputc(*s, f);
			break;
		default: fputc(*s, f);
		}
	}
}

/* A code fence longer than any run of backticks in text (so a file's
 * own "```" cannot close it and turn the rest into Markdown). */
static void md_fence(FILE *f, const char *text)
{
	size_t run = 0, most = 0, i;

	for (; *text; text++) {
		run = *text == '`' ? run + 1 : 0;
		most = run > most ? run : most;
	}
	for (i = 0; i < (most < 3 ? 3 : most + 1); i++)
		fputc('`', f);
}

/* A scalar as text: numbers to 5 significant digits. */
static void scalar_text(const cJSON *v, char *buf, size_t size)
{
	if (cJSON_IsNumber(v))
		snprintf(buf, size, "%.5g", v->valuedouble);
	else if (cJSON_IsString(v))
		snprintf(buf, size, "%s", v->valuestring);
	else if (cJSON_IsBool(v))
		snprintf(buf, size, "%s", cJSON_IsTrue(v) ? "yes" : "no");
	else if (cJSON_IsNull(v))
		snprintf(buf, size, "n/a");
	else if (cJSON_IsArray(v) && cJSON_GetArraySize(v) > 0 &&
		 !cJSON_IsObject(cJSON_GetArrayItem(v, 0))) {
		size_t n = 0;
		int i, k = cJSON_GetArraySize(v);

		buf[0] = '\0';
		for (i = 0; i < k && i < 8 && n + 16 < size; i++) {
			char one[64];

			scalar_text(cJSON_GetArrayItem(v, i), one, sizeof(one));
			n += snprintf(buf + n, size - n, "%s%s", i ? ", " : "", one);
		}
		if (k > 8 && n + 8 < size)
			snprintf(buf + n, size - n, ", ... (%d)", k);
	} else
		snprintf(buf, size, "(%d items)", cJSON_GetArraySize(v));
}

/* One output format: the HTML page or its Markdown twin. */
struct sink {
	FILE *f;
	int html;
};

static void cell(struct sink *s, const char *text, int head)
{
	if (s->html) {
		fputs(head ? "<th>" : "<td>", s->f);
		html_escaped(s->f, text);
		fputs(head ? "</th>" : "</td>", s->f);
	} else {
		fputc(' ', s->f);
		md_escaped(s->f, text);
		fputs(" |", s->f);
	}
}

static void row_start(struct sink *s)
{
	fputs(s->html ? "<tr>" : "|", s->f);
}

static void row_end(struct sink *s)
{
	fputs(s->html ? "</tr>\n" : "\n", s->f);
}

static void table_start(struct sink *s)
{
	if (s->html)
		fputs("<table>\n", s->f);
}

static void table_end(struct sink *s)
{
	fputs(s->html ? "</table>\n" : "\n", s->f);
}

static void md_rule(struct sink *s, int cols)
{
	int i;

	if (s->html)
		return;
	fputc('|', s->f);
	for (i = 0; i < cols; i++)
		fputs(" --- |", s->f);
	fputc('\n', s->f);
}

/* A list of objects as a table: the first object's keys are the columns. */
static void object_list(struct sink *s, const char *name, const cJSON *arr)
{
	const cJSON *first = cJSON_GetArrayItem(arr, 0), *k, *o;
	char text[256];
	int cols = 0, rows = 0;

	fprintf(s->f, s->html ? "<h4>%s</h4>\n" : "\n**%s**\n\n", name);
	table_start(s);
	row_start(s);
	cJSON_ArrayForEach(k, first) {
		cell(s, k->string, 1);
		cols++;
	}
	row_end(s);
	md_rule(s, cols);
	cJSON_ArrayForEach(o, arr) {
		if (rows++ == ROWS_MAX)
			break;
		row_start(s);
		cJSON_ArrayForEach(k, first) {
			scalar_text(cJSON_GetObjectItemCaseSensitive(o, k->string),
				    text, sizeof(text));
			cell(s, text, 0);
		}
		row_end(s);
	}
	table_end(s);
}

/* Scalars of an object (one level of nesting flattened as a.b). */
static void scalar_rows(struct sink *s, const cJSON *obj, const char *prefix)
{
	const cJSON *v;
	char key[256], text[512];

	cJSON_ArrayForEach(v, obj) {
		snprintf(key, sizeof(key), "%s%s", prefix, v->string);
		if (cJSON_IsObject(v) && !prefix[0]) {
			char p[128];

			snprintf(p, sizeof(p), "%s.", v->string);
			scalar_rows(s, v, p);
			continue;
		}
		if (cJSON_IsObject(v) || (cJSON_IsArray(v) &&
		    cJSON_IsObject(cJSON_GetArrayItem(v, 0))))
			continue;
		scalar_text(v, text, sizeof(text));
		row_start(s);
		cell(s, key, 0);
		cell(s, text, 0);
		row_end(s);
	}
}

static void json_body(struct sink *s, const cJSON *root)
{
	const cJSON *v;

	table_start(s);
	if (!s->html)
		fputs("| quantity | value |\n| --- | --- |\n", s->f);
	scalar_rows(s, root, "");
	table_end(s);
	cJSON_ArrayForEach(v, root)
		if (cJSON_IsArray(v) && cJSON_IsObject(cJSON_GetArrayItem(v, 0)))
			object_list(s, v->string, v);
}

/* One section; returns 1 when it had something to show. */
static int render_section(struct sink *s, const char *dir,
			  const struct section *sec)
{
	int i, shown = 0;
	char path[4096], *text;
	size_t len;

	if (s->html)
		fprintf(s->f, "<section id=\"%s\">\n<h2>%s</h2>\n<p>%s</p>\n",
			sec->id, sec->title, sec->what);
	else
		fprintf(s->f, "\n## %s\n\n%s\n\n", sec->title, sec->what);
	if (sec->json && exists(dir, sec->json)) {
		struct stray_error err;
		cJSON *root;

		snprintf(path, sizeof(path), "%s/%s", dir, sec->json);
		stray_error_clear(&err);
		if (stray_file_read(path, &text, &len, &err) == STRAY_OK) {
			root = cJSON_Parse(text);
			if (root) {
				json_body(s, root);
			} else {	/* it ran; its output is broken */
				fprintf(s->f, s->html
					? "<p class=\"empty\">%s is malformed (not JSON): the stage ran but its result cannot be shown.</p>\n"
					: "*%s is malformed (not JSON): the stage ran but its result cannot be shown.*\n",
					sec->json);
				fprintf(stderr, "stray report: %s: malformed JSON\n",
					path);
			}
			shown = 1;
			cJSON_Delete(root);
			free(text);
		}
	}
	if (sec->txt && exists(dir, sec->txt)) {
		struct stray_error err;

		snprintf(path, sizeof(path), "%s/%s", dir, sec->txt);
		stray_error_clear(&err);
		if (stray_file_read(path, &text, &len, &err) == STRAY_OK) {
			if (s->html) {
				fputs("<pre>", s->f);
				html_escaped(s->f, text);
				fputs("</pre>\n", s->f);
			} else {
				md_fence(s->f, text);
				fprintf(s->f, "\n%s%s", text,
					len && text[len - 1] == '\n' ? "" : "\n");
				md_fence(s->f, text);
				fputs("\n\n", s->f);
			}
			shown = 1;
			free(text);
		}
	}
	for (i = 0; i < FIGS_MAX && sec->fig[i]; i++) {
		if (!exists(dir, sec->fig[i]))
			continue;
		if (s->html)
			fprintf(s->f, "<figure><img src=\"%s\" alt=\"%s\"></figure>\n",
				sec->fig[i], sec->title);
		else
			fprintf(s->f, "![%s](%s)\n\n", sec->title, sec->fig[i]);
		shown = 1;
	}
	if (!shown)
		fprintf(s->f, s->html ? "<p class=\"empty\">This stage was not run: no %s in this folder.</p>\n"
				      : "*This stage was not run: no %s in this folder.*\n",
			sec->json ? sec->json : sec->fig[0]);
	if (s->html)
		fputs("</section>\n", s->f);
	return shown;
}

static const char html_head[] =
	"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
	"<title>%s</title>\n<style>\n"
	"body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}\n"
	"table{border-collapse:collapse;margin:.5em 0}\n"
	"td,th{border:1px solid #bbb;padding:.2em .6em;text-align:left}\n"
	"img{max-width:100%%;border:1px solid #ddd}\n"
	".empty{color:#a00;font-style:italic}\n"
	"pre{background:#f6f6f6;padding:.5em;overflow-x:auto;font-size:85%%}\n"
	"</style>\n"
	/* The screenshot test reads these attributes: every figure loaded? */
	"<script>window.addEventListener('load',function(){var im=document.images,b=0;"
	"for(var i=0;i<im.length;i++)if(!im[i].complete||im[i].naturalWidth===0)b++;"
	"document.body.setAttribute('data-figures',im.length);"
	"document.body.setAttribute('data-broken',b);});</script>\n"
	"</head><body>\n<h1>%s</h1>\n";

/* A new string with & < > " ' escaped for HTML text and attributes. */
static char *html_escape_dup(const char *text)
{
	char *out = malloc(6 * strlen(text) + 1), *o = out;

	for (; out && *text; text++)
		switch (*text) {
		case '&': o += sprintf(o, "&amp;"); break;
		case '<': o += sprintf(o, "&lt;"); break;
		case '>': o += sprintf(o, "&gt;"); break;
		case '"': o += sprintf(o, "&quot;"); break;
		case '\'': o += sprintf(o, "&#39;"); break;
		default: *o++ = *text;
		}
	if (out)
		*o = '\0';
	return out;
}

static int write_report(const char *dir, const char *title, int html,
			int *shown, struct stray_error *err)
{
	struct stray_file_out out;
	struct sink s;
	char path[4096];
	size_t i;
	int rc;

	snprintf(path, sizeof(path), "%s/%s", dir, html ? "report.html"
							 : "report.md");
	rc = stray_file_open_atomic(&out, path, err);
	if (rc != STRAY_OK)
		return rc;
	s.f = out.f;
	s.html = html;
	if (html) {		/* the title is the user's text: escaped */
		char *t = html_escape_dup(title);

		if (!t) {
			stray_file_abort(&out);
			return stray_error_set(err, STRAY_ENOMEM, "title", 0);
		}
		fprintf(s.f, html_head, t, t);
		free(t);
	} else {
		fputs("# ", s.f);
		md_escaped(s.f, title);
		fputc('\n', s.f);
	}
	for (i = 0, *shown = 0; i < N_SECTIONS; i++)
		*shown += render_section(&s, dir, &sections[i]);
	if (html)
		fputs("</body></html>\n", s.f);
	return stray_file_commit(&out, err);
}

int cmd_report(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "title", required_argument, NULL, 't' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	const char *title = "straylight design review";
	struct stray_error err;
	int opt, shown;

	while ((opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 'h': fputs(usage, stdout); return CLI_OK;
		case 't': title = optarg; break;
		default:
			return cli_usage_error("report", "unknown option '%s'",
					       argv[optind - 1]);
		}
	}
	if (optind != argc - 1)
		return cli_usage_error("report", "one folder expected");
	stray_error_clear(&err);
	{
		struct stat st;

		if (stat(argv[optind], &st) != 0 || !S_ISDIR(st.st_mode)) {
			stray_error_at(&err, STRAY_ENOTFOUND, argv[optind], 0,
				       "DIR", "is not a folder");
			return cli_fail("report", &err);
		}
	}
	if (write_report(argv[optind], title, 1, &shown, &err) != STRAY_OK ||
	    write_report(argv[optind], title, 0, &shown, &err) != STRAY_OK)
		return cli_fail("report", &err);
	printf("report: %s/report.html and report.md, %d of %zu sections with results\n",
	       argv[optind], shown, N_SECTIONS);
	return CLI_OK;
}
