/*
 * ccsds_kvn.c - epochs and the KVN line splitter shared by the OEM and AEM
 * readers (CCSDS 502.0-B-3, 504.0-B-2).
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/ccsds.h"
#include "stray/errfmt.h"

#define TT_MINUS_TAI 32.184
#define GPS_TAI (-19.0)

/* H. Hinnant's days_from_civil. */
long stray_ccsds_days_from_2000(long y, long m, long d)
{
	long era, yoe, doy, doe;

	y -= m <= 2;
	era = (y >= 0 ? y : y - 399) / 400;
	yoe = y - era * 400;
	doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
	doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
	return era * 146097 + doe - 719468 - 10957;
}

/* Its inverse (civil_from_days). */
static void civil_from_2000(long z, long *y, long *m, long *d)
{
	long era, doe, yoe, doy, mp;

	z += 719468 + 10957;
	era = (z >= 0 ? z : z - 146096) / 146097;
	doe = z - era * 146097;
	yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
	doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
	mp = (5 * doy + 2) / 153;
	*d = doy - (153 * mp + 2) / 5 + 1;
	*m = mp < 10 ? mp + 3 : mp - 9;
	*y = yoe + era * 400 + (*m <= 2);
}

/* TAI - UTC from 1972 (IERS Bulletin C): the months it stepped, one
 * second each, from 10 s at 1972-01-01; before 1972 the 10 s is kept. */
static const long leap_ym[] = {
	197207, 197301, 197401, 197501, 197601, 197701, 197801, 197901,
	198001, 198107, 198207, 198307, 198507, 198801, 199001, 199101,
	199207, 199307, 199407, 199601, 199707, 199901, 200601, 200901,
	201207, 201507, 201701,
};
#define N_LEAP (sizeof(leap_ym) / sizeof(leap_ym[0]))

/* TAI - UTC on the UTC day `day` (days from 2000-01-01): the latest step
 * first, so a recent epoch costs one comparison. */
static double tai_minus_utc(long day)
{
	size_t i;

	for (i = N_LEAP; i > 0; i--)
		if (day >= stray_ccsds_days_from_2000(leap_ym[i - 1] / 100,
						      leap_ym[i - 1] % 100, 1))
			return 10.0 + (double)i;
	return 10.0;
}

int stray_ccsds_time_system(const char *text)
{
	static const char *const names[] = { "UTC", "TAI", "TT", "GPS" };
	int i;

	for (i = 0; i < 4; i++)
		if (stray_kvn_eq(text, names[i]))
			return i;
	return -1;
}

int stray_kvn_eq(const char *a, const char *b)
{
	for (; *a && *b; a++, b++)
		if (toupper((unsigned char)*a) != toupper((unsigned char)*b))
			return 0;
	return *a == *b;
}

int stray_ccsds_inertial_frame(const char *text)
{
	return stray_kvn_eq(text, "EME2000") || stray_kvn_eq(text, "ICRF") ||
	       stray_kvn_eq(text, "GCRF") || stray_kvn_eq(text, "J2000");
}

static int leap_year(long y)
{
	return y % 4 == 0 && (y % 100 != 0 || y % 400 == 0);
}

/* Offset of time system ts from TT on UTC/TAI-like day `day` [s]. */
static double to_tt(int ts, long day)
{
	switch (ts) {
	case STRAY_TS_UTC: return tai_minus_utc(day) + TT_MINUS_TAI;
	case STRAY_TS_TAI: return TT_MINUS_TAI;
	case STRAY_TS_GPS: return TT_MINUS_TAI - GPS_TAI;
	default: return 0.0;
	}
}

int stray_ccsds_epoch(const char *text, int ts, double *t_tt)
{
	static const int mdays[12] = { 31, 28, 31, 30, 31, 30,
				       31, 31, 30, 31, 30, 31 };
	int y, a, b, hh, mm, n = 0, ordinal = 0;
	double ss;
	long day;
	const char *rest;

	if (sscanf(text, "%4d-%2d-%2dT%2d:%2d:%lf%n", &y, &a, &b, &hh, &mm,
		   &ss, &n) == 6 && text[4] == '-' && text[7] == '-' &&
	    text[10] == 'T')
		ordinal = 0;
	else if (n = 0, sscanf(text, "%4d-%3dT%2d:%2d:%lf%n", &y, &a, &hh,
			       &mm, &ss, &n) == 5 && text[4] == '-' &&
		 text[8] == 'T')
		ordinal = 1;
	else
		return -1;
	rest = text + n;
	if (*rest == 'Z')
		rest++;
	if (*rest != '\0' || y < 1900 || y > 2100 || hh < 0 || hh > 23 ||
	    mm < 0 || mm > 59 || !(ss >= 0.0 && ss < 61.0) ||
	    !isdigit((unsigned char)text[n - 1]))
		return -1;
	if (ordinal) {
		if (a < 1 || a > 365 + leap_year(y))
			return -1;
		day = stray_ccsds_days_from_2000(y, 1, 1) + a - 1;
	} else {
		if (a < 1 || a > 12 || b < 1 ||
		    b > mdays[a - 1] + (a == 2 && leap_year(y)))
			return -1;
		day = stray_ccsds_days_from_2000(y, a, b);
	}
	/* Second 60 exists only in UTC, at 23:59 of a day that ends in a
	 * leap second (the table above: TAI - UTC steps the next day). */
	if (ss >= 60.0 && (ts != STRAY_TS_UTC || hh != 23 || mm != 59 ||
			   tai_minus_utc(day + 1) == tai_minus_utc(day)))
		return -2;
	*t_tt = (double)day * 86400.0 + hh * 3600.0 + mm * 60.0 + ss +
		to_tt(ts, day) - 43200.0;
	return 0;
}

