/*
 * review_int.h - what the review's own files share: the verdicts, the
 * steps' JSON outputs, the report's writers.
 */
#ifndef REVIEW_INT_H
#define REVIEW_INT_H

#include <cjson/cJSON.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include "review/review.h"

struct review_verdict {
	const char *key, *unit, *figure, *step;
	double required, found, lo, hi;	/* NaN: none */
	int le;				/* pass when found <= required */
	int pass;
};

static inline int access_ok(const char *path)
{
	return access(path, R_OK);
}

static inline int exists_file(const char *dir, const char *name)
{
	char path[REVIEW_PATH_MAX * 2];
	struct stat st;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* verdicts.c: a step as review.json and the manifest give it (name,
 * status, seconds, outputs - taken - and why). */
cJSON *review_step_json(const struct review_step *s, cJSON *outputs);

/* project_keys.c: an error on key (a run-time name) of the project file. */
int review_bad(struct stray_error *err, const struct review_project *p,
	       const char *key, const char *value, const char *reason);

/* project_keys.c: a key given twice in obj (*key); keys of obj outside
 * allowed[] (NULL-ended) or given twice refused, naming where. */
int review_dup_key(const cJSON *obj, const char **key);
int review_only_keys(const cJSON *obj, const char *const *allowed,
		     const char *where, const struct review_project *p,
		     struct stray_error *err);

/* dir/name parsed, or NULL when absent or not JSON. */
cJSON *review_read_json(const char *dir, const char *name);
const struct review_step *review_step_named(const struct review_plan *plan,
					    const char *name);
int review_step_done(const struct review_plan *plan, const char *name);

int review_verdicts(const char *dir, const struct review_project *p,
		    const struct review_plan *plan, struct review_verdict *v);
int review_write_json(const char *dir, const struct review_project *p,
		      const struct review_plan *plan,
		      const struct review_verdict *v, int n,
		      struct stray_error *err);

/* The report's two writers share one text model: a section at a time. */
struct review_doc {
	FILE *f;
	int html;
};
void doc_h2(struct review_doc *d, const char *title, const char *id);
void doc_p(struct review_doc *d, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));
void doc_table(struct review_doc *d, int ncol, const char *const *head);
void doc_row(struct review_doc *d, int ncol, const char *const *cells);
void doc_table_end(struct review_doc *d);
void doc_fig(struct review_doc *d, const char *src, const char *alt);
void doc_end_section(struct review_doc *d);
void doc_text(struct review_doc *d, const char *text);

/* A JSON object as tables (doc.c); skip: keys left out (NULL-ended). */
void review_json_tables(struct review_doc *d, const cJSON *o,
			const char *title, const char *const *skip);
const char *review_unit(const char *key);

/* The report's sections (report_steps.c). */
void review_design(struct review_doc *d, const char *dir,
		   const struct review_project *p,
		   const struct review_plan *plan);
void review_step_sections(struct review_doc *d, const char *dir,
			  const struct review_project *p,
			  const struct review_plan *plan);

#endif /* REVIEW_INT_H */
