/*
 * synth_sweep.c - render a synthetic lab sweep (see synth_sweep.h).
 *
 * Model of one pixel's counts (gain 1 e-/count, 12-bit ADC clipped at
 * SATLEVEL = 4095), in the order the thesis lists the lab's effects
 * (§3.1, table 3.1):
 *   I = offset[channel] + i_dark t + S(k) t nd (direct + atmospheric)
 *       + t nd ambient + noise(read, shot),
 * with S(k) the source drifting linearly over the frame index k, direct
 * the known lens response (a decaying level with a column gradient that
 * grows off axis, a row vignette and two moving ghosts), and the same
 * t and nd for the FULL and AMBIENT frames of an angle.
 */
#include <fitsio.h>
#include <math.h>
#include <openssl/evp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "synth_sweep.h"

#define SAT_LEVEL 4095
#define F0 1.0e6		/* on-axis direct rate, counts/s */
#define RATE_ATM 1.0e3		/* atmospheric scatter of the beam */
#define RATE_ROOM 200.0		/* room light */
#define I_DARK 5.0		/* dark current, counts/s */
#define READ_NOISE 4.0		/* counts rms */

static const double offsets[8] = { 100, 104, 97, 110, 95, 102, 108, 99 };
static const double exposures[] = { 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0 };
#define N_EXP (sizeof(exposures) / sizeof(exposures[0]))

void synth_default(struct synth_config *c)
{
	memset(c, 0, sizeof(*c));
	c->n_rows = 64;
	c->n_cols = 96;
	c->col0 = 0;
	c->row0 = 0;
	c->theta_step_deg = 1.0;
	c->n_angles = 15;
	c->repeats = 3;
	c->darks_per_exp = 3;
	c->revisit = 1;
	c->drift = 0.0;
	c->ghosts = 1;
	c->n_hot = 6;
	c->n_dead = 3;
	c->sat_spots = 1;
	c->seed = 1;
}

/* splitmix64 (Steele et al. 2014) and Box-Muller normals. */
struct rng {
	uint64_t s;
};

static double uniform(struct rng *r)
{
	uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);

	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	z ^= z >> 31;
	return ((double)(z >> 11) + 0.5) / 9007199254740992.0;
}

static double normal(struct rng *r)
{
	double u = uniform(r), v = uniform(r);

	return sqrt(-2.0 * log(u)) * cos(6.283185307179586 * v);
}

/* ---- the lens (truth) ------------------------------------------------ */

static double level(double th)
{
	return pow(10.0, -th / 6.0);
}

/* Ghost centre in stored columns, or NaN where absent. */
static double ghost_centre(int g, double th)
{
	if (g == 0)
		return th >= 3.0 && th <= 11.0 ? 12.0 + 5.0 * (th - 3.0) : NAN;
	return th >= 6.0 && th <= 14.0 ? 85.0 - 3.0 * (th - 6.0) : NAN;
}

/* Ghost g's share of the direct rate of a pixel (no vignette). */
static double ghost_rate(int g, double th, size_t col)
{
	double m = ghost_centre(g, th), amp = g == 0 ? 0.2 : 0.12;

	if (isnan(m))
		return 0.0;
	return F0 * amp * level(th) *
	       exp(-0.5 * ((double)col - m) * ((double)col - m) / 4.0);
}

static double direct_rate(const struct synth_config *c, double th, size_t r,
			  size_t col)
{
	double x = ((double)col + 0.5) / (double)c->n_cols - 0.5;
	double y = ((double)r + 0.5) / (double)c->n_rows - 0.5;
	double g = 0.6 * sin(th * 3.141592653589793 / 28.0);
	double v = level(th) * (1.0 + 2.0 * g * x) * (1.0 - 0.2 * y * y);
	int k;

	v *= F0;
	for (k = 0; c->ghosts && k < 2; k++)
		v += ghost_rate(k, th, col);
	return v;
}

static double total_direct(const struct synth_config *c, double th)
{
	double s = 0.0;
	size_t r, col;

	for (r = 0; r < c->n_rows; r++)
		for (col = 0; col < c->n_cols; col++)
			s += direct_rate(c, th, r, col);
	return s;
}

static double peak_rate(const struct synth_config *c, double th)
{
	double m = 0.0;
	size_t r, col;

	for (r = 0; r < c->n_rows; r++)
		for (col = 0; col < c->n_cols; col++)
			m = fmax(m, direct_rate(c, th, r, col));
	return m + 1.5 * RATE_ATM + RATE_ROOM;
}

/* Longest exposure of the ladder keeping the peak at 60% of full well;
 * ND filters (0.1 each) stacked when even the shortest saturates. */
