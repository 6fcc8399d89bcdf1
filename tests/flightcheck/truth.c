/*
 * truth.c - the flight-frame generator (truth.h).  Test and demo side
 * only: nothing in tools/ links it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "truth.h"
#include "fdrfw/ephem.h"
#include "stray/aem.h"
#include "stray/catalogue.h"
#include "stray/ccsds.h"
#include "stray/colour.h"
#include "stray/errfmt.h"
#include "stray/frames.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"
#include "stray/sensor_geom.h"
#include "stray/sweep_store.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define CAT_MAX 200000
#define STARS_MAX 100000

void fc_truth_defaults(struct fc_truth *t)
{
	memset(t, 0, sizeof(*t));
	t->scale = 1.7;
	t->n_frames = 16;
	t->window = 512;
	t->theta_lo_deg = 20.0;
	t->theta_hi_deg = 90.0;
	t->mag_max = 10.0;
	t->point_err_arcsec = 30.0;
	t->gradient = 0.05;
	t->hot_frac = 2e-4;
	t->seed = 18;
	t->gain_e_per_dn = STRAY_FRAMES_GAIN_E_PER_DN;
	t->bias_dn = STRAY_FRAMES_BIAS_DN;
}

static void cross(const double a[3], const double b[3], double c[3])
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalise(double v[3])
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	v[0] /= n;
	v[1] /= n;
	v[2] /= n;
}

/* Head axes (rows of M, v_head = M v_inertial) at Sun offset theta. */
static void pointing(const double s[3], const double p[3], double theta,
		     double m[3][3])
{
	int i;

	for (i = 0; i < 3; i++)
		m[2][i] = cos(theta) * s[i] + sin(theta) * p[i];
	cross(p, s, m[0]);
	normalise(m[0]);
	cross(m[2], m[0], m[1]);
}

/* M_true = R(e) M for a small rotation e (rad) about the head axes. */
static void perturb(double m[3][3], const double e[3])
{
	double r[3][3] = { { 1.0, e[2], -e[1] }, { -e[2], 1.0, e[0] },
			   { e[1], -e[0], 1.0 } }, o[3][3];
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++) {
			o[i][j] = 0.0;
			for (k = 0; k < 3; k++)
				o[i][j] += r[i][k] * m[k][j];
		}
	for (i = 0; i < 3; i++) {
		normalise(o[i]);
		for (j = 0; j < 3; j++)
			m[i][j] = o[i][j];
	}
}

