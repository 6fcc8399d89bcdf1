/*
 * fuzz_rig_config.c - libFuzzer target: strayrigd's JSON config parser;
 * an accepted config keeps its arrays inside their bounds.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rig/config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct rig_config cfg;
	struct rig_error err;
	char *text = malloc(size + 1);

	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = '\0';
	rig_config_defaults(&cfg);
	rig_error_clear(&err);
	if (rig_config_parse(&cfg, "fuzz.json", text, &err) == RIG_OK &&
	    (cfg.wheel.n_slots < 1 || cfg.wheel.n_slots > 12 ||
	     cfg.camera.n_rows < 1 || cfg.camera.n_rows > 24 ||
	     cfg.sim.n_faults > RIG_FAULTS_MAX || cfg.sim.vlab.n_ghosts > 4))
		__builtin_trap();
	if (err.code != RIG_OK && strchr(err.msg, '\n'))
		__builtin_trap();
	free(text);
	return 0;
}
