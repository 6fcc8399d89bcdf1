/*
 * sim.c - the simulator backend's ops table: routes each open device to
 * its device-side model, keeps the virtual clock and applies faults.
 * A transfer to a device that the fault schedule has unplugged returns
 * EDISCONNECT, as libusb's LIBUSB_ERROR_NO_DEVICE does.
 */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rig/sim.h"
#include "rig/status.h"

/* Device handles are tags pointing into the sim. */
static int tag[RIG_SIM_DEVICE_COUNT + RIG_LINE_COUNT];

static int dev_of(const void *dev)
{
	int i = (int)((const int *)dev - tag);

	return i >= RIG_SIM_GPIO ? RIG_SIM_GPIO : i;
}

int rig_sim_fault_active(struct rig_sim *sim, int dev, int kind)
{
	unsigned n = sim->events[dev];
	int i;

	for (i = 0; i < sim->cfg->n_faults; i++) {
		const struct rig_fault *f = &sim->cfg->faults[i];

		if (f->device == dev && f->kind == kind && n >= f->at &&
		    n < f->at + f->count)
			return 1;
	}
	return 0;
}

void rig_sim_disconnect(struct rig_sim *sim, int dev, unsigned reopen_fails)
{
	sim->gone[dev] = 1;
	sim->open_fail[dev] = reopen_fails;
}

int rig_sim_event(struct rig_sim *sim, int dev, double *value)
{
	unsigned n = ++sim->events[dev];
	int i;

	for (i = 0; i < sim->cfg->n_faults; i++) {
		const struct rig_fault *f = &sim->cfg->faults[i];

		/* A disconnect or kill happens once; its count is the
		 * number of re-opens that fail (the time to replug). */
		unsigned last = f->kind == RIG_FAULT_DISCONNECT ||
				f->kind == RIG_FAULT_KILL ? f->at
							  : f->at + f->count - 1;

		if (f->device != dev || n < f->at || n > last)
			continue;
		sim->fault_hits[i]++;
		sim->faults_fired++;
		if (value)
			*value = f->value;
		if (f->kind == RIG_FAULT_KILL)
			raise(SIGKILL);
		if (f->kind == RIG_FAULT_DISCONNECT)
			rig_sim_disconnect(sim, dev, f->count);
		return f->kind;
	}
	return -1;
}

static int sim_open_dev(struct rig_sim *sim, int dev, void **out)
{
	if (sim->open_fail[dev] > 0) {
		sim->open_fail[dev]--;
		return RIG_EDISCONNECT;
	}
	sim->gone[dev] = 0;
	*out = &tag[dev];
	return RIG_OK;
}

static int s_usb_open(void *self, const struct rig_usb_id *id, void **dev)
{
	struct rig_sim *sim = self;
	const struct rig_config *c = sim->cfg;

	if (id->vid == c->stage.usb.vid && id->pid == c->stage.usb.pid) {
		memset(sim->stage.in, 0, sizeof(sim->stage.in));
		sim->stage.in_len = sim->stage.out_len = 0;
		return sim_open_dev(sim, RIG_SIM_STAGE, dev);
	}
	if (id->vid == c->camera.usb.vid && id->pid == c->camera.usb.pid) {
		sim->cam.queued = 0;
		return sim_open_dev(sim, RIG_SIM_CAMERA, dev);
	}
	return RIG_EDISCONNECT;
}

static int s_usb_control(void *self, void *dev, uint8_t type, uint8_t req,
			 uint16_t value, uint16_t index, unsigned timeout_ms)
{
	struct rig_sim *sim = self;

	(void)type, (void)req, (void)value, (void)index, (void)timeout_ms;
	return sim->gone[dev_of(dev)] ? RIG_EDISCONNECT : RIG_OK;
}

static int s_usb_write(void *self, void *dev, uint8_t ep, const uint8_t *buf,
		       size_t len, unsigned timeout_ms)
{
	struct rig_sim *sim = self;
	int d = dev_of(dev);

	(void)ep, (void)timeout_ms;
	if (sim->gone[d])
		return RIG_EDISCONNECT;
	return d == RIG_SIM_STAGE ? rig_sim_stage_write(sim, buf, len)
				  : rig_sim_camera_write(sim, buf, len);
}

static int s_usb_read(void *self, void *dev, uint8_t ep, uint8_t *buf,
		      size_t cap, size_t *got, unsigned timeout_ms)
{
	struct rig_sim *sim = self;
	int d = dev_of(dev);

	(void)ep;
	if (sim->gone[d])
		return RIG_EDISCONNECT;
	return d == RIG_SIM_STAGE
		       ? rig_sim_stage_read(sim, buf, cap, got, timeout_ms)
		       : rig_sim_camera_read(sim, buf, cap, got, timeout_ms);
}

static void s_close(void *self, void *dev)
{
	(void)self, (void)dev;
}

static int s_hid_open(void *self, uint16_t vid, uint16_t pid,
		      const char *serial, void **dev)
{
	struct rig_sim *sim = self;

	(void)serial;
	if (vid == sim->cfg->monitor.vid && pid == sim->cfg->monitor.pid) {
		sim->mon.have_report = 0;
		return sim_open_dev(sim, RIG_SIM_MONITOR, dev);
	}
	if (vid != sim->cfg->wheel.vid || pid != sim->cfg->wheel.pid)
		return RIG_EDISCONNECT;
	sim->wheel.have_report = 0;
	return sim_open_dev(sim, RIG_SIM_WHEEL, dev);
}

