/*
 * format.c - the names of a sweep folder (sweep_store.h): frame types
 * and frame file names, and a file listed twice.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/sweep_store.h"

static const char *const type_names[STRAY_SWEEP_FRAMETYP_COUNT] = {
	"DARK", "AMBIENT", "FULL"
};

int stray_sweep_frametyp_parse(const char *text)
{
	int t;

	for (t = 0; t < STRAY_SWEEP_FRAMETYP_COUNT; t++)
		if (strcmp(text, type_names[t]) == 0)
			return t;
	return -1;
}

const char *stray_sweep_frametyp_name(int type)
{
	return type >= 0 && type < STRAY_SWEEP_FRAMETYP_COUNT
		? type_names[type] : "?";
}

void stray_sweep_frame_filename(const struct stray_sweep_frame *f,
				char *out, size_t size)
{
	snprintf(out, size, "a%+08.3f_%s_%03ld.fits", f->angle_deg,
		 stray_sweep_frametyp_name(f->type), f->seqnum);
}

/* Days since 1970-01-01 of a civil date (proleptic Gregorian). */
static long days_from_civil(long y, long m, long d)
{
	long era, yoe, doy, doe;

	y -= m <= 2;
	era = (y >= 0 ? y : y - 399) / 400;
	yoe = y - era * 400;
	doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
	doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
	return era * 146097 + doe - 719468;
}

void stray_sweep_utc_format(double t, char *out, size_t size)
{
	long long ms = (long long)floor(t * 1000.0 + 0.5);
	long long s = ms / 1000, day = s / 86400, sod = s % 86400;
	long z = (long)day + 719468, era = (z >= 0 ? z : z - 146096) / 146097;
	long doe = z - era * 146097;
	long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
	long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
	long mp = (5 * doy + 2) / 153, d = doy - (153 * mp + 2) / 5 + 1;
	long m = mp < 10 ? mp + 3 : mp - 9, y = yoe + era * 400 + (m <= 2);

	snprintf(out, size, "%04ld-%02ld-%02ldT%02d:%02d:%02d.%03dZ", y, m, d,
		 (int)(sod / 3600), (int)(sod / 60 % 60), (int)(sod % 60),
		 (int)(ms % 1000));
}

int stray_sweep_utc_parse(const char *text, double *t)
{
	int y, mo, d, h, mi, sec, n = 0, k;
	double frac = 0, scale = 0.1;
	static const int mdays[12] = { 31, 29, 31, 30, 31, 30, 31, 31, 30,
				       31, 30, 31 };

	if (sscanf(text, "%4d-%2d-%2dT%2d:%2d:%2d%n", &y, &mo, &d, &h, &mi,
		   &sec, &n) != 6 || n != 19)
		return STRAY_EPARSE;
	if (text[n] == '.') {
		for (k = 1; k <= 6 && text[n + k] >= '0' && text[n + k] <= '9';
		     k++, scale /= 10)
			frac += (text[n + k] - '0') * scale;
		if (k == 1)
			return STRAY_EPARSE;
		n += k;
	}
	if (text[n] == 'Z')
		n++;
	if (text[n] || y < 1970 || y > 9999 || mo < 1 || mo > 12 || d < 1 ||
	    d > mdays[mo - 1] || h > 23 || mi > 59 || sec > 60 || h < 0 ||
	    mi < 0 || sec < 0)
		return STRAY_EPARSE;
	*t = (double)days_from_civil(y, mo, d) * 86400.0 + h * 3600.0 +
	     mi * 60.0 + sec + frac;
	return STRAY_OK;
}

struct file_key {
	const char *file;
	long line;
	size_t index;
};

static int by_file(const void *a, const void *b)
{
	const struct file_key *x = a, *y = b;
	int c = strcmp(x->file, y->file);

	return c ? c : (x->line > y->line) - (x->line < y->line);
}

int stray_sweep_repeated_file(const void *rows, size_t n, size_t size,
			      size_t name_off, size_t line_off, size_t *dup)
{
	const unsigned char *base = rows;
	struct file_key *k = malloc((n ? n : 1) * sizeof(*k));
	size_t i;

	*dup = n;
	if (!k)
		return STRAY_ENOMEM;
	for (i = 0; i < n; i++) {
		const unsigned char *r = base + i * size;

		k[i].file = (const char *)(r + name_off);
		memcpy(&k[i].line, r + line_off, sizeof(long));
		k[i].index = i;
	}
	qsort(k, n, sizeof(*k), by_file);
	for (i = 1; i < n; i++)	/* sorted: a repeat follows its first */
		if (strcmp(k[i].file, k[i - 1].file) == 0 &&
		    (*dup == n || k[i].line < k[*dup].line))
			*dup = i;
	if (*dup < n)
		*dup = k[*dup].index;
	free(k);
	return STRAY_OK;
}
