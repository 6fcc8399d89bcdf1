/*
 * angles.c - parse angle lists and ranges.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "tracer/angles.h"

static int bad_item(struct stray_error *err, const char *item,
		    const char *why)
{
	stray_error_set(err, STRAY_EINVAL, "--angles", why);
	stray_error_text(err, item);
	return STRAY_EINVAL;
}

/* Up to three ':'-separated finite numbers; returns how many, -1 if bad. */
static int numbers(const char *item, double v[3])
{
	const char *p = item;
	int n = 0;

	for (;;) {
		char *end;

		if (n == 3)
			return -1;
		errno = 0;
		v[n] = strtod(p, &end);
		if (end == p || errno || !isfinite(v[n]))
			return -1;
		n++;
		if (*end == '\0')
			return n;
		if (*end != ':')
			return -1;
		p = end + 1;
	}
}

static int push(double **a, size_t *n, size_t *cap, double v)
{
	if (*n == *cap) {
		size_t c = *cap ? 2 * *cap : 64;
		double *q = realloc(*a, c * sizeof(double));

		if (!q)
			return STRAY_ENOMEM;
		*a = q;
		*cap = c;
	}
	(*a)[(*n)++] = v;
	return STRAY_OK;
}

static int add_item(const char *item, double **a, size_t *n, size_t *cap,
		    struct stray_error *err)
{
	double v[3], count;
	int k = numbers(item, v);
	long i;

	if (k == 1)
		return push(a, n, cap, v[0]);
	if (k != 3)
		return bad_item(err, item, "expected a number or start:stop:step");
	if (!(v[2] > 0.0) || v[1] < v[0])
		return bad_item(err, item, "range needs step > 0 and stop >= start");
	count = floor((v[1] - v[0]) / v[2] + 1e-9) + 1.0;
	if (count + (double)*n > TRACER_ANGLES_MAX)
		return bad_item(err, item, "too many angles");
	for (i = 0; i < (long)count; i++)
		if (push(a, n, cap, v[0] + (double)i * v[2]))
			return STRAY_ENOMEM;
	return STRAY_OK;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

int tracer_angles_parse(const char *list, double **theta_deg, size_t *n,
			struct stray_error *err)
{
	char *copy = strdup(list), *save = NULL, *item;
	double *a = NULL;
	size_t cnt = 0, cap = 0, i, m = 0;
	int rc = STRAY_OK;

	if (!copy)
		return stray_error_set(err, STRAY_ENOMEM, "--angles",
				       "out of memory");
	for (item = strtok_r(copy, ",", &save); item && !rc;
	     item = strtok_r(NULL, ",", &save))
		rc = add_item(item, &a, &cnt, &cap, err);
	if (!rc && cnt == 0)
		rc = bad_item(err, list, "no angles given");
	for (i = 0; i < cnt && !rc; i++)
		if (!(a[i] >= 0.0 && a[i] <= 180.0))
			rc = stray_error_set_value(err, STRAY_EINVAL, "--angles",
				"angle must be in [0, 180] deg", a[i]);
	if (rc == STRAY_ENOMEM)
		stray_error_set(err, rc, "--angles", "out of memory");
	free(copy);
	if (rc) {
		free(a);
		return rc;
	}
	qsort(a, cnt, sizeof(double), cmp_double);
	for (i = 0; i < cnt; i++)	/* merge duplicates (range joints) */
		if (m == 0 || a[i] - a[m - 1] > 1e-9)
			a[m++] = a[i];
	*theta_deg = a;
	*n = m;
	return STRAY_OK;
}

int tracer_angles_with_zero(double **theta_deg, size_t *n, int *added,
			    struct stray_error *err)
{
	double *t;

	*added = 0;
	if ((*theta_deg)[0] == 0.0)
		return STRAY_OK;
	t = realloc(*theta_deg, (*n + 1) * sizeof(double));
	if (!t)
		return stray_error_set(err, STRAY_ENOMEM, "--angles",
				       "out of memory");
	memmove(t + 1, t, *n * sizeof(double));
	t[0] = 0.0;	/* alpha is normalised to P(0) (ref4-baffle.md) */
	*theta_deg = t;
	(*n)++;
	*added = 1;
	return STRAY_OK;
}