void stray_ccsds_format_epoch(double t_tt, int ts, char *buf, size_t size)
{
	double u = t_tt + 43200.0 - to_tt(ts, 0), s;
	long day, y, m, d, sec;
	int pass;

	/* The offset depends on the day it is for: settle it twice. */
	for (pass = 0; pass < 2; pass++) {
		day = (long)floor(u / 86400.0);
		u = t_tt + 43200.0 - to_tt(ts, day);
	}
	day = (long)floor(u / 86400.0);
	s = u - (double)day * 86400.0;
	/* Round to the microsecond first, so 59.9999997 is not printed 60. */
	s = floor(s * 1e6 + 0.5) / 1e6;
	if (s >= 86400.0) {
		s -= 86400.0;
		day++;
	}
	civil_from_2000(day, &y, &m, &d);
	sec = (long)floor(s);
	snprintf(buf, size, "%04ld-%02ld-%02ldT%02ld:%02ld:%09.6f", y, m, d,
		 sec / 3600, sec / 60 % 60, s - (double)(sec - sec % 60));
}

/* A decimal number as CCSDS writes one: [+-]digits[.digits][E[+-]digits].
 * strtod alone would also take hex floats (0x1p3), INF and NAN. */
static int decimal(const char *s)
{
	int digits = 0;

	if (*s == '+' || *s == '-')
		s++;
	for (; isdigit((unsigned char)*s); s++)
		digits++;
	if (*s == '.')
		for (s++; isdigit((unsigned char)*s); s++)
			digits++;
	if (!digits)
		return 0;
	if (*s == 'e' || *s == 'E') {
		s++;
		if (*s == '+' || *s == '-')
			s++;
		if (!isdigit((unsigned char)*s))
			return 0;
		while (isdigit((unsigned char)*s))
			s++;
	}
	return *s == '\0';
}

int stray_kvn_number(const char *s, double *x)
{
	char *end;

	if (!decimal(s))
		return 0;
	*x = strtod(s, &end);
	return end != s && *end == '\0' && isfinite(*x);
}

static char *trim(char *s)
{
	char *e;

	while (*s == ' ' || *s == '\t')
		s++;
	e = s + strlen(s);
	while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r'))
		*--e = '\0';
	return s;
}

int stray_kvn_next(const char *buf, size_t len, size_t *pos, long *lineno,
		   char *scratch, size_t scratch_size,
		   struct stray_kvn_line *line, const char *file,
		   struct stray_error *err)
{
	size_t start = *pos, end = start;
	char *s, *eq, *save = NULL, *tok;

	if (start >= len)
		return 0;
	while (end < len && buf[end] != '\n')
		end++;
	*pos = end < len ? end + 1 : end;
	++*lineno;
	if (end - start >= scratch_size)
		return stray_error_at(err, STRAY_EPARSE, file, *lineno, "line",
				      "longer than a KVN line may be"), -1;
	if (memchr(buf + start, '\0', end - start))
		return stray_error_at(err, STRAY_EPARSE, file, *lineno, "line",
				      "holds a NUL byte: not KVN text"), -1;
	memcpy(scratch, buf + start, end - start);
	scratch[end - start] = '\0';
	memset(line, 0, sizeof(*line));
	s = trim(scratch);
	if (*s == '\0') {
		line->kind = STRAY_KVN_BLANK;
		return 1;
	}
	if (strncmp(s, "COMMENT", 7) == 0 &&
	    (s[7] == '\0' || s[7] == ' ' || s[7] == '\t')) {
		line->kind = STRAY_KVN_COMMENT;
		return 1;
	}
	if ((eq = strchr(s, '=')) != NULL) {
		*eq = '\0';
		line->kind = STRAY_KVN_KEYVAL;
		line->key = trim(s);
		line->value = trim(eq + 1);
		return 1;
	}
	for (tok = strtok_r(s, " \t", &save); tok;
	     tok = strtok_r(NULL, " \t", &save)) {
		if (line->n_field == 16)
			return stray_error_at(err, STRAY_EPARSE, file, *lineno,
					      "data", "more than 16 fields"), -1;
		line->field[line->n_field++] = tok;
	}
	line->kind = line->n_field == 1 ? STRAY_KVN_WORD : STRAY_KVN_DATA;
	return 1;
}

#define KVN_LINE_MAX 1024

int stray_kvn_each(const char *buf, size_t len, const char *file,
		   long *lineno,
		   int (*fn)(void *ctx, const struct stray_kvn_line *line),
		   void *ctx, struct stray_error *err)
{
	struct stray_kvn_line l;
	char scratch[KVN_LINE_MAX];
	size_t pos = 0;
	int rc = STRAY_OK, got;

	while (rc == STRAY_OK &&
	       (got = stray_kvn_next(buf, len, &pos, lineno, scratch,
				     sizeof(scratch), &l, file, err)) != 0) {
		if (got < 0)
			rc = STRAY_EPARSE;
		else if (l.kind != STRAY_KVN_BLANK &&
			 l.kind != STRAY_KVN_COMMENT)
			rc = fn(ctx, &l);
	}
	return rc;
}

int stray_kvn_header_key(const char *key)
{
	return strcmp(key, "CREATION_DATE") == 0 ||
	       strcmp(key, "ORIGINATOR") == 0 ||
	       strcmp(key, "MESSAGE_ID") == 0 ||
	       strcmp(key, "CLASSIFICATION") == 0;
}

int stray_kvn_fail(struct stray_error *err, const char *file, long line,
		   const char *key, const char *why, const char *text)
{
	/* the keyword is named at run time: the line buffer does not last */
	stray_error_at(err, STRAY_EPARSE, file, line, "keyword", why);
	stray_error_column(err, key);
	stray_error_text(err, text);
	return STRAY_EPARSE;
}