static void choose_exposure(double peak, double *t, double *nd)
{
	double room = 0.6 * (SAT_LEVEL - 120.0);
	size_t i;

	for (*nd = 1.0; *nd > 1e-4; *nd *= 0.1)
		for (i = N_EXP; i-- > 0;)
			if (exposures[i] * *nd * peak <= room) {
				*t = exposures[i];
				return;
			}
	*t = exposures[0];
}

/* ---- frames ---------------------------------------------------------- */

struct sweep_state {
	const struct synth_config *c;
	struct synth_truth *t;
	const char *dir;
	struct rng rng;
	long *det_row;
	uint16_t *pix;
	unsigned char *bad;	/* 1 hot, 2 dead */
	double *hot_rate;
	size_t frame, n_frames;
	char rows_text[4096];
};

static int write_fits(struct sweep_state *s, const struct synth_entry *e,
		      double monitor)
{
	const struct synth_config *c = s->c;
	char path[4096];
	long naxes[2] = { (long)c->n_cols, (long)c->n_rows };
	long seq = e->seqnum, sat = SAT_LEVEL, col0 = c->col0;
	long row0 = s->det_row[0];
	double a = e->angle_deg, t = e->exptime_s, nd = e->ndtrans;
	fitsfile *f;
	int status = 0;

	snprintf(path, sizeof(path), "!%s/%s", s->dir, e->file);
	fits_create_file(&f, path, &status);
	fits_create_img(f, USHORT_IMG, 2, naxes, &status);
	fits_write_key(f, TSTRING, "FRAMETYP", (char *)e->type, NULL, &status);
	fits_write_key(f, TDOUBLE, "ANGLE", &a, "deg", &status);
	fits_write_key(f, TDOUBLE, "EXPTIME", &t, "s", &status);
	fits_write_key(f, TDOUBLE, "NDTRANS", &nd, NULL, &status);
	fits_write_key(f, TLONG, "SEQNUM", &seq, NULL, &status);
	fits_write_key(f, TLONG, "COL0", &col0, NULL, &status);
	fits_write_key(f, TLONG, "ROW0", &row0, NULL, &status);
	fits_write_key(f, TLONG, "SATLEVEL", &sat, NULL, &status);
	if (c->sampled)
		fits_write_key_longstr(f, "ROWS", s->rows_text, NULL, &status);
	if (c->monitor)
		fits_write_key(f, TDOUBLE, "MONITOR", &monitor, NULL, &status);
	fits_write_img(f, TUSHORT, 1, (LONGLONG)(c->n_rows * c->n_cols),
		       s->pix, &status);
	fits_close_file(f, &status);
	if (status)
		fits_report_error(stderr, status);
	return status ? -1 : 0;
}

/* Counts of one pixel: offset, dark, light, noise, clipping. */
static uint16_t pixel(struct sweep_state *s, size_t i, double mu_light,
		      double t)
{
	const struct synth_config *c = s->c;
	long row = s->det_row[i / c->n_cols];
	long col = c->col0 + (long)(i % c->n_cols);
	double dark = I_DARK * t + (s->bad[i] == 1 ? s->hot_rate[i] * t : 0.0);
	double mu = offsets[(row % 2) * 4 + col % 4] + dark + mu_light;
	double v = mu + sqrt(READ_NOISE * READ_NOISE + dark + mu_light) *
			normal(&s->rng);

	if (s->bad[i] == 2)
		return 0;
	v = floor(v + 0.5);
	return (uint16_t)(v < 0.0 ? 0.0 : v > SAT_LEVEL ? SAT_LEVEL : v);
}

static void sat_spot(struct sweep_state *s)
{
	const struct synth_config *c = s->c;
	size_t r0 = 2 + (size_t)(uniform(&s->rng) * (double)(c->n_rows - 5));
	size_t c0 = 2 + (size_t)(uniform(&s->rng) * (double)(c->n_cols - 5));
	size_t r, col;

	for (r = r0; r < r0 + 3; r++)
		for (col = c0; col < c0 + 3; col++)
			s->pix[r * c->n_cols + col] = SAT_LEVEL;
	s->t->n_sat_spots++;
}

