/*
 * sim_monitor.c - device side of the lamp monitor photodiode
 * (monitor_report.h): answers each READ with the photocurrent of the
 * virtual lamp, nominal_pa times the lamp's drift factor, with 0.05 %
 * noise, or a 50 pA dark current when the lamp is off.  A timeout fault
 * drops the answer.
 */
#include <math.h>
#include <string.h>

#include "rig/monitor_report.h"
#include "rig/sim_devices.h"
#include "rig/status.h"
#include "rig/vlab.h"

#define DARK_PA 50.0
#define NOISE_FRAC 5e-4

/* Deterministic small noise from the read count (a hash, not an RNG). */
static double noise(uint32_t n)
{
	uint32_t h = n * 2654435761u;

	h ^= h >> 16;
	return ((double)(h & 0xffff) / 65535.0 - 0.5) * 2 * NOISE_FRAC;
}

int rig_sim_monitor_write(struct sim_monitor *m, struct rig_sim_core *core,
			  int lamp_on, const uint8_t *buf, size_t len)
{
	struct rig_monitor_in in;
	double pa;
	uint8_t seq;
	int kind;

	if (rig_monitor_out_decode(buf, len, &seq) != RIG_OK)
		return RIG_OK;
	kind = rig_sim_core_event(core, RIG_DEV_MONITOR, NULL);
	if (core->gone[RIG_DEV_MONITOR])
		return RIG_EDISCONNECT;
	if (kind == RIG_FAULT_TIMEOUT || kind == RIG_FAULT_STALL)
		return RIG_OK;
	pa = lamp_on
		     ? core->cfg->monitor.nominal_pa *
			       rig_vlab_lamp_factor(&core->cfg->sim.vlab,
						    core->t_s)
		     : DARK_PA;
	pa *= 1 + noise(++m->reads);
	memset(&in, 0, sizeof(in));
	in.seq = seq;
	in.current_pa = pa >= 4294967295.0 ? 0xffffffffu
					   : (uint32_t)lround(pa);
	in.flags = pa >= 4294967295.0 ? RIG_MONITOR_OVERRANGE : 0;
	rig_monitor_in_encode(&in, m->report);
	m->have_report = 1;
	return RIG_OK;
}

int rig_sim_monitor_read(struct sim_monitor *m, struct rig_sim_core *core,
			 uint8_t *buf, size_t cap, size_t *got,
			 unsigned timeout_ms)
{

	if (!m->have_report || cap < RIG_MONITOR_REPORT_LEN) {
		core->t_s += timeout_ms * 1e-3;
		return RIG_ETIMEOUT;
	}
	memcpy(buf, m->report, RIG_MONITOR_REPORT_LEN);
	*got = RIG_MONITOR_REPORT_LEN;
	m->have_report = 0;
	return RIG_OK;
}

void rig_sim_monitor_reset(struct sim_monitor *m)
{
	m->have_report = 0;
}
