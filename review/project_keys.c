/*
 * project_keys.c - what the readers of the project file (project.c, the
 * project; mission.c, its mission and heads) share: one error naming the
 * file, the key and its value, and the keys an object may hold.
 */
#include <cjson/cJSON.h>
#include <string.h>

#include "review/review.h"
#include "review_int.h"
#include "stray/errfmt.h"

int review_bad(struct stray_error *err, const struct review_project *p,
	       const char *key, const char *value, const char *reason)
{
	stray_error_at(err, STRAY_EINVAL, p->path, 0, NULL, reason);
	stray_error_column(err, key);
	if (value)
		stray_error_text(err, value);
	return STRAY_EINVAL;
}

/* A key given twice in obj (JSON allows it; a reader takes one of the
 * two, so the other would be silently dropped). */
int review_dup_key(const cJSON *obj, const char **key)
{
	const cJSON *it, *jt;

	cJSON_ArrayForEach(it, obj)
		for (jt = obj->child; jt != it; jt = jt->next)
			if (it->string && jt->string &&
			    strcmp(it->string, jt->string) == 0) {
				*key = it->string;
				return 1;
			}
	return 0;
}

/* Keys of obj outside allowed[] are an error, as is a key given twice. */
int review_only_keys(const cJSON *obj, const char *const *allowed,
		     const char *where, const struct review_project *p,
		     struct stray_error *err)
{
	const cJSON *it;
	const char *dup;
	int i;

	if (review_dup_key(obj, &dup))
		return review_bad(err, p, where, dup, "key given twice");
	cJSON_ArrayForEach(it, obj) {
		for (i = 0; allowed[i]; i++)
			if (strcmp(it->string, allowed[i]) == 0)
				break;
		if (!allowed[i])
			return review_bad(err, p, where, it->string,
				   "unknown key (docs/review.md)");
	}
	return STRAY_OK;
}
