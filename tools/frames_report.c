/*
 * frames_report.c - what `stray frames` prints: the lost stars per
 * magnitude (frames/frames_lost.h) as JSON and as text.
 */
#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "frames_report.h"

static const char *const det_name[2] = { "thesis", "threshold" };

void frames_lost_json(const struct frames_lost *l, cJSON *o)
{
	cJSON *ls = cJSON_AddObjectToObject(o, "lost_stars");
	int d, b;

	for (d = 0; d < 2; d++) {
		cJSON *a = cJSON_AddArrayToObject(ls, det_name[d]);

		for (b = 0; b < FRAMES_LOST_BINS; b++) {
			cJSON *e;
			double n = (double)l->n[b], f;

			if (l->n[b] == 0)
				continue;
			f = l->found[d][b] / n;
			e = cJSON_CreateObject();
			cJSON_AddItemToObject(e, "mag_lo", cli_json_number(
				FRAMES_LOST_MAG0 + b * FRAMES_LOST_STEP));
			cJSON_AddItemToObject(e, "mag_hi", cli_json_number(
				FRAMES_LOST_MAG0 + (b + 1) * FRAMES_LOST_STEP));
			cJSON_AddItemToObject(e, "stars", cli_json_number(n));
			cJSON_AddItemToObject(e, "found", cli_json_number(f));
			cJSON_AddItemToObject(e, "sigma", cli_json_number(
				sqrt(f * (1.0 - f) / n)));
			cJSON_AddItemToObject(e, "model", cli_json_number(
				l->model[d][b] / n));
			cJSON_AddItemToArray(a, e);
		}
	}
}

void frames_lost_print(const struct frames_lost *l)
{
	int d, b;

	for (d = 0; d < 2; d++)
		for (b = 0; b < FRAMES_LOST_BINS; b++) {
			double n = (double)l->n[b];

			if (l->n[b] < 20)
				continue;
			printf("  %-9s stars m %.2f-%.2f: found %.3f (model %.3f) of %ld\n",
			       det_name[d], FRAMES_LOST_MAG0 + b * FRAMES_LOST_STEP,
			       FRAMES_LOST_MAG0 + (b + 1) * FRAMES_LOST_STEP,
			       l->found[d][b] / n, l->model[d][b] / n, l->n[b]);
		}
}
