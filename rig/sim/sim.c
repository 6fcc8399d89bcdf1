/*
 * sim.c - the simulator backend's ops table over its device table: each
 * open finds its device by bus id in the table, and each transfer goes
 * to that device's model.  A transfer to a device that the fault
 * schedule has unplugged returns EDISCONNECT, as libusb's
 * LIBUSB_ERROR_NO_DEVICE does.  The lab state one model needs of the
 * others (the camera: stage angle, ND slot, lines) is gathered here.
 */
#include <string.h>
#include <time.h>

#include "rig/sim.h"
#include "rig/status.h"

enum sim_bus { SIM_USB, SIM_HID, SIM_GPIO };

/* One entry per enum rig_device. */
struct sim_device {
	enum sim_bus bus;
	/* Does the vid:pid name this device (USB and HID)? */
	int (*is)(const struct rig_config *c, uint16_t vid, uint16_t pid);
	void (*open)(struct rig_sim *sim);	/* reset its transfer state */
	int (*write)(struct rig_sim *sim, const uint8_t *buf, size_t len);
	int (*read)(struct rig_sim *sim, uint8_t *buf, size_t cap,
		    size_t *got, unsigned timeout_ms);
};

static void lab_view(const struct rig_sim *sim, struct sim_lab_view *lab)
{
	lab->theta_deg = rig_sim_angle_deg(sim);
	lab->nd_trans = rig_sim_wheel_trans(&sim->wheel, &sim->core);
	lab->lamp_on = rig_sim_lamp_on(sim);
	lab->beam_blocked = rig_sim_beam_blocked(sim);
	lab->shutter_open = rig_sim_shutter_open(sim);
}

/* ---- stage ---- */
static int stage_is(const struct rig_config *c, uint16_t vid, uint16_t pid)
{
	return vid == c->stage.usb.vid && pid == c->stage.usb.pid;
}

static void stage_open(struct rig_sim *sim)
{
	rig_sim_stage_reset(&sim->stage);
}

static int stage_write(struct rig_sim *sim, const uint8_t *buf, size_t len)
{
	return rig_sim_stage_write(&sim->stage, &sim->core, buf, len);
}

static int stage_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		      size_t *got, unsigned timeout_ms)
{
	return rig_sim_stage_read(&sim->stage, &sim->core, buf, cap, got,
				  timeout_ms);
}

/* ---- ND wheel ---- */
static int wheel_is(const struct rig_config *c, uint16_t vid, uint16_t pid)
{
	return vid == c->wheel.vid && pid == c->wheel.pid;
}

static void wheel_open(struct rig_sim *sim)
{
	rig_sim_wheel_reset(&sim->wheel);
}

static int wheel_write(struct rig_sim *sim, const uint8_t *buf, size_t len)
{
	return rig_sim_wheel_write(&sim->wheel, &sim->core, buf, len);
}

static int wheel_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		      size_t *got, unsigned timeout_ms)
{
	return rig_sim_wheel_read(&sim->wheel, &sim->core, buf, cap, got,
				  timeout_ms);
}

/* ---- camera ---- */
static int camera_is(const struct rig_config *c, uint16_t vid, uint16_t pid)
{
	return vid == c->camera.usb.vid && pid == c->camera.usb.pid;
}

static void camera_open(struct rig_sim *sim)
{
	rig_sim_camera_reset(&sim->cam);
}

static int camera_write(struct rig_sim *sim, const uint8_t *buf, size_t len)
{
	struct sim_lab_view lab;

	lab_view(sim, &lab);
	return rig_sim_camera_write(&sim->cam, &sim->core, &lab, buf, len);
}

static int camera_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		       size_t *got, unsigned timeout_ms)
{
	return rig_sim_camera_read(&sim->cam, &sim->core, buf, cap, got,
				   timeout_ms);
}

/* ---- lamp monitor ---- */
static int monitor_is(const struct rig_config *c, uint16_t vid,
		      uint16_t pid)
{
	return vid == c->monitor.vid && pid == c->monitor.pid;
}

static void monitor_open(struct rig_sim *sim)
{
	rig_sim_monitor_reset(&sim->mon);
}

static int monitor_write(struct rig_sim *sim, const uint8_t *buf,
			 size_t len)
{
	return rig_sim_monitor_write(&sim->mon, &sim->core,
				     rig_sim_lamp_on(sim), buf, len);
}

static int monitor_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
			size_t *got, unsigned timeout_ms)
{
	return rig_sim_monitor_read(&sim->mon, &sim->core, buf, cap, got,
				    timeout_ms);
}

/* The device table.  GPIO lines are opened by name and set or read, not
 * written as bytes: rig_sim_lines_* below. */
static const struct sim_device devices[RIG_DEV_COUNT] = {
	[RIG_DEV_STAGE] = { SIM_USB, stage_is, stage_open, stage_write,
			    stage_read },
	[RIG_DEV_WHEEL] = { SIM_HID, wheel_is, wheel_open, wheel_write,
			    wheel_read },
	[RIG_DEV_CAMERA] = { SIM_USB, camera_is, camera_open, camera_write,
			     camera_read },
	[RIG_DEV_MONITOR] = { SIM_HID, monitor_is, monitor_open,
			      monitor_write, monitor_read },
	[RIG_DEV_GPIO] = { SIM_GPIO, NULL, NULL, NULL, NULL },
};

/* Device handles are tags pointing into this array: one per device, then
 * one per GPIO line. */
static int tag[RIG_DEV_COUNT + RIG_LINE_COUNT];

static int dev_of(const void *dev)
{
	int i = (int)((const int *)dev - tag);

	return i >= RIG_DEV_GPIO ? RIG_DEV_GPIO : i;
}