int fc_truth_write(const struct fc_truth *t, const char *dir,
		   const char *aem_path, struct stray_error *err)
{
	const struct stray_sensor *sn = stray_sensor_st16_like();
	struct stray_fluxes fl;
	struct stray_sweep_manifest mf;
	struct stray_frame_cfg c;
	struct stray_colour col;
	struct stray_cat_star *cat = malloc(CAT_MAX * sizeof(*cat));
	struct stray_star *stars = malloc(STARS_MAX * sizeof(*stars));
	int cols = t->window > 0 ? t->window : (int)sn->pixels_x;
	int rows = t->window > 0 ? t->window : (int)sn->pixels_y;
	int col0 = ((int)sn->pixels_x - cols) / 2, row0 = ((int)sn->pixels_y - rows) / 2;
	size_t npx = (size_t)cols * rows;
	float *expect = malloc(npx * sizeof(float));
	uint16_t *dn = malloc(npx * sizeof(uint16_t));
	uint16_t *det_rows = malloc((size_t)rows * sizeof(uint16_t));
	double *tt = malloc((size_t)(t->n_frames + 1) * sizeof(double));
	double (*q)[4] = malloc((size_t)(t->n_frames + 1) * sizeof(*q));
	double a_cs = PI * 0.25 * sn->aperture_diameter_mm *
		      sn->aperture_diameter_mm * 1e-6;
	double a_px = sn->pixel_pitch_um * sn->pixel_pitch_um * 1e-12;
	double k_px = stray_sensor_k_px(sn, STRAY_NORM_CONSISTENT);
	double f_px = stray_sensor_focal_length_mm(sn) / (sn->pixel_pitch_um * 1e-3);
	double s[3], p[3], zc[3] = { 0.0, 0.0, 1.0 };
	int utc = stray_ccsds_time_system("UTC"), i, rc;
	float sf[3];
	FILE *f;

	if (!cat || !stars || !expect || !dn || !det_rows || !tt || !q) {
		rc = stray_error_set(err, STRAY_ENOMEM, "truth", "out of memory");
		goto out;
	}
	if ((rc = stray_reference_fluxes(sn, &fl, err)) != STRAY_OK ||
	    (rc = stray_colour_for_qe(&col, sn->qe, err)) != STRAY_OK)
		goto out;
	for (i = 0; i < rows; i++)
		det_rows[i] = (uint16_t)(row0 + i);
	stray_ccsds_epoch("2026-06-21T10:00:00", utc, &tt[0]);
	fdrfw_sun_dir((int32_t)lround(tt[0]), sf);
	s[0] = sf[0];
	s[1] = sf[1];
	s[2] = sf[2];
	normalise(s);
	cross(s, zc, p);
	normalise(p);
	/* the AEM: one record a minute, the frames on them; one more
	 * record so the last frame is inside the span */
	for (i = 0; i <= t->n_frames; i++) {
		double m[3][3], th = t->theta_lo_deg + (t->theta_hi_deg -
			t->theta_lo_deg) * (i < t->n_frames ? i : i - 1) /
			(t->n_frames > 1 ? t->n_frames - 1 : 1);

		tt[i] = tt[0] + 60.0 * i;
		pointing(s, p, th * DEG, m);
		stray_dcm_q(m, q[i]);
	}
	if (!(f = fopen(aem_path, "w"))) {
		rc = stray_error_at(err, STRAY_EIO, aem_path, 0, 0, "cannot write");
		goto out;
	}
	rc = stray_aem_write(f, "FLIGHTCHECK-TRUTH", utc, tt, (const double (*)[4])q,
			     (size_t)t->n_frames + 1);
	if (fclose(f) || rc) {
		rc = stray_error_at(err, STRAY_EIO, aem_path, 0, 0, "cannot write");
		goto out;
	}
	if (mkdir(dir, 0777)) {
		rc = stray_error_at(err, STRAY_EIO, dir, 0, 0, "cannot create");
		goto out;
	}
	if ((rc = stray_sweep_store_open(&mf, dir, 0, err)) != STRAY_OK)
		goto out;
	stray_frame_cfg_defaults(&c, cols, rows);
	c.col0 = col0;
	c.row0 = row0;
	c.read_noise_e = sn->read_noise_e;
	c.gain_e_per_dn = t->gain_e_per_dn;
	c.bias_dn = t->bias_dn;
	c.gradient = t->gradient;
	c.hot_frac = t->hot_frac;
	c.hot_e = 800.0;
	for (i = 0; i < t->n_frames && rc == STRAY_OK; i++) {
		struct stray_camera cam;
		struct stray_sweep_frame fr;
		struct stray_sweep_image im;
		uint64_t seed = stray_frame_seed(t->seed, (uint64_t)i);
		double e[3], alpha, theta, dot, sun_e;
		char date[40], beg[40], end[40];
		size_t n_cat, n_st;
		int k;
		static const double cyc[3] = { 1.0, 0.5, 2.0 };
		double t_exp = sn->t_exp_s * (t->mixed_exposure ? cyc[i % 3] : 1.0);
		double radius;

		stray_q_dcm(q[i], cam.m_ih);
		/* pointing knowledge error: a deterministic small rotation */
		for (k = 0; k < 3; k++)
			e[k] = t->point_err_arcsec / 3600.0 * DEG *
			       sin(1.7 * i + 2.1 * k + 0.3);
		perturb(cam.m_ih, e);
		cam.f_px = f_px;
		cam.cx = 0.5 * sn->pixels_x - col0;
		cam.cy = 0.5 * sn->pixels_y - row0;
		radius = atan(0.75 * hypot(cols, rows) / f_px) / DEG + 0.2;
		if (t->cat) {	/* the real sky at the frame's epoch */
			stray_starcat_cone(t->cat, stray_jyear_of_tt(tt[i]),
					   cam.m_ih[2], radius, t->mag_max, cat,
					   CAT_MAX, &n_cat);
			stray_colour_apply(&col, cat, n_cat);
		} else {
			stray_catalogue_cone(STRAY_CATALOGUE_SEED, cam.m_ih[2],
					     radius, t->mag_max, cat, CAT_MAX,
					     &n_cat);
		}
		n_st = stray_camera_stars(&cam, cat, n_cat, cols, rows, 8.0,
					  fl.zero_mag * t_exp * a_cs,
					  stars, STARS_MAX);
		c.dark_e = sn->dark_current_e_s * t_exp;
		dot = cam.m_ih[2][0] * s[0] + cam.m_ih[2][1] * s[1] +
		      cam.m_ih[2][2] * s[2];
		theta = acos(fmax(-1.0, fmin(1.0, dot))) / DEG;
		alpha = stray_curve_alpha_at(&t->curve, theta);
		sun_e = fl.sun * t_exp * a_px;
		c.stray_e = t->scale * k_px * alpha * sun_e;	/* eq. 2.3 */
		stray_frame_expect(&c, stars, n_st, expect);
		stray_frame_sample(&c, expect, seed + 1, dn);
		stray_ccsds_format_epoch(tt[i], t->cat ? stray_ccsds_time_system("TT") : utc,
					 date, sizeof(date));
		/* the real sky's frames as a camera writes them: the
		 * exposure's start and end in TT */
		stray_ccsds_format_epoch(tt[i] - 0.5 * t_exp,
					 stray_ccsds_time_system("TT"), beg, sizeof(beg));
		stray_ccsds_format_epoch(tt[i] + 0.5 * t_exp,
					 stray_ccsds_time_system("TT"), end, sizeof(end));
		{
			struct stray_sweep_key key[] = {
				{ "BIAS", STRAY_SWEEP_KEY_DOUBLE, t->bias_dn, 0,
				  NULL, "[DN] bias level" },
				{ "GAIN", STRAY_SWEEP_KEY_DOUBLE, t->gain_e_per_dn,
				  0, NULL, "[e-/DN]" },
				{ "SATURATE", STRAY_SWEEP_KEY_DOUBLE,
				  STRAY_FRAMES_SAT_DN, 0, NULL,
				  "[DN] the ADC's full scale" },
				{ "DATE-OBS", STRAY_SWEEP_KEY_STRING, 0, 0, date,
				  "mid-exposure (UTC; TT with TIMESYS)" },
				{ "TIMESYS", STRAY_SWEEP_KEY_STRING, 0, 0, "TT",
				  "of DATE-BEG, DATE-END" },
				{ "DATE-BEG", STRAY_SWEEP_KEY_STRING, 0, 0, beg,
				  "TT, exposure start" },
				{ "DATE-END", STRAY_SWEEP_KEY_STRING, 0, 0, end,
				  "TT, exposure end" },
				{ "TALPHA", STRAY_SWEEP_KEY_DOUBLE, alpha, 0, NULL,
				  "truth: alpha_sys (not for analysis)" },
				{ "TSCALE", STRAY_SWEEP_KEY_DOUBLE, t->scale, 0, NULL,
				  "truth: hidden scale (not for analysis)" },
				{ "STARSRC", STRAY_SWEEP_KEY_STRING, 0, 0,
				  t->cat ? "real catalogue" : "synthetic catalogue",
				  "stray/catalogue.h, stray/starcat.h" },
			};
			/* the synthetic sky's frames keep DATE-OBS in UTC only */
			size_t n_key = sizeof(key) / sizeof(key[0]);

			memset(&fr, 0, sizeof(fr));
			fr.type = STRAY_SWEEP_FULL;
			fr.exptime_s = t_exp;
			fr.ndtrans = 1.0;
			fr.seqnum = i;
			fr.sat_dn = STRAY_FRAMES_SAT_DN;
			fr.full_frame = rows == (int)sn->pixels_y;
			fr.instrument = "flight (synthetic)";
			fr.extra = key;
			if (!t->cat) {	/* DATE-OBS (UTC) only */
				key[4] = key[n_key - 3];	/* over TIMESYS, */
				key[5] = key[n_key - 2];	/* DATE-BEG, */
				key[6] = key[n_key - 1];	/* DATE-END */
				n_key -= 3;
			}
			fr.n_extra = n_key;
			im.n_rows = (size_t)rows;
			im.n_cols = (size_t)cols;
			im.col0 = col0;
			im.rows = det_rows;
			im.px = dn;
			rc = stray_sweep_store_append(&mf, &fr, &im, err);
		}
	}
	stray_sweep_manifest_free(&mf);
out:
	free(cat);
	free(stars);
	free(expect);
	free(dn);
	free(det_rows);
	free(tt);
	free(q);
	return rc;
}
