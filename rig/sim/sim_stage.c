/*
 * sim_stage.c - device side of a K10CR1-class APT rotation mount behind
 * its FTDI bridge: decodes host messages, moves at 10 deg/s on the
 * virtual clock [K10CR1 manual: max velocity 10 deg/s], answers with
 * APT messages framed as FTDI bulk-IN packets (two status bytes per 64).
 */
#include <math.h>
#include <string.h>

#include "rig/apt.h"
#include "rig/bytes.h"
#include "rig/sim_devices.h"
#include "rig/status.h"

#define SPEED_DEG_S 10.0
#define FTDI_PACKET 64
#define FTDI_LATENCY_S 0.016	/* FTDI default latency timer */

static int32_t current_pos(const struct sim_stage *s,
			   const struct rig_sim_core *core)
{
	double f;

	if (!s->moving || s->stalled)
		return s->pos;
	f = (core->t_s - s->t0) / (s->t1 - s->t0);
	if (f > 1)
		f = 1;
	return (int32_t)lround(s->from + f * (double)(s->target - s->from));
}

static void queue(struct sim_stage *s, const struct rig_apt_msg *m)
{
	size_t n = rig_apt_encode(m, s->out + s->out_len,
				  sizeof(s->out) - s->out_len);

	s->out_len += n;	/* 0 when full: the host is not reading */
}

/* Status block: channel, position, encoder count, status bits. */
static void queue_status(struct sim_stage *s, uint16_t id)
{
	struct rig_apt_msg m;

	memset(&m, 0, sizeof(m));
	m.id = id;
	m.dest = RIG_APT_HOST;
	m.source = RIG_APT_USB_UNIT;
	m.data_len = RIG_APT_STATUS_LEN;
	rig_put_u16(m.data, RIG_APT_CHAN1);
	rig_put_u32(m.data + 2, (uint32_t)s->pos);
	rig_put_u32(m.data + 6, (uint32_t)s->pos);
	queue(s, &m);
}

static void start_motion(struct sim_stage *s,
			 const struct rig_sim_core *core, int32_t to)
{
	double deg = fabs((double)(to - s->pos)) /
		     core->cfg->stage.counts_per_deg;

	s->from = s->pos;
	s->target = to;
	s->t0 = core->t_s;
	s->t1 = core->t_s + deg / SPEED_DEG_S + 0.05;
	s->moving = 1;
}

/* Where a move settles off its target (sim.stage_error_deg, uniform,
 * 0 by default): a hash of the lab seed and the move count, in counts.
 * The position counter reads the settled position, as an encoder does. */
static int32_t settle_error(struct sim_stage *s,
			    const struct rig_sim_core *core)
{
	const struct rig_sim_config *sc = &core->cfg->sim;
	uint64_t z = sc->vlab.seed * 0xD1B54A32D192ED03ull + ++s->moves;
	double u;

	if (!(sc->stage_error_deg > 0))
		return 0;
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	z ^= z >> 31;
	u = (double)(z >> 11) / 9007199254740992.0 * 2 - 1;
	return (int32_t)lround(u * sc->stage_error_deg *
			       core->cfg->stage.counts_per_deg);
}

static void handle_move(struct sim_stage *s, struct rig_sim_core *core,
			const struct rig_apt_msg *m)
{
	double miss = 0;
	int kind = rig_sim_core_event(core, RIG_DEV_STAGE, &miss);
	int32_t to = (int32_t)rig_get_u32(m->data + 2);

	if (kind == RIG_FAULT_MISS)
		to -= (int32_t)lround(miss * core->cfg->stage.counts_per_deg);
	to += settle_error(s, core);
	s->homing = 0;
	s->stalled = kind == RIG_FAULT_STALL || kind == RIG_FAULT_TIMEOUT;
	start_motion(s, core, to);
}

