/*
 * fuzz_rig_control.c - libFuzzer target: strayrigd's control-socket
 * request parser; an accepted request has a known command and, for move,
 * a finite angle, and the refusal text is always one line.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rig/daemon.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct rig_request req;
	char msg[RIG_ERROR_MSG_MAX];
	char *text = malloc(size + 1);
	int rc;

	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = '\0';
	rc = rig_request_parse(text, &req, msg, sizeof(msg));
	if (rc == RIG_OK && (req.cmd < 0 || req.cmd >= RIG_CMD_COUNT ||
			     (req.cmd == RIG_CMD_MOVE &&
			      !isfinite(req.theta_deg))))
		__builtin_trap();
	if (rc != RIG_OK && (!msg[0] || strchr(msg, '\n')))
		__builtin_trap();
	free(text);
	return 0;
}
