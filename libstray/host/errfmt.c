/*
 * errfmt.c - the hosted half of the error path: where, and the one line.
 */
#include <stdio.h>
#include <string.h>

#include "stray/errfmt.h"

/*
 * Copy src into dst, escaping what a terminal must not be sent raw:
 * control bytes always, and bytes >= 0x80 too when high is set (the
 * offending text may be binary garbage; file names may be UTF-8).
 */
static void copy_escaped(char *dst, size_t size, const char *src, int high)
{
	static const char hex[] = "0123456789abcdef";
	size_t o = 0;

	for (; *src && o + 1 < size; src++) {
		unsigned char ch = (unsigned char)*src;

		if (ch >= 0x20 && ch != 0x7f && (ch < 0x80 || !high)) {
			dst[o++] = (char)ch;
			continue;
		}
		if (o + 5 > size)
			break;
		dst[o++] = '\\';
		dst[o++] = 'x';
		dst[o++] = hex[ch >> 4];
		dst[o++] = hex[ch & 15];
	}
	dst[o] = '\0';
}

static void copy_text(char *dst, size_t size, const char *src)
{
	copy_escaped(dst, size, src, 0);
}

void stray_error_locate(struct stray_error *err, const char *file, long line)
{
	if (!err)
		return;
	if (file && err->file[0] == '\0')
		copy_text(err->file, sizeof(err->file), file);
	if (line > 0 && err->line == 0)
		err->line = line;
}

void stray_error_text(struct stray_error *err, const char *text)
{
	if (err && text && err->text[0] == '\0')
		copy_escaped(err->text, sizeof(err->text), text, 1);
}

void stray_error_column(struct stray_error *err, const char *name)
{
	if (err && name && err->column[0] == '\0')
		copy_text(err->column, sizeof(err->column), name);
}

int stray_error_at(struct stray_error *err, int code, const char *file,
		   long line, const char *field, const char *reason)
{
	if (err && err->code == STRAY_OK) {
		stray_error_set(err, code, field, reason);
		stray_error_locate(err, file, line);
	}
	return code;
}

char *stray_error_format(const struct stray_error *err, char *buf,
			 size_t size)
{
	char where[STRAY_ERROR_FILE_MAX + 24] = "";
	char what[STRAY_ERROR_COLUMN_MAX + STRAY_ERROR_TEXT_MAX + 64] = "";
	const char *reason = err->reason ? err->reason
					 : stray_status_text(err->code);
	const char *field = err->column[0] ? err->column
			    : err->field ? err->field : "value";

	if (err->file[0] && err->line > 0)
		snprintf(where, sizeof(where), "%s:%ld: ", err->file, err->line);
	else if (err->file[0])
		snprintf(where, sizeof(where), "%s: ", err->file);
	if (err->text[0])
		snprintf(what, sizeof(what), "%s '%s': ", field, err->text);
	else if (err->has_value)
		snprintf(what, sizeof(what), "%s %.10g: ", field, err->value);
	else if (err->field || err->column[0])
		snprintf(what, sizeof(what), "%s: ", field);
	snprintf(buf, size, "%s%s%s", where, what, reason);
	return buf;
}
