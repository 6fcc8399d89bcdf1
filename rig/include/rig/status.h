/*
 * status.h - the rig's status codes and its one error record.
 *
 * Every fallible rig function returns an int from enum rig_status (0 = OK)
 * and, given a caller-owned struct rig_error, records one line naming the
 * device, field and value.  The first error wins (SQLite's
 * sqlite3ErrorWithMsg), so the low-level cause survives the callers'
 * generic retries.
 */
#ifndef RIG_STATUS_H
#define RIG_STATUS_H

enum rig_status {
	RIG_OK = 0,
	RIG_EINVAL,	/* a value or command is out of its domain */
	RIG_EPARSE,	/* malformed config, message or request */
	RIG_EIO,	/* a file could not be written or read */
	RIG_ETIMEOUT,	/* a device did not answer in time */
	RIG_EDISCONNECT,	/* a device is gone from the bus */
	RIG_ECRC,	/* a frame failed its CRC32 */
	RIG_EPROTO,	/* a device sent something the protocol forbids */
	RIG_ETARGET,	/* the stage stopped away from its target */
	RIG_EINTERLOCK,	/* refused: it would break an interlock */
	RIG_EDEVICE,	/* a device reported an error or failed read-back */
	RIG_ENOMEM,
	RIG_EAGAIN,	/* incomplete: more bytes needed */
	RIG_ESTATE,	/* not possible in the current state */
	RIG_ERANGE,	/* no setting in the allowed range */
	RIG_STATUS_COUNT
};

#define RIG_ERROR_MSG_MAX 240

struct rig_error {
	int code;
	char msg[RIG_ERROR_MSG_MAX];
};

/* Reset to "no error". */
void rig_error_clear(struct rig_error *err);

/*
 * Record code and a printf-style one-line message unless an error is
 * already recorded; err may be NULL.  Returns code.
 */
int rig_error_set(struct rig_error *err, int code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* Static text of a code; never NULL. */
const char *rig_status_text(int code);

/* True for faults a retry or reconnect may cure. */
int rig_status_is_transient(int code);

#endif /* RIG_STATUS_H */