static int line_of(const void *dev)
{
	return (int)((const int *)dev - tag) - RIG_DEV_GPIO;
}

static int open_on_bus(struct rig_sim *sim, enum sim_bus bus, uint16_t vid,
		       uint16_t pid, void **dev)
{
	int d, rc;

	for (d = 0; d < RIG_DEV_COUNT; d++) {
		if (devices[d].bus != bus ||
		    !devices[d].is(sim->core.cfg, vid, pid))
			continue;
		devices[d].open(sim);
		rc = rig_sim_core_open(&sim->core, d);
		if (rc == RIG_OK)
			*dev = &tag[d];
		return rc;
	}
	return RIG_EDISCONNECT;
}

static int dev_write(struct rig_sim *sim, void *dev, const uint8_t *buf,
		     size_t len)
{
	int d = dev_of(dev);

	if (sim->core.gone[d])
		return RIG_EDISCONNECT;
	return devices[d].write(sim, buf, len);
}

static int dev_read(struct rig_sim *sim, void *dev, uint8_t *buf,
		    size_t cap, size_t *got, unsigned timeout_ms)
{
	int d = dev_of(dev);

	if (sim->core.gone[d])
		return RIG_EDISCONNECT;
	return devices[d].read(sim, buf, cap, got, timeout_ms);
}

/* ---- the HAL ops ---- */
static int s_usb_open(void *self, const struct rig_usb_id *id, void **dev)
{
	return open_on_bus(self, SIM_USB, id->vid, id->pid, dev);
}

static int s_usb_control(void *self, void *dev, uint8_t type, uint8_t req,
			 uint16_t value, uint16_t index, unsigned timeout_ms)
{
	struct rig_sim *sim = self;

	(void)type, (void)req, (void)value, (void)index, (void)timeout_ms;
	return sim->core.gone[dev_of(dev)] ? RIG_EDISCONNECT : RIG_OK;
}

static int s_usb_write(void *self, void *dev, uint8_t ep, const uint8_t *buf,
		       size_t len, unsigned timeout_ms)
{
	(void)ep, (void)timeout_ms;
	return dev_write(self, dev, buf, len);
}

static int s_usb_read(void *self, void *dev, uint8_t ep, uint8_t *buf,
		      size_t cap, size_t *got, unsigned timeout_ms)
{
	(void)ep;
	return dev_read(self, dev, buf, cap, got, timeout_ms);
}

static void s_close(void *self, void *dev)
{
	(void)self, (void)dev;
}

static int s_hid_open(void *self, uint16_t vid, uint16_t pid,
		      const char *serial, void **dev)
{
	(void)serial;
	return open_on_bus(self, SIM_HID, vid, pid, dev);
}

static int s_hid_write(void *self, void *dev, const uint8_t *buf, size_t len)
{
	return dev_write(self, dev, buf, len);
}

static int s_hid_read(void *self, void *dev, uint8_t *buf, size_t cap,
		      size_t *got, unsigned timeout_ms)
{
	return dev_read(self, dev, buf, cap, got, timeout_ms);
}

static int s_gpio_open(void *self, const struct rig_gpio_id *id, void **dev)
{
	struct rig_sim *sim = self;
	int line, rc = rig_sim_lines_open(&sim->lines, &sim->core, id, &line);

	if (rc == RIG_OK)
		*dev = &tag[RIG_DEV_GPIO + line];
	return rc;
}

static int s_gpio_set(void *self, void *dev, int value)
{
	struct rig_sim *sim = self;

	return rig_sim_lines_set(&sim->lines, &sim->core, line_of(dev),
				 value);
}

static int s_gpio_get(void *self, void *dev, int *value)
{
	struct rig_sim *sim = self;

	return rig_sim_lines_get(&sim->lines, &sim->core, line_of(dev),
				 value);
}

/* The wall clock plus the virtual time: a pause shows as real time
 * passing, frames as their virtual exposures. */
static double s_utc(void *self)
{
	struct timespec ts;

	clock_gettime(CLOCK_REALTIME, &ts);
	return (double)ts.tv_sec + ts.tv_nsec * 1e-9 +
	       ((struct rig_sim *)self)->core.t_s;
}

static double s_now(void *self)
{
	return ((struct rig_sim *)self)->core.t_s;
}

static void s_sleep(void *self, double s)
{
	((struct rig_sim *)self)->core.t_s += s;
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
	.clock_utc = s_utc,
};

int rig_sim_init(struct rig_sim *sim, const struct rig_config *cfg,
		 struct rig_hal *hal)
{
	memset(sim, 0, sizeof(*sim));
	rig_sim_core_init(&sim->core, cfg);
	sim->wheel.slot = sim->wheel.target = 0;
	rig_sim_lines_init(&sim->lines, &sim->core);
	hal->ops = &sim_ops;
	hal->self = sim;
	return RIG_OK;
}

void rig_sim_fini(struct rig_sim *sim)
{
	rig_sim_camera_fini(&sim->cam);
}

int rig_sim_lamp_on(const struct rig_sim *sim)
{
	return rig_sim_lines_logical(&sim->lines, &sim->core, RIG_LINE_LAMP);
}

int rig_sim_beam_blocked(const struct rig_sim *sim)
{
	return rig_sim_lines_logical(&sim->lines, &sim->core,
				     RIG_LINE_BEAM_BLOCK);
}

int rig_sim_shutter_open(const struct rig_sim *sim)
{
	return rig_sim_lines_logical(&sim->lines, &sim->core,
				     RIG_LINE_SHUTTER);
}

double rig_sim_angle_deg(const struct rig_sim *sim)
{
	return rig_sim_stage_angle_deg(&sim->stage, &sim->core);
}

unsigned rig_sim_faults_fired(const struct rig_sim *sim)
{
	return sim->core.faults_fired;
}
