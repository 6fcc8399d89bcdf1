/*
 * make_flight.c - the truth generator as a program, for the demo:
 * make_flight DIR A.aem TRUTH.csv [scale] [frames] [window] [lo hi] [CAT]
 * (window 0: full frames; lo, hi: the Sun offset angles swept, deg; CAT:
 * the real sky of that catalogue with colours and proper motion, mixed
 * exposure times, a 1.6 e-/DN gain and a 180 DN bias, a 40" attitude
 * error).  Prints nothing on success; the hidden truth
 * is in the frames' TALPHA/TSCALE keywords for people to check.
 */
#include <stdio.h>
#include <stdlib.h>

#include "truth.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"

int main(int argc, char **argv)
{
	struct fc_truth t;
	struct stray_curve c;
	struct stray_error err = { 0 };
	char msg[512];

	struct stray_starcat cat = { 0 };

	if (argc < 4 || argc > 10 || argc == 8) {
		fputs("usage: make_flight DIR A.aem TRUTH.csv [scale] [frames] [window] [lo hi] [CAT]\n",
		      stderr);
		return 2;
	}
	fc_truth_defaults(&t);
	if (argc > 4)
		t.scale = atof(argv[4]);
	if (argc > 5)
		t.n_frames = atoi(argv[5]);
	if (argc > 6)
		t.window = atoi(argv[6]);
	if (argc > 8) {
		t.theta_lo_deg = atof(argv[7]);
		t.theta_hi_deg = atof(argv[8]);
	}
	if (argc > 9) {
		if (stray_starcat_load(argv[9], &cat, &err) != STRAY_OK) {
			fprintf(stderr, "make_flight: %s\n",
				stray_error_format(&err, msg, sizeof(msg)));
			return 2;
		}
		t.cat = &cat;
		t.mixed_exposure = 1;
		t.gain_e_per_dn = 1.6;
		t.bias_dn = 180.0;
		t.point_err_arcsec = 40.0;
	}
	if (!(t.scale > 0.0) || t.n_frames < 2 || t.n_frames > 600 || t.window < 0 ||
	    !(t.theta_lo_deg >= 0.0 && t.theta_hi_deg <= 180.0)) {
		fputs("make_flight: scale > 0, 2 <= frames <= 600, window >= 0\n", stderr);
		return 2;
	}
	if (stray_curve_load(argv[3], &c, &err) != STRAY_OK ||
	    (t.curve = stray_curve_view_of(&c),
	     fc_truth_write(&t, argv[1], argv[2], &err)) != STRAY_OK) {
		fprintf(stderr, "make_flight: %s\n",
			stray_error_format(&err, msg, sizeof(msg)));
		return 2;
	}
	stray_curve_free(&c);
	stray_starcat_free(&cat);
	return 0;
}
