/*
 * error.c - recording errors in a caller-owned record (freestanding).
 */
#include "stray/config.h"
#include "stray/error.h"

static const char *const status_text[STRAY_STATUS_COUNT] = {
	[STRAY_OK] = "ok",
	[STRAY_EINVAL] = "invalid value",
	[STRAY_EPARSE] = "malformed input",
	[STRAY_ENOTFOUND] = "not found",
	[STRAY_ERANGE] = "out of range",
	[STRAY_ENOCONV] = "no convergence",
	[STRAY_EIO] = "input/output error",
	[STRAY_ENOMEM] = "out of memory",
};

void stray_error_clear(struct stray_error *err)
{
	if (!err)
		return;
	err->code = STRAY_OK;
	err->field = 0;
	err->reason = 0;
	err->value = 0.0;
	err->has_value = 0;
	err->line = 0;
	err->file[0] = '\0';
	err->column[0] = '\0';
	err->text[0] = '\0';
}

int stray_error_set(struct stray_error *err, int code, const char *field,
		    const char *reason)
{
	if (err && err->code == STRAY_OK && code != STRAY_OK) {
		err->code = code;
		err->field = field;
		err->reason = reason;
	}
	return code;
}

int stray_error_set_value(struct stray_error *err, int code,
			  const char *field, const char *reason,
			  stray_real value)
{
	if (err && err->code == STRAY_OK && code != STRAY_OK) {
		stray_error_set(err, code, field, reason);
		err->value = value;
		err->has_value = 1;
	}
	return code;
}

const char *stray_status_text(int code)
{
	if (code < 0 || code >= STRAY_STATUS_COUNT)
		return "unknown error";
	return status_text[code];
}

int stray_status_is_bad_input(int code)
{
	return code == STRAY_EINVAL || code == STRAY_EPARSE ||
	       code == STRAY_ENOTFOUND;
}
