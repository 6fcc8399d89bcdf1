/*
 * fdr_options.h - the command-line options of the FDR setup
 * (stray/fdr_setup.h) that the commands share, and its --json and text.
 */
#ifndef STRAY_TOOLS_FDR_OPTIONS_H
#define STRAY_TOOLS_FDR_OPTIONS_H

#include <cJSON.h>
#include <getopt.h>

#include "stray/fdr_setup.h"

/* Long options shared by the commands, values 1000+ (see fdr_setup.c). */
#define SENSOR_LONG_OPTIONS \
	{ "sensor", required_argument, NULL, 1000 }, \
	{ "sun", required_argument, NULL, 1001 }, \
	{ "vega", required_argument, NULL, 1002 }, \
	{ "qe", required_argument, NULL, 1003 }

/* --normalisation, for every command where a curve meets eq. 2.3. */
#define NORMALISATION_LONG_OPTION \
	{ "normalisation", required_argument, NULL, 1011 }

#define NORMALISATION_USAGE \
	"  --normalisation consistent|thesis\n" \
	"                      eq. 2.3's per-pixel factor k_px: A_cs / (n_tot A_px)\n" \
	"                      for a power-ratio curve (default), or the thesis's 1\n"

/* --detector, for every command that answers with a detector's model. */
#define DETECTOR_LONG_OPTIONS \
	{ "detector", required_argument, NULL, 1012 }, \
	{ "detector-sigma", required_argument, NULL, 1013 }

#define DETECTOR_USAGE \
	"  --detector D        the tracker's star detector: thesis (eq. 2.18 as\n" \
	"                      published, default), window (sliding window sum),\n" \
	"                      threshold (fixed pixel threshold), tetra3 (k sigma\n" \
	"                      of the frame); default: the sensor file's\n" \
	"  --detector-sigma K  tetra3's threshold in frame sigmas (3)\n"

#define FDR_SETUP_LONG_OPTIONS \
	SENSOR_LONG_OPTIONS, \
	NORMALISATION_LONG_OPTION, \
	DETECTOR_LONG_OPTIONS, \
	{ "noise", required_argument, NULL, 1004 }, \
	{ "detector-noise", no_argument, NULL, 1005 }, \
	{ "map", required_argument, NULL, 1006 }, \
	{ "moon-phase", required_argument, NULL, 1007 }, \
	{ "rate", required_argument, NULL, 1008 }, \
	{ "earth-albedo", required_argument, NULL, 1009 }, \
	{ "altitude-km", required_argument, NULL, 1010 }

#define SENSOR_USAGE \
	"  --sensor S          built-in sensor name or JSON file (st16-like)\n" \
	"  --sun F, --vega F, --qe F\n" \
	"                      spectrum CSVs or builtin:NAME, replacing the sensor's\n"

#define FDR_SETUP_USAGE SENSOR_USAGE NORMALISATION_USAGE DETECTOR_USAGE \
	"  --noise gauss|poisson\n" \
	"                      shot-noise model: the thesis's Gaussian (default)\n" \
	"                      or exact Poisson tails\n" \
	"  --detector-noise    add the sensor's read noise and dark current\n" \
	"  --map F.csv         non-uniform stray light: columns fraction,rel_alpha\n" \
	"  --moon-phase DEG    lunar phase angle (0 = full Moon)\n" \
	"  --rate R            tolerated false detections per image\n" \
	"                      (default: the sensor's fdr_tolerated)\n" \
	"  --earth-albedo A    the sunlit Earth's albedo (0.3)\n" \
	"  --altitude-km H     spacecraft altitude for the Earth (550)\n"

/* Handle a shared option: 1 handled, 0 not ours, or CLI_USAGE on error. */
int fdr_setup_option(struct fdr_setup *s, const char *cmd, int opt,
		     const char *arg);

/* "detector" (and "detector_sigma" for tetra3) into a --json object. */
void fdr_setup_detector_json(const struct fdr_setup *s, cJSON *o);

/* "normalisation" and "k_px" into a command's --json object. */
void fdr_setup_json(const struct fdr_setup *s, cJSON *o);

/* The same as one line of text output. */
void fdr_setup_print_normalisation(const struct fdr_setup *s);

#endif /* STRAY_TOOLS_FDR_OPTIONS_H */
