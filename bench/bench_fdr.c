/*
 * bench_fdr.c - cost of the FDR model's operations, as ratios against a
 * baseline measured in the same run (one erfc call), so the figures mean
 * the same on a loaded or an idle machine.
 */
#include <math.h>
#include <stdio.h>
#include <time.h>

#include "stray/fdr.h"
#include "stray/photometry_io.h"

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static volatile double sink;

static double per_call_erfc(long n)
{
	double t0 = now_s(), acc = 0.0;
	long i;

	for (i = 0; i < n; i++)
		acc += erfc(1.0 + 1e-7 * (double)i);
	sink = acc;
	return (now_s() - t0) / n;
}

int main(void)
{
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_fluxes f;
	struct stray_fdr_model m;
	struct stray_error err;
	double base, t0, a = 0.0, i_sdt, lf;
	long i, n = 2000;

	stray_error_clear(&err);
	base = per_call_erfc(2000000);
	t0 = now_s();
	for (i = 0; i < 20; i++)
		stray_reference_fluxes(s, &f, &err);
	printf("reference fluxes (3 spectra, eq. 2.1): %8.0f erfc-calls each\n",
	       (now_s() - t0) / 20 / base);
	stray_sensor_fdr_model(s, f.sun, f.drs, &m);
	stray_fdr_threshold(&m, &i_sdt, &err);
	t0 = now_s();
	for (i = 0; i < 200000; i++) {
		stray_fdr_log_rate(&m, 1e-6 * (1.0 + 1e-6 * i), i_sdt, &lf, &err);
		a += lf;
	}
	printf("FDR at one alpha (Gaussian):           %8.1f erfc-calls each\n",
	       (now_s() - t0) / 200000 / base);
	t0 = now_s();
	for (i = 0; i < n; i++)
		stray_fdr_alpha_required(&m, 5.0 + 1e-9 * i, &a, &err);
	printf("alpha_required (Brent, Gaussian):      %8.1f erfc-calls each\n",
	       (now_s() - t0) / n / base);
	m.noise = STRAY_NOISE_POISSON;
	t0 = now_s();
	for (i = 0; i < n / 10; i++)
		stray_fdr_alpha_required(&m, 5.0 + 1e-9 * i, &a, &err);
	printf("alpha_required (exact Poisson):        %8.1f erfc-calls each\n",
	       (now_s() - t0) / (n / 10) / base);
	printf("(baseline: one erfc call = %.1f ns on this machine, this run)\n",
	       base * 1e9);
	sink = a;
	return 0;
}