static int add_entry(struct sweep_state *s, const char *type, double th,
		     double t, double nd, long seq, int spot)
{
	const struct synth_config *c = s->c;
	struct synth_entry *e;
	double src = 1.0 + c->drift * (double)s->frame /
			   (double)(s->n_frames > 1 ? s->n_frames - 1 : 1);
	size_t i, n = c->n_rows * c->n_cols;
	int lit = strcmp(type, "DARK") != 0, full = strcmp(type, "FULL") == 0;

	if (s->t->n_entries == SYNTH_ENTRIES_MAX)
		return -1;
	e = &s->t->entry[s->t->n_entries++];
	snprintf(e->file, sizeof(e->file), "f%04zu_%s.fits", s->frame, type);
	e->type = type;
	e->angle_deg = th;
	e->exptime_s = t;
	e->ndtrans = nd;
	e->seqnum = seq;
	for (i = 0; i < n; i++) {
		double x = ((double)(i % c->n_cols) + 0.5) / c->n_cols - 0.5;
		double light = 0.0;

		if (lit)
			light = t * nd * (src * ((full ? direct_rate(c, th,
				i / c->n_cols, i % c->n_cols) : 0.0) +
				RATE_ATM * (1.0 + x)) + RATE_ROOM);
		s->pix[i] = pixel(s, i, light, t);
	}
	if (spot)
		sat_spot(s);
	s->frame++;
	return write_fits(s, e, src);
}

static void place_bad(struct sweep_state *s)
{
	const struct synth_config *c = s->c;
	size_t n = c->n_rows * c->n_cols;
	int k, want = c->n_hot + c->n_dead;

	for (k = 0; k < want && k < 2 * SYNTH_PIX_MAX;) {
		size_t i = (size_t)(uniform(&s->rng) * (double)n);
		long rc[2];

		if (i >= n || s->bad[i])
			continue;
		rc[0] = s->det_row[i / c->n_cols];
		rc[1] = c->col0 + (long)(i % c->n_cols);
		if (k < c->n_hot && s->t->n_hot < SYNTH_PIX_MAX) {
			s->bad[i] = 1;
			s->hot_rate[i] = 1500.0 + 4500.0 * uniform(&s->rng);
			memcpy(s->t->hot[s->t->n_hot++], rc, sizeof(rc));
		} else if (s->t->n_dead < SYNTH_PIX_MAX) {
			s->bad[i] = 2;
			memcpy(s->t->dead[s->t->n_dead++], rc, sizeof(rc));
		}
		k++;
	}
}

static void set_rows(struct sweep_state *s)
{
	const struct synth_config *c = s->c;
	size_t r, len = 0;

	for (r = 0; r < c->n_rows; r++) {
		/* Sampled: pairs of rows 130 apart, as the thesis's 7 pairs. */
		s->det_row[r] = c->sampled ? c->row0 + (long)(r / 2) * 130 +
						     (long)(r % 2)
					   : c->row0 + (long)r;
		if (c->sampled && len + 24 < sizeof(s->rows_text))
			len += (size_t)snprintf(s->rows_text + len,
						sizeof(s->rows_text) - len,
						"%s%ld", r ? "," : "",
						s->det_row[r]);
	}
}

static int render(struct sweep_state *s)
{
	const struct synth_config *c = s->c;
	size_t n_vis = c->n_angles + (c->revisit ? 1 : 0), v, e;
	double t_of[SYNTH_ANGLES_MAX], nd_of[SYNTH_ANGLES_MAX];
	double t_amb[SYNTH_ANGLES_MAX];
	int used[N_EXP] = { 0 }, k, pass;

	for (v = 0; v < c->n_angles; v++) {
		double th = (double)v * c->theta_step_deg;

		choose_exposure(peak_rate(c, th), &t_of[v], &nd_of[v]);
		t_amb[v] = t_of[v];
		for (e = 0; e < N_EXP; e++) {
			/* The dimmer ambient frame may take the next longer
			 * exposure (eq. 3.6 allows t2 != t1). */
			if (c->amb_longer && exposures[e] == t_of[v] &&
			    e + 1 < N_EXP)
				t_amb[v] = exposures[e + 1];
		}
		for (e = 0; e < N_EXP; e++)
			used[e] |= exposures[e] == t_of[v] ||
				   exposures[e] == t_amb[v];
	}
	s->n_frames = n_vis * 2 * (size_t)c->repeats;
	for (e = 0; e < N_EXP; e++)
		s->n_frames += used[e] ? (size_t)c->darks_per_exp : 0;
	for (e = 0; e < N_EXP; e++)
		for (k = 0; used[e] && k < c->darks_per_exp; k++)
			if (add_entry(s, "DARK", 0.0, exposures[e], 1.0, k, 0))
				return -1;
	for (pass = 0; pass < (c->two_pass ? 2 : 1); pass++)
		for (v = 0; v < n_vis; v++) {
			size_t a = v < c->n_angles ? v : 0;
			double th = (double)a * c->theta_step_deg;
			int spot = c->sat_spots && a % 5 == 2;

			for (k = 0; k < c->repeats; k++) {	/* interleaved */
				long seq = (long)k +
					   (v >= c->n_angles ? c->repeats : 0);

				if ((pass == 0 &&
				     add_entry(s, "FULL", th, t_of[a], nd_of[a],
					       seq, spot && k == 1)) ||
				    ((pass == 1 || !c->two_pass) &&
				     add_entry(s, "AMBIENT", th, t_amb[a],
					       nd_of[a], seq, 0)))
					return -1;
			}
		}
	return 0;
}