static void handle(struct sim_stage *s, struct rig_sim_core *core,
		   const struct rig_apt_msg *m)
{
	struct rig_apt_msg r;

	switch (m->id) {
	case RIG_APT_MOT_MOVE_HOME:
		s->homing = 1;
		s->stalled = 0;
		start_motion(s, core, 0);
		break;
	case RIG_APT_MOT_MOVE_ABSOLUTE:
		if (m->data_len >= 6)
			handle_move(s, core, m);
		break;
	case RIG_APT_MOT_REQ_POSCOUNTER:
		memset(&r, 0, sizeof(r));
		r.id = RIG_APT_MOT_GET_POSCOUNTER;
		r.dest = RIG_APT_HOST;
		r.source = RIG_APT_USB_UNIT;
		r.data_len = 6;
		rig_put_u16(r.data, RIG_APT_CHAN1);
		rig_put_u32(r.data + 2, (uint32_t)current_pos(s, core));
		queue(s, &r);
		break;
	case RIG_APT_MOT_MOVE_STOP:
		s->pos = current_pos(s, core);
		s->moving = s->stalled = 0;
		queue_status(s, RIG_APT_MOT_MOVE_STOPPED);
		break;
	default:
		break;	/* a real unit ignores what it does not know */
	}
}

int rig_sim_stage_write(struct sim_stage *s, struct rig_sim_core *core,
			const uint8_t *buf, size_t len)
{
	struct rig_apt_msg m;
	size_t used;
	int rc;

	if (len > sizeof(s->in) - s->in_len)
		return RIG_ETIMEOUT;	/* our FIFO is full */
	memcpy(s->in + s->in_len, buf, len);
	s->in_len += len;
	while ((rc = rig_apt_decode(s->in, s->in_len, &m, &used)) !=
	       RIG_EAGAIN) {
		if (rc != RIG_OK)
			used = 1;
		memmove(s->in, s->in + used, s->in_len - used);
		s->in_len -= used;
		if (rc == RIG_OK)
			handle(s, core, &m);
		if (core->gone[RIG_DEV_STAGE])
			return RIG_EDISCONNECT;
	}
	return RIG_OK;
}

static void update(struct sim_stage *s, const struct rig_sim_core *core)
{
	if (!s->moving || s->stalled || core->t_s < s->t1)
		return;
	s->pos = s->target;
	s->moving = 0;
	if (s->homing) {
		struct rig_apt_msg m;

		rig_apt_short(&m, RIG_APT_MOT_MOVE_HOMED, RIG_APT_CHAN1, 0);
		m.dest = RIG_APT_HOST;
		m.source = RIG_APT_USB_UNIT;
		queue(s, &m);
		s->homing = 0;
	} else {
		queue_status(s, RIG_APT_MOT_MOVE_COMPLETED);
	}
}

int rig_sim_stage_read(struct sim_stage *s, struct rig_sim_core *core,
		       uint8_t *buf, size_t cap, size_t *got,
		       unsigned timeout_ms)
{
	size_t n = 0;

	(void)timeout_ms;
	update(s, core);
	if (s->out_len == 0) {
		/* Idle FTDI: status bytes only, once per latency period. */
		core->t_s += FTDI_LATENCY_S;
		if (cap < 2)
			return RIG_EINVAL;
		buf[0] = 0x01;
		buf[1] = 0x60;
		*got = 2;
		return RIG_OK;
	}
	while (s->out_len > 0 && cap - n > 2) {
		size_t take = FTDI_PACKET - 2;

		if (take > s->out_len)
			take = s->out_len;
		if (take > cap - n - 2)
			take = cap - n - 2;
		buf[n] = 0x01;
		buf[n + 1] = 0x60;
		memcpy(buf + n + 2, s->out, take);
		memmove(s->out, s->out + take, s->out_len - take);
		s->out_len -= take;
		n += take + 2;
		if (take < FTDI_PACKET - 2)
			break;
	}
	*got = n;
	return RIG_OK;
}

void rig_sim_stage_reset(struct sim_stage *s)
{
	memset(s->in, 0, sizeof(s->in));
	s->in_len = s->out_len = 0;
}

double rig_sim_stage_angle_deg(const struct sim_stage *s,
			       const struct rig_sim_core *core)
{
	return s->pos / core->cfg->stage.counts_per_deg;
}
