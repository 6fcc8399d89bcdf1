/*
 * cli_capture.c - what a command hands to a library call instead of
 * printing it (tools/cli_capture.h).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli_capture.h"

struct cli_capture *cli_capture;

int cli_capturing(void)
{
	return cli_capture != NULL;
}

static int nomem(struct stray_error *err, const char *what)
{
	return stray_error_set(err, STRAY_ENOMEM, what, "out of memory");
}

int cli_capture_curve(const struct stray_curve *c, struct stray_error *err)
{
	struct stray_curve *k;
	size_t i;
	int rc;

	if (!cli_capture)
		return STRAY_OK;
	k = &cli_capture->curve;
	stray_curve_free(k);
	cli_capture->has_curve = 0;
	if ((rc = stray_curve_alloc(k, c->n, c->sigma != NULL, err)))
		return rc;
	memcpy(k->theta_deg, c->theta_deg, c->n * sizeof(double));
	memcpy(k->alpha, c->alpha, c->n * sizeof(double));
	if (c->sigma)
		memcpy(k->sigma, c->sigma, c->n * sizeof(double));
	for (i = 0; i < c->n_extra && !rc; i++)
		rc = stray_curve_add_column(k, c->extra_name[i], c->extra[i],
					    err);
	if (!rc && c->n_meta) {
		k->meta = calloc(c->n_meta, sizeof(char *));
		if (!k->meta)
			rc = nomem(err, "curve");
		for (i = 0; !rc && i < c->n_meta; i++) {
			k->meta[i] = strdup(c->meta[i]);
			if (!k->meta[i])
				rc = nomem(err, "curve");
			else
				k->n_meta = i + 1;
		}
	}
	if (rc)
		stray_curve_free(k);
	else
		cli_capture->has_curve = 1;
	return rc;
}

int cli_capture_frame(const uint16_t *dn, int cols, int rows, size_t index,
		      size_t total, struct stray_error *err)
{
	struct cli_capture *k = cli_capture;
	size_t px = (size_t)cols * (size_t)rows;

	if (!k)
		return STRAY_OK;
	if (!k->frames) {
		/* the whole run's frames in one buffer: Python's array of
		 * shape (frames, rows, cols) is a view of it, not a copy */
		if (px == 0 || total > SIZE_MAX / sizeof(uint16_t) / px)
			return nomem(err, "frames");
		k->frames = malloc(total * px * sizeof(uint16_t));
		if (!k->frames)
			return nomem(err, "frames");
		k->max_frames = total;
		k->cols = cols;
		k->rows = rows;
	}
	if (index >= k->max_frames || cols != k->cols || rows != k->rows)
		return stray_error_set(err, STRAY_EINVAL, "frames",
				       "frame outside the run's buffer");
	memcpy(k->frames + index * px, dn, px * sizeof(uint16_t));
	if (index + 1 > k->n_frames)
		k->n_frames = index + 1;
	return STRAY_OK;
}

void cli_capture_note(const char *line)
{
	static const char more[] = "(more notes than fit)\n";
	char *n = cli_capture->notes;
	size_t len = strlen(n), cap = sizeof(cli_capture->notes);
	size_t need = strlen(line) + 1;

	if (len + need + sizeof(more) > cap) {
		if (!strstr(n, more) && len + sizeof(more) <= cap)
			memcpy(n + len, more, sizeof(more));
		return;
	}
	memcpy(n + len, line, need - 1);
	n[len + need - 1] = '\n';
	n[len + need] = '\0';
}

void cli_capture_free(struct cli_capture *c)
{
	cJSON_Delete(c->json);
	c->json = NULL;
	stray_curve_free(&c->curve);
	c->has_curve = 0;
	free(c->frames);
	c->frames = NULL;
	c->n_frames = c->max_frames = 0;
}
