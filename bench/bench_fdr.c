/*
 * bench_fdr.c - cost of the FDR model's operations, as ratios against a
 * baseline (one erfc call) measured right before each, in alternating
 * runs (baseline, operation, baseline, ...; bench_alt.h): the median and
 * min-max of the pairs' ratios, so the figures mean the same on a loaded
 * or an idle machine and their noise is shown.
 */
#include <math.h>
#include <stdio.h>

#include "bench_alt.h"
#include "stray/fdr.h"
#include "stray/photometry_io.h"

static volatile double sink;

static double per_call_erfc(long n)
{
	double t0 = bench_now(), acc = 0.0;
	long i;

	for (i = 0; i < n; i++)
		acc += erfc(1.0 + 1e-7 * (double)i);
	sink = acc;
	return (bench_now() - t0) / n;
}

/* One timed run of operation op: seconds per call. */
static double per_call_op(int op, const struct stray_sensor *s,
			  struct stray_fdr_model *m, double i_sdt)
{
	struct stray_fluxes f;
	struct stray_error err;
	double t0, a = 0.0, lf;
	long i, n = op == 0 ? 20 : op == 1 ? 200000 : op == 2 ? 2000 : 200;
	int noise = m->noise;

	stray_error_clear(&err);
	if (op == 3)
		m->noise = STRAY_NOISE_POISSON;
	t0 = bench_now();
	for (i = 0; i < n; i++) {
		if (op == 0)
			stray_reference_fluxes(s, &f, &err);
		else if (op == 1) {
			stray_fdr_log_rate(m, 1e-6 * (1.0 + 1e-6 * i), i_sdt,
					   &lf, &err);
			a += lf;
		} else
			stray_fdr_alpha_required(m, 5.0 + 1e-9 * i, &a, &err);
	}
	sink = a;
	t0 = (bench_now() - t0) / n;
	m->noise = noise;
	return t0;
}

int main(void)
{
	static const char *const label[4] = {
		"reference fluxes (3 spectra, eq. 2.1): ",
		"FDR at one alpha (Gaussian):           ",
		"alpha_required (Brent, Gaussian):      ",
		"alpha_required (exact Poisson):        " };
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_fluxes f;
	struct stray_fdr_model m;
	struct stray_error err;
	double base[BENCH_MAX_PAIRS], t[BENCH_MAX_PAIRS], all[BENCH_MAX_PAIRS];
	double i_sdt, lo, hi;
	int pairs = bench_pairs(), op, i, nb = 0;

	stray_error_clear(&err);
	stray_reference_fluxes(s, &f, &err);
	stray_sensor_fdr_model(s, f.sun, f.drs, &m);
	stray_fdr_threshold(&m, &i_sdt, &err);
	printf("erfc-calls each, median (min-max) of %d alternating pairs:\n",
	       pairs);
	for (op = 0; op < 4; op++) {
		for (i = 0; i < pairs; i++) {
			base[i] = per_call_erfc(500000);
			t[i] = per_call_op(op, s, &m, i_sdt);
			if (nb < BENCH_MAX_PAIRS)
				all[nb++] = base[i];
		}
		bench_ratio(label[op], t, base, pairs, 8, op ? 1 : 0);
	}
	printf("(baseline: one erfc call = %.1f ns on this machine, this run,"
	       " median of %d)\n", 1e9 * bench_median(all, nb, &lo, &hi), nb);
	return 0;
}
