/*
 * sim_core.c - the simulator's core (sim_core.h): virtual clock, event
 * counts, the fault schedule and the unplugged devices.
 */
#include <signal.h>
#include <string.h>

#include "rig/sim_core.h"

void rig_sim_core_init(struct rig_sim_core *core,
		       const struct rig_config *cfg)
{
	memset(core, 0, sizeof(*core));
	core->cfg = cfg;
}

int rig_sim_core_fault_active(const struct rig_sim_core *core, int dev,
			      int kind)
{
	const struct rig_sim_config *sc = &core->cfg->sim;
	unsigned n = core->events[dev];
	int i;

	for (i = 0; i < sc->n_faults; i++) {
		const struct rig_fault *f = &sc->faults[i];

		if (f->device == dev && f->kind == kind && n >= f->at &&
		    n < f->at + f->count)
			return 1;
	}
	return 0;
}

void rig_sim_core_disconnect(struct rig_sim_core *core, int dev,
			     unsigned reopen_fails)
{
	core->gone[dev] = 1;
	core->open_fail[dev] = reopen_fails;
}

int rig_sim_core_event(struct rig_sim_core *core, int dev, double *value)
{
	const struct rig_sim_config *sc = &core->cfg->sim;
	unsigned n = ++core->events[dev];
	int i;

	for (i = 0; i < sc->n_faults; i++) {
		const struct rig_fault *f = &sc->faults[i];

		/* A disconnect or kill happens once; its count is the
		 * number of re-opens that fail (the time to replug). */
		unsigned last = f->kind == RIG_FAULT_DISCONNECT ||
				f->kind == RIG_FAULT_KILL ? f->at
							  : f->at + f->count - 1;

		if (f->device != dev || n < f->at || n > last)
			continue;
		core->fault_hits[i]++;
		core->faults_fired++;
		if (value)
			*value = f->value;
		if (f->kind == RIG_FAULT_KILL)
			raise(SIGKILL);
		if (f->kind == RIG_FAULT_DISCONNECT)
			rig_sim_core_disconnect(core, dev, f->count);
		return f->kind;
	}
	return -1;
}

int rig_sim_core_open(struct rig_sim_core *core, int dev)
{
	if (core->open_fail[dev] > 0) {
		core->open_fail[dev]--;
		return RIG_EDISCONNECT;
	}
	core->gone[dev] = 0;
	return RIG_OK;
}
