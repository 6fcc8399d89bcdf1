/*
 * cmd_photometer.c - `stray photometer`: a virtual photometer sweep of a
 * baffle alone (thesis §4.1: a photometer behind the baffle on the rotation
 * stage, 0-85 deg every 1 deg), made from a "true" curve by the effects of
 * a lab measurement: an ambient / atmospheric floor added to the signal,
 * relative read-out noise, and the instrument's detection floor.
 *
 * It is the lab half of the demo's diagnosis: the true curve comes from
 * `stray trace` with whatever the designer did not know (a coating, an edge
 * radius), and `stray diagnose` is then given only this measured curve.
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "stray/curve_io.h"
#include "tracer/rng.h"

#define TWO_PI 6.28318530717958647692

static const char usage[] =
	"usage: stray photometer --truth T.csv --out M.csv [--noise-rel R]\n"
	"                        [--floor F] [--detect-floor D] [--seed K]\n"
	"\n"
	"A virtual photometer sweep of a baffle alone (thesis §4.1) from a true\n"
	"attenuation curve: alpha_meas = alpha + F + noise, noise Gaussian with\n"
	"standard deviation sqrt((R alpha)^2 + D^2), readings below D reported\n"
	"as D; the sigma column says what the instrument would claim.\n"
	"\n"
	"  --truth T.csv       the true curve (e.g. from stray trace)\n"
	"  --out M.csv         the measured curve (theta_deg,alpha,sigma)\n"
	"  --noise-rel R       relative read-out noise (0.03)\n"
	"  --floor F           ambient and atmospheric floor, added (1e-7)\n"
	"  --detect-floor D    detection floor, absolute noise (1e-7)\n"
	"  --seed K            noise seed (1)\n";

struct photometer_args {
	const char *truth, *out;
	double noise_rel, floor, detect_floor;
	unsigned long long seed;
};

/* A standard normal number from the counter-based stream (Box-Muller). */
static double gauss(struct tracer_rng *r)
{
	double u1 = tracer_rng_uniform(r), u2 = tracer_rng_uniform(r);

	return sqrt(-2.0 * log(1.0 - u1)) * cos(TWO_PI * u2);
}

static int measure(const struct photometer_args *a, const struct stray_curve *t,
		   struct stray_curve *m, struct stray_error *err)
{
	struct tracer_rng rng;
	size_t i;
	int rc = stray_curve_alloc(m, t->n, 1, err);

	if (rc)
		return rc;
	for (i = 0; i < t->n; i++) {
		double x = t->alpha[i] + a->floor;
		double s = sqrt(a->noise_rel * a->noise_rel * x * x +
				a->detect_floor * a->detect_floor);

		tracer_rng_init(&rng, a->seed, i);	/* one stream per angle */
		x += s * gauss(&rng);
		m->theta_deg[i] = t->theta_deg[i];
		m->alpha[i] = fmax(x, a->detect_floor);
		m->sigma[i] = s;
	}
	rc = stray_curve_add_meta(m, "kind", "baffle", err);
	if (!rc)
		rc = stray_curve_add_meta(m, "source",
			"virtual photometer sweep (stray photometer)", err);
	return rc;
}

static int parse_args(int argc, char **argv, struct photometer_args *a)
{
	static const struct option opts[] = {
		{ "truth", required_argument, NULL, 't' },
		{ "out", required_argument, NULL, 'o' },
		{ "noise-rel", required_argument, NULL, 'n' },
		{ "floor", required_argument, NULL, 'f' },
		{ "detect-floor", required_argument, NULL, 'd' },
		{ "seed", required_argument, NULL, 's' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	double seed = 1.0;
	int opt, rc = CLI_OK;

	while (rc == CLI_OK &&
	       (opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 'h': fputs(usage, stdout); return -1;
		case 't': a->truth = optarg; break;
		case 'o': a->out = optarg; break;
		case 'n': rc = cli_parse_double("photometer", "noise-rel", optarg, &a->noise_rel); break;
		case 'f': rc = cli_parse_double("photometer", "floor", optarg, &a->floor); break;
		case 'd': rc = cli_parse_double("photometer", "detect-floor", optarg, &a->detect_floor); break;
		case 's': rc = cli_parse_double("photometer", "seed", optarg, &seed); break;
		default:
			return cli_usage_error("photometer", "unknown option '%s'",
					       argv[optind - 1]);
		}
	}
	if (rc != CLI_OK)
		return rc;
	if (!a->truth || !a->out)
		return cli_usage_error("photometer", "--truth and --out are required");
	if (!(a->noise_rel >= 0.0 && a->noise_rel < 1.0) || !(a->floor >= 0.0) ||
	    !(a->detect_floor > 0.0))
		return cli_usage_error("photometer", "--noise-rel must be in [0, 1), --floor >= 0, --detect-floor > 0");
	if (!(seed >= 0.0 && seed < 1.8e19 && seed == floor(seed)))
		return cli_usage_error("photometer", "option '--seed': must be a whole number >= 0");
	a->seed = (unsigned long long)seed;
	return CLI_OK;
}

int cmd_photometer(int argc, char **argv)
{
	struct photometer_args a = { NULL, NULL, 0.03, 1e-7, 1e-7, 1 };
	struct stray_curve truth, meas;
	struct stray_error err;
	int rc = parse_args(argc, argv, &a);

	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	if (stray_curve_load(a.truth, &truth, &err) != STRAY_OK)
		return cli_fail("photometer", &err);
	rc = measure(&a, &truth, &meas, &err);
	if (!rc)
		rc = stray_curve_save(a.out, &meas, &err);
	stray_curve_free(&truth);
	stray_curve_free(&meas);
	return rc ? cli_fail("photometer", &err) : CLI_OK;
}
