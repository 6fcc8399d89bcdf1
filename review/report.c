/*
 * report.c - review.json and the report of a review (HTML and Markdown):
 * the verdict table first, then the design, then every step of the
 * manifest with its numbers, units and figures.  Every sentence is made
 * from this project's data; a step not run says why.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "review_int.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/provenance.h"

static const char html_head[] =
	"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
	"<title>Design review</title>\n<style>\n"
	"body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}\n"
	"table{border-collapse:collapse;margin:.5em 0}\n"
	"td,th{border:1px solid #bbb;padding:.2em .6em;text-align:left}\n"
	"img{max-width:100%%;border:1px solid #ddd}\n"
	".pass{color:#060;font-weight:bold}.fail{color:#a00;font-weight:bold}\n"
	"code{background:#f6f6f6}\n"
	"</style>\n"
	/* scripts/check-report.sh reads these: every figure loaded? */
	"<script>window.addEventListener('load',function(){var im=document.images,b=0;"
	"for(var i=0;i<im.length;i++)if(!im[i].complete||im[i].naturalWidth===0)b++;"
	"document.body.setAttribute('data-figures',im.length);"
	"document.body.setAttribute('data-broken',b);});</script>\n"
	"</head><body>\n";

static void fmt_found(const struct review_verdict *v,
		      const struct review_plan *plan, char *found,
		      char *interval, size_t size)
{
	interval[0] = '\0';
	if (!review_step_done(plan, v->step))
		snprintf(found, size, "not found: step %s not run", v->step);
	else if (!isfinite(v->found))
		snprintf(found, size, "none (not excluded within the curve)");
	else
		snprintf(found, size, "%.4g %s", v->found, v->unit);
	if (isfinite(v->lo) && isfinite(v->hi))
		snprintf(interval, size, "[%.4g, %.4g] %s", v->lo, v->hi, v->unit);
	else if (isfinite(v->found))
		snprintf(interval, size, "none given by the step");
}

static void verdict_section(struct review_doc *d, const struct review_project *p,
			    const struct review_plan *plan,
			    const struct review_verdict *v, int n)
{
	static const char *const head[6] = { "requirement", "required",
		"found", "interval (1 sigma)", "verdict", "figure" };
	char req[96], found[160], iv[160];
	const char *cells[6];
	int i, k, pass = 0, n_v = n;

	doc_h2(d, "Verdicts", "verdicts");
	for (i = 0; i < n; i++)
		pass += v[i].pass;
	doc_p(d, "%s: %d of %d requirements met.", p->name, pass, n);
	doc_table(d, 6, head);
	for (i = 0; i < n; i++) {
		snprintf(req, sizeof(req), "%s %.4g %s", v[i].le ? "<=" : ">=",
			 v[i].required, v[i].unit);
		fmt_found(&v[i], plan, found, iv, sizeof(found));
		cells[0] = v[i].key;
		cells[1] = req;
		cells[2] = found;
		cells[3] = iv;
		cells[4] = v[i].pass ? "PASS" : "FAIL";
		cells[5] = v[i].figure ? v[i].figure : "none (step not run)";
		doc_row(d, 6, cells);
	}
	doc_table_end(d);
	/* each figure once, in the order the verdicts name them */
	for (i = 0; i < n; i++) {
		for (k = 0; k < i; k++)
			if (v[k].figure && v[i].figure &&
			    strcmp(v[k].figure, v[i].figure) == 0)
				break;
		if (v[i].figure && k == i) {
			char cap[256];
			size_t n = 0;

			/* the caption names every verdict the figure shows */
			for (k = i; k < n_v && n < sizeof(cap); k++)
				if (v[k].figure && strcmp(v[k].figure, v[i].figure) == 0)
					n += (size_t)snprintf(cap + n, sizeof(cap) - n, "%s%s",
							      n ? ", " : "", v[k].key);
			doc_fig(d, v[i].figure, cap);
		}
	}
	doc_end_section(d);
}

static int write_one(const char *dir, const char *name, int html,
		     const struct review_project *p,
		     const struct review_plan *plan,
		     const struct review_verdict *v, int n,
		     struct stray_error *err)
{
	char path[REVIEW_PATH_MAX * 2];
	struct stray_file_out fo;
	struct review_doc d;
	int rc;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	if ((rc = stray_file_open_atomic(&fo, path, err)) != STRAY_OK)
		return rc;
	d.f = fo.f;
	d.html = html;
	if (html)
		fputs(html_head, d.f);
	fputs(html ? "<h1>" : "# ", d.f);
	doc_text(&d, "Design review: ");
	doc_text(&d, p->name);
	fputs(html ? "</h1>\n" : "\n\n", d.f);
	doc_p(&d, "Project file %s; stray %s.", p->path, stray_provenance_version());
	verdict_section(&d, p, plan, v, n);
	review_design(&d, dir, p, plan);
	review_step_sections(&d, dir, p, plan);
	if (html)
		fputs("</body></html>\n", d.f);
	return stray_file_commit(&fo, err);
}

int review_write(const char *dir, const struct review_project *p,
		 const struct review_plan *plan, struct stray_error *err)
{
	struct review_verdict v[REVIEW_REQ_MAX];
	char obj[REVIEW_PATH_MAX * 2], png[REVIEW_PATH_MAX * 2];
	int n = review_verdicts(dir, p, plan, v), rc;

	snprintf(obj, sizeof(obj), "%s/scene.obj", dir);
	snprintf(png, sizeof(png), "%s/design.png", dir);
	if (review_step_done(plan, "trace") && exists_file(dir, "scene.obj") &&
	    (rc = review_draw_section(obj, png, err)) != STRAY_OK)
		return rc;
	if ((rc = review_write_json(dir, p, plan, v, n, err)) != STRAY_OK)
		return rc;
	if ((rc = write_one(dir, "report.html", 1, p, plan, v, n, err)) != STRAY_OK)
		return rc;
	return write_one(dir, "report.md", 0, p, plan, v, n, err);
}