static void fill_truth(const struct synth_config *c, struct synth_truth *t)
{
	double p0 = total_direct(c, 0.0);
	size_t v;
	int g;

	t->n_angles = c->n_angles;
	for (v = 0; v < c->n_angles; v++) {
		double th = (double)v * c->theta_step_deg;

		t->theta_deg[v] = th;
		t->alpha[v] = total_direct(c, th) / p0;	/* eq. 3.12 */
		for (g = 0; g < 2; g++) {
			double sg = 0.0;
			size_t col;

			for (col = 0; col < c->n_cols; col++)
				sg += ghost_rate(g, th, col) * (double)c->n_rows;
			t->ghost_col[g][v] = c->ghosts ?
				ghost_centre(g, th) + (double)c->col0 : NAN;
			t->ghost_rel[g][v] = sg / total_direct(c, th);
		}
	}
}

int synth_write_sweep(const char *dir, const struct synth_config *c,
		      struct synth_truth *t)
{
	struct sweep_state s;
	size_t n = c->n_rows * c->n_cols;
	int rc = -1;

	memset(t, 0, sizeof(*t));
	memset(&s, 0, sizeof(s));
	if (c->n_angles > SYNTH_ANGLES_MAX || c->n_rows > 8192)
		return -1;
	s.c = c;
	s.t = t;
	s.dir = dir;
	s.rng.s = c->seed;
	s.det_row = calloc(c->n_rows, sizeof(long));
	s.pix = calloc(n, sizeof(uint16_t));
	s.bad = calloc(n, 1);
	s.hot_rate = calloc(n, sizeof(double));
	mkdir(dir, 0777);
	if (s.det_row && s.pix && s.bad && s.hot_rate) {
		set_rows(&s);
		place_bad(&s);
		fill_truth(c, t);
		rc = render(&s);
	}
	if (rc == 0)
		rc = synth_write_manifest(dir, t, NULL, NULL);
	free(s.det_row);
	free(s.pix);
	free(s.bad);
	free(s.hot_rate);
	return rc;
}

/* SHA-256 of a whole file as hex (OpenSSL). */
static int file_sha256(const char *path, char hex[65])
{
	unsigned char md[32], buf[8192];
	EVP_MD_CTX *ctx = EVP_MD_CTX_new();
	FILE *f = fopen(path, "rb");
	size_t n, i;
	int ok = ctx && f && EVP_DigestInit_ex(ctx, EVP_sha256(), NULL);

	while (ok && (n = fread(buf, 1, sizeof(buf), f)) > 0)
		ok = EVP_DigestUpdate(ctx, buf, n);
	ok = ok && EVP_DigestFinal_ex(ctx, md, NULL);
	if (f)
		fclose(f);
	EVP_MD_CTX_free(ctx);
	for (i = 0; ok && i < 32; i++)
		snprintf(hex + 2 * i, 3, "%02x", md[i]);
	return ok ? 0 : -1;
}

int synth_write_manifest(const char *dir, const struct synth_truth *t,
			 int (*skip)(const struct synth_entry *, void *),
			 void *ctx)
{
	char path[4096], hex[65];
	FILE *f;
	size_t i;
	int rc = 0;

	snprintf(path, sizeof(path), "%s/manifest.csv", dir);
	f = fopen(path, "w");
	if (!f)
		return -1;
	fprintf(f, "file,frametyp,angle_deg,exptime_s,ndtrans,seqnum,sha256\n");
	for (i = 0; i < t->n_entries && rc == 0; i++) {
		const struct synth_entry *e = &t->entry[i];

		if (skip && skip(e, ctx))
			continue;
		snprintf(path, sizeof(path), "%s/%s", dir, e->file);
		rc = file_sha256(path, hex);
		fprintf(f, "%s,%s,%.17g,%.17g,%.17g,%ld,%s\n", e->file, e->type,
			e->angle_deg, e->exptime_s, e->ndtrans, e->seqnum, hex);
	}
	if (fclose(f) != 0)
		rc = -1;
	return rc;
}
