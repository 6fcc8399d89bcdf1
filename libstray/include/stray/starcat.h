/*
 * starcat.h - real star catalogues (issue 24): Hipparcos I/311 `hip2.dat`
 * (van Leeuwen 2007), Hipparcos I/239 `hip_main.dat` (ESA 1997), the Yale
 * Bright Star Catalogue (BSC5, V/50) and a CSV (docs/flightcheck.md:
 * `ra_deg,dec_deg,v_mag,b_v` required; `hip,pmra_mas_yr,pmdec_mas_yr,
 * epoch_jyear,hp_mag` optional).  Each star keeps its catalogue epoch and
 * proper motion; a cone is taken at the epoch asked for (a frame's), the
 * positions moved by the proper motion.  Magnitudes are Johnson V (the
 * Hipparcos Hp of hip2.dat converted to V with B-V: stray_hp_to_v), so the
 * colour term (stray/colour.h) takes them to the sensor's passband.
 * Hosted: the parse is from memory (the fuzz target's entry), the load
 * reads the file whole (nothing is fetched at run time).
 */
#ifndef STRAY_STARCAT_H
#define STRAY_STARCAT_H

#include <stddef.h>

#include "stray/catalogue.h"
#include "stray/error.h"

#define STRAY_STARCAT_MAX_STARS 2000000	/* docs/limits.md */
#define STRAY_STARCAT_MAX_BYTES (256u << 20)	/* STRAY_FILE_READ_MAX */
#define STRAY_STARCAT_PM_MAX_MAS_YR 20000.0	/* Barnard's star: 10.4"/yr */

enum stray_starcat_kind {
	STRAY_STARCAT_HIP2 = 1,	/* I/311 hip2.dat, Hp, epoch J1991.25 */
	STRAY_STARCAT_HIP1,	/* I/239 hip_main.dat, V, epoch J1991.25 */
	STRAY_STARCAT_BSC5,	/* V/50 catalog, V, J2000 */
	STRAY_STARCAT_CSV
};

struct stray_starcat_star {
	double ra_deg, dec_deg;		/* ICRS/FK5 at epoch_jyear */
	double pmra_mas_yr;		/* mu_alpha cos(delta) */
	double pmdec_mas_yr;
	double epoch_jyear;
	double v_mag, b_v;		/* Johnson V and B-V */
	long id;			/* HIP or HR number, 0 when none */
};

struct stray_starcat {
	struct stray_starcat_star *s;
	size_t n;
	int kind;			/* enum stray_starcat_kind */
	size_t n_skipped;		/* records with no position, V or B-V */
};

/* "hip2", "hip_main", "bsc5", "csv". */
const char *stray_starcat_kind_name(int kind);

/* Parse a catalogue held in memory (name: for the messages).  The kind is
 * told by the text (a CSV header, `|` separated HIP records, the I/311
 * or BSC5 fixed columns); a line that is of its kind but broken is an
 * error naming the line and field; records the catalogue leaves without
 * a position, V or B-V are skipped and counted. */
int stray_starcat_parse(const char *text, size_t len, const char *name,
			struct stray_starcat *c, struct stray_error *err);

/* Read path whole and parse it. */
int stray_starcat_load(const char *path, struct stray_starcat *c,
		       struct stray_error *err);

void stray_starcat_free(struct stray_starcat *c);

/* V from Hipparcos Hp and B-V: V - Hp = -0.2964 (B-V) + 0.1110 (B-V)^2
 * (a quadratic fit of the ESA 1997 Hp-V relation for -0.2 < B-V < 1.8,
 * ~0.05 mag; B-V clamped to that range). */
double stray_hp_to_v(double hp, double b_v);

/* The Julian year of TT seconds since J2000. */
double stray_jyear_of_tt(double t_tt_s);

/*
 * The stars brighter than mag_max (V) within radius_deg of dir, at
 * epoch_jyear (proper motion applied along the tangent plane), as
 * stray_cat_star with their B-V.  Writes at most max; *n the number
 * written; returns the number found.
 */
size_t stray_starcat_cone(const struct stray_starcat *c, double epoch_jyear,
			  const double dir[3], double radius_deg,
			  double mag_max, struct stray_cat_star *out,
			  size_t max, size_t *n);

#endif /* STRAY_STARCAT_H */
