/*
 * fuzz_sensor_json.c - libFuzzer target for sensor files: cJSON parsing,
 * key mapping and range checks on arbitrary bytes (NUL-terminated copy);
 * a sensor that parses is run through its detector's models (issue 28:
 * thresholds, false stars and a star's detection at one alpha) with fixed
 * fluxes, so any number the checks let through meets the freestanding
 * code.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "stray/detector.h"
#include "stray/errfmt.h"
#include "stray/sensor_io.h"

/* The detector models on a sensor that parsed (st16-like-scale fluxes). */
static void run_detector(const struct stray_sensor *s)
{
	struct stray_fdr_model m;
	struct stray_detector d;
	enum stray_detector_kind k = STRAY_DET_THESIS;
	stray_real lr, p;

	if (s->detector[0] &&
	    stray_detector_parse(s->detector, &k, NULL) != STRAY_OK)
		return;
	stray_sensor_fdr_model(s, 5.6e21, 1.6e7, &m);
	m.read_noise_e = s->read_noise_e;
	m.dark_current_e_s = s->dark_current_e_s;
	stray_detector_init(&d, k, m.n_pps);
	if (s->detector_sigma > 0)
		d.sigma_k = s->detector_sigma;
	if (stray_detector_setup(&d, &m, NULL) != STRAY_OK)
		return;
	(void)stray_detector_log_false_rate(&d, &m, 1e-7, &lr, NULL);
	(void)stray_detector_star_prob(&d, &m, 1e-7,
				       stray_fdr_drs_photons(&m), &p, NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_sensor s;
	struct stray_error err;
	char *text = malloc(size + 1), line[1024];

	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = '\0';
	stray_error_clear(&err);
	if (stray_sensor_parse("fuzz.json", text, "/tmp", &s, &err) != STRAY_OK)
		stray_error_format(&err, line, sizeof(line));
	else
		run_detector(&s);
	free(text);
	return 0;
}
