/*
 * fuzz_review_project.c - libFuzzer target for the project file of
 * `stray review` (review/project.c, review/mission.c) and the plan made
 * from a project that parses: arbitrary bytes, one-line errors, no leak.
 * Paths resolve under a folder that does not exist; built-in names only.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "review/review.h"
#include "stray/errfmt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct review_project p;
	static struct review_plan plan;
	struct stray_error err;
	char line[1024];

	stray_error_clear(&err);
	if (review_project_parse("dir/project.json", "/nonexistent-fuzz",
				 (const char *)data, size, &p, &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	if (p.n_req < 1 || p.n_req > REVIEW_REQ_MAX || p.n_heads > REVIEW_HEADS_MAX)
		abort();
	if (review_plan_make(&p, 10000, &plan, &err) != STRAY_OK)
		stray_error_format(&err, line, sizeof(line));
	review_plan_free(&plan);
	return 0;
}
