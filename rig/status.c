/*
 * status.c - code-to-text table and the first-error-wins record.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "rig/status.h"

static const char *const status_text[RIG_STATUS_COUNT] = {
	[RIG_OK] = "ok",
	[RIG_EINVAL] = "invalid value",
	[RIG_EPARSE] = "malformed input",
	[RIG_EIO] = "i/o error",
	[RIG_ETIMEOUT] = "timed out",
	[RIG_EDISCONNECT] = "device disconnected",
	[RIG_ECRC] = "CRC mismatch",
	[RIG_EPROTO] = "protocol violation",
	[RIG_ETARGET] = "target missed",
	[RIG_EINTERLOCK] = "refused by interlock",
	[RIG_EDEVICE] = "device error",
	[RIG_ENOMEM] = "out of memory",
	[RIG_EAGAIN] = "incomplete",
	[RIG_ESTATE] = "wrong state",
	[RIG_ERANGE] = "out of range",
};

void rig_error_clear(struct rig_error *err)
{
	if (err) {
		err->code = RIG_OK;
		err->msg[0] = '\0';
	}
}

int rig_error_set(struct rig_error *err, int code, const char *fmt, ...)
{
	va_list ap;
	char *p;

	if (!err || err->code != RIG_OK)
		return code;
	err->code = code;
	va_start(ap, fmt);
	vsnprintf(err->msg, sizeof(err->msg), fmt, ap);
	va_end(ap);
	/* One line, whatever the offending text held. */
	for (p = err->msg; *p; p++)
		if ((unsigned char)*p < 0x20 || *p == 0x7f)
			*p = '?';
	return code;
}

const char *rig_status_text(int code)
{
	if (code < 0 || code >= RIG_STATUS_COUNT || !status_text[code])
		return "unknown status";
	return status_text[code];
}

int rig_status_is_transient(int code)
{
	return code == RIG_ETIMEOUT || code == RIG_EDISCONNECT ||
	       code == RIG_ECRC || code == RIG_ETARGET;
}