static int s_hid_write(void *self, void *dev, const uint8_t *buf, size_t len)
{
	struct rig_sim *sim = self;
	int d = dev_of(dev);

	if (sim->gone[d])
		return RIG_EDISCONNECT;
	return d == RIG_SIM_MONITOR ? rig_sim_monitor_write(sim, buf, len)
				    : rig_sim_wheel_write(sim, buf, len);
}

static int s_hid_read(void *self, void *dev, uint8_t *buf, size_t cap,
		      size_t *got, unsigned timeout_ms)
{
	struct rig_sim *sim = self;
	int d = dev_of(dev);

	if (sim->gone[d])
		return RIG_EDISCONNECT;
	return d == RIG_SIM_MONITOR
		       ? rig_sim_monitor_read(sim, buf, cap, got, timeout_ms)
		       : rig_sim_wheel_read(sim, buf, cap, got, timeout_ms);
}

static int s_gpio_open(void *self, const struct rig_gpio_id *id, void **dev)
{
	struct rig_sim *sim = self;
	int i;

	for (i = 0; i < RIG_LINE_COUNT; i++)
		if (strcmp(id->line, sim->cfg->lines[i].line) == 0 &&
		    strcmp(id->chip, sim->cfg->lines[i].chip) == 0) {
			if (sim->open_fail[RIG_SIM_GPIO] > 0) {
				sim->open_fail[RIG_SIM_GPIO]--;
				return RIG_EDISCONNECT;
			}
			sim->gone[RIG_SIM_GPIO] = 0;
			sim->gpio[i] = id->initial ? 1 : 0;
			*dev = &tag[RIG_SIM_GPIO + i];
			return RIG_OK;
		}
	return RIG_EDISCONNECT;
}

static int s_gpio_set(void *self, void *dev, int value)
{
	struct rig_sim *sim = self;
	int line = (int)((int *)dev - tag) - RIG_SIM_GPIO;

	if (sim->gone[RIG_SIM_GPIO])
		return RIG_EDISCONNECT;
	/* A stalled line driver ignores the write (read-back catches it). */
	if (rig_sim_event(sim, RIG_SIM_GPIO, NULL) != RIG_FAULT_STALL)
		sim->gpio[line] = value ? 1 : 0;
	return sim->gone[RIG_SIM_GPIO] ? RIG_EDISCONNECT : RIG_OK;
}

static int s_gpio_get(void *self, void *dev, int *value)
{
	struct rig_sim *sim = self;
	int line = (int)((int *)dev - tag) - RIG_SIM_GPIO;

	if (sim->gone[RIG_SIM_GPIO])
		return RIG_EDISCONNECT;
	*value = sim->gpio[line];
	return RIG_OK;
}

static double s_now(void *self)
{
	return ((struct rig_sim *)self)->t_s;
}

static void s_sleep(void *self, double s)
{
	((struct rig_sim *)self)->t_s += s;
}

static const struct rig_hal_ops sim_ops = {
	.name = "sim",
	.usb_open = s_usb_open,
	.usb_control = s_usb_control,
	.usb_write = s_usb_write,
	.usb_read = s_usb_read,
	.usb_close = s_close,
	.hid_open = s_hid_open,
	.hid_write = s_hid_write,
	.hid_read = s_hid_read,
	.hid_close = s_close,
	.gpio_open = s_gpio_open,
	.gpio_set = s_gpio_set,
	.gpio_get = s_gpio_get,
	.gpio_close = s_close,
	.clock_now = s_now,
	.clock_sleep = s_sleep,
};

int rig_sim_init(struct rig_sim *sim, const struct rig_config *cfg,
		 struct rig_hal *hal)
{
	int i;

	memset(sim, 0, sizeof(*sim));
	sim->cfg = cfg;
	sim->wheel.slot = sim->wheel.target = 0;
	/* Power-on levels: every line inactive... which for an active-low
	 * line means physically high. */
	for (i = 0; i < RIG_LINE_COUNT; i++)
		sim->gpio[i] = cfg->lines[i].active_low ? 1 : 0;
	hal->ops = &sim_ops;
	hal->self = sim;
	return RIG_OK;
}

void rig_sim_fini(struct rig_sim *sim)
{
	free(sim->cam.clean);
	free(sim->cam.wire);
	sim->cam.clean = sim->cam.wire = NULL;
}

static int logical(const struct rig_sim *sim, int line)
{
	return sim->gpio[line] ^ (sim->cfg->lines[line].active_low ? 1 : 0);
}

int rig_sim_lamp_on(const struct rig_sim *sim)
{
	return logical(sim, RIG_LINE_LAMP);
}

int rig_sim_beam_blocked(const struct rig_sim *sim)
{
	return logical(sim, RIG_LINE_BEAM_BLOCK);
}

int rig_sim_shutter_open(const struct rig_sim *sim)
{
	return logical(sim, RIG_LINE_SHUTTER);
}

double rig_sim_angle_deg(const struct rig_sim *sim)
{
	return sim->stage.pos / sim->cfg->stage.counts_per_deg;
}
