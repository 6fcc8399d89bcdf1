/*
 * sim_monitor.c - device side of the lamp monitor photodiode
 * (monitor_report.h): answers each READ with the photocurrent of the
 * virtual lamp, nominal_pa times the lamp's drift factor, with +-0.05 %
 * noise (sim.monitor_noise), or a 50 pA dark current when the lamp is
 * off.  A timeout fault drops the answer.
 */
#include <math.h>
#include <string.h>

#include "rig/monitor_report.h"
#include "rig/sim_devices.h"
#include "rig/status.h"
#include "rig/vlab.h"

#define DARK_PA 50.0

/*
 * Deterministic small noise from the lab seed and the read count: a
 * splitmix64 hash of both, so successive reads are independent (white,
 * as a photodiode's read noise is) and sweeps of other seeds differ.
 * (A multiplicative hash of the count alone drifted smoothly from read
 * to read and was the same for every seed.)
 */
static double noise(uint64_t seed, uint32_t n, double frac)
{
	uint64_t z = seed * 0x9E3779B97F4A7C15ull + n;

	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	z ^= z >> 31;
	return ((double)(z >> 11) / 9007199254740992.0 - 0.5) * 2 * frac;
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
	pa *= 1 + noise(core->cfg->sim.vlab.seed, ++m->reads,
			core->cfg->sim.monitor_noise);
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
