/*
 * cli_capture.h - a command run inside a library call (tools/api.c,
 * issue 32): what the command would print or write for its caller is
 * kept here instead.  While cli_capture is set, cli_json_emit keeps the
 * --json object, the one-line error goes to err rather than stderr, and
 * the commands hand over the curve they write (trace, reduce) and the
 * frames they render (frames).  NULL (the `stray` program): nothing is
 * kept and everything prints as usual.
 */
#ifndef STRAY_TOOLS_CLI_CAPTURE_H
#define STRAY_TOOLS_CLI_CAPTURE_H

#include <stddef.h>
#include <stdint.h>

#include <cJSON.h>

#include "stray/curve_io.h"

struct cli_capture {
	cJSON *json;		/* the --json object, or NULL */
	char err[1400];		/* the line stray prints on failure */
	struct stray_curve curve;	/* the curve written (trace, reduce) */
	int has_curve;
	char notes[4096];	/* cli_note lines, each ending '\n' */
	uint16_t *frames;	/* n_frames x rows x cols, malloc'd */
	size_t n_frames, max_frames;
	int rows, cols;
};

/* The capture of the running library call; NULL in `stray`. */
extern struct cli_capture *cli_capture;

/* Nonzero inside a library call. */
int cli_capturing(void);

/* A deep copy of c, kept as the call's curve; STRAY_OK or ENOMEM. */
int cli_capture_curve(const struct stray_curve *c, struct stray_error *err);

/* Frame `index` of `total` (cols x rows counts), copied into the call's
 * frame buffer (allocated at the first frame); STRAY_OK or ENOMEM. */
int cli_capture_frame(const uint16_t *dn, int cols, int rows, size_t index,
		      size_t total, struct stray_error *err);

/* line kept among the call's notes (a last line says when more did
 * not fit). */
void cli_capture_note(const char *line);

/* Free what c holds (the frame buffer too, unless taken: NULL). */
void cli_capture_free(struct cli_capture *c);

#endif /* STRAY_TOOLS_CLI_CAPTURE_H */
