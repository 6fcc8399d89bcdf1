/*
 * lab_native.c - the lab's own drivers as its device table (lab.h,
 * struct rig_lab_ops): APT stage, HID wheel and monitor, GPIO lines and
 * the frame-link camera, each on the lab's HAL (real or simulated).
 */
#include "rig/lab.h"

static int nat_open(struct rig_lab *lab, int dev, struct rig_error *err)
{
	const struct rig_config *c = lab->cfg;

	switch (dev) {
	case RIG_DEV_STAGE:
		return rig_stage_open(&lab->stage, lab->hal, &c->stage, err);
	case RIG_DEV_WHEEL:
		return rig_wheel_open(&lab->wheel, lab->hal, &c->wheel, err);
	case RIG_DEV_CAMERA:
		return rig_camera_open(&lab->camera, lab->hal, &c->camera,
				       err);
	case RIG_DEV_MONITOR:
		return rig_monitor_open(&lab->monitor, lab->hal, &c->monitor,
					err);
	default:
		return rig_lines_open(&lab->lines, lab->hal, c->lines, err);
	}
}

static void nat_close(struct rig_lab *lab, int dev)
{
	switch (dev) {
	case RIG_DEV_STAGE: rig_stage_close(&lab->stage); break;
	case RIG_DEV_WHEEL: rig_wheel_close(&lab->wheel); break;
	case RIG_DEV_CAMERA:
		lab->crc_rereads += lab->camera.crc_rereads;
		rig_camera_close(&lab->camera);
		break;
	case RIG_DEV_MONITOR: rig_monitor_close(&lab->monitor); break;
	default: rig_lines_close(&lab->lines); break;
	}
}

static int nat_home(struct rig_lab *lab, struct rig_error *err)
{
	return rig_stage_home(&lab->stage, err);
}

static int nat_move(struct rig_lab *lab, double theta_deg,
		    struct rig_error *err)
{
	return rig_stage_move(&lab->stage, theta_deg, err);
}

static int nat_stop(struct rig_lab *lab, struct rig_error *err)
{
	return rig_stage_stop(&lab->stage, err);
}

static int nat_wheel_goto(struct rig_lab *lab, int slot, struct rig_error *err)
{
	return rig_wheel_goto(&lab->wheel, slot, err);
}

static int nat_wheel_count(struct rig_lab *lab, int *n, struct rig_error *err)
{
	return rig_wheel_count(&lab->wheel, n, err);
}

static int nat_line_set(struct rig_lab *lab, enum rig_line which, int on,
			struct rig_error *err)
{
	return rig_lines_set(&lab->lines, which, on, err);
}

static int nat_capture(struct rig_lab *lab, double t_exp_s,
		       struct rig_image *img, struct rig_error *err)
{
	int rc = rig_camera_set_exposure(&lab->camera, t_exp_s, err);

	return rc == RIG_OK ? rig_camera_capture(&lab->camera, img, err) : rc;
}

static int nat_monitor(struct rig_lab *lab, double *level,
		       struct rig_error *err)
{
	return rig_monitor_read(&lab->monitor, level, err);
}

const struct rig_lab_ops rig_lab_native_ops = {
	nat_open, nat_close, nat_home, nat_move, nat_stop, nat_wheel_goto,
	nat_wheel_count, nat_line_set, nat_capture, nat_monitor,
};
