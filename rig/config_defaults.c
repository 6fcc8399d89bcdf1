/*
 * config_defaults.c - the default configuration: a K10CR1 rotation mount,
 * a six-slot ND wheel, three GPIO lines and an st16-like camera reading
 * 14 rows in 7 pairs (thesis §3.2: interface bandwidth), all simulated.
 */
#include <string.h>

#include "rig/config.h"

static void default_lines(struct rig_line_cfg *l)
{
	static const char *const names[RIG_LINE_COUNT] = {
		"SHUTTER_OPEN", "BEAM_BLOCK", "LAMP_EN"
	};
	int i;

	for (i = 0; i < RIG_LINE_COUNT; i++) {
		strcpy(l[i].chip, "gpiochip0");
		strcpy(l[i].line, names[i]);
		l[i].active_low = 0;
	}
}

static void default_camera(struct rig_camera_cfg *c)
{
	static const uint16_t rows[14] = { 200, 201, 480, 481, 760, 761, 960,
					   961, 1160, 1161, 1440, 1441, 1720,
					   1721 };

	c->usb.vid = 0x04b4;	/* Cypress FX3 bridge of the test camera */
	c->usb.pid = 0x00f1;
	c->n_rows = 14;
	memcpy(c->rows, rows, sizeof(rows));
	c->col0 = 0;
	c->n_cols = 2592;
	c->sat_dn = 4095;	/* 12-bit ADC, ref4-baffle.md st16-like */
	c->timeout_s = 0.5;
	c->crc_retries = 3;
}

void rig_config_defaults(struct rig_config *cfg)
{
	static const double nd[6] = { 1, 0.3, 0.1, 0.03, 0.01, 0.001 };

	memset(cfg, 0, sizeof(*cfg));
	strcpy(cfg->backend, "sim");
	strcpy(cfg->socket_path, "/tmp/strayrigd.sock");
	cfg->socket_mode = 0600;
	cfg->stage.usb.vid = 0x0403;	/* FTDI, Thorlabs APT pid */
	cfg->stage.usb.pid = 0xfaf0;
	cfg->stage.counts_per_deg = 49152000.0 / 360.0;	/* K10CR1 manual */
	cfg->stage.tol_deg = 0.01;
	cfg->stage.move_timeout_s = 30;
	cfg->stage.min_deg = -5;
	cfg->stage.max_deg = 90;
	cfg->wheel.vid = 0x16c0;
	cfg->wheel.pid = 0x05df;
	cfg->wheel.n_slots = 6;
	memcpy(cfg->wheel.trans, nd, sizeof(nd));
	cfg->wheel.move_timeout_s = 5;
	default_lines(cfg->lines);
	default_camera(&cfg->camera);
	cfg->monitor.enabled = 0;
	cfg->monitor.vid = 0x16c0;
	cfg->monitor.pid = 0x05e0;
	cfg->monitor.nominal_pa = 1e6;
	cfg->sweep.theta_start_deg = 0;
	cfg->sweep.theta_stop_deg = 45;	/* thesis §3.2: 0-45 deg at 1 deg */
	cfg->sweep.theta_step_deg = 1;
	cfg->sweep.repeats = 3;
	cfg->sweep.t_min_s = 0.01;
	cfg->sweep.t_max_s = 1.0;
	cfg->sweep.t_init_s = 0.1;
	cfg->sweep.peak_target = 0.8;
	cfg->sweep.retries = 3;
	rig_sim_config_defaults(&cfg->sim);
	rig_indi_cfg_defaults(&cfg->indi);
}
