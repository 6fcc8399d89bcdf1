/*
 * oem.h - CCSDS Orbit Ephemeris Message (502.0-B-3, KVN form): reader,
 * interpolation as its header says, writer.
 *
 * Accepted: CENTER_NAME EARTH, REF_FRAME EME2000/ICRF/GCRF/J2000,
 * TIME_SYSTEM UTC/TAI/TT/GPS, INTERPOLATION LAGRANGE/HERMITE/LINEAR with
 * INTERPOLATION_DEGREE; several segments, whose epochs must follow each
 * other (an epoch repeated at a segment boundary is kept once);
 * covariance blocks are skipped (one left open is refused); positions
 * above the Earth's surface and under 1e7 km, speeds up to 25 km/s; a
 * step longer than the interpolation window is a gap, never bridged.
 * Anything else is refused with the line
 * and keyword named.
 */
#ifndef STRAY_OEM_H
#define STRAY_OEM_H

#include <stddef.h>
#include <stdio.h>

#include "stray/error.h"

enum stray_interp { STRAY_INTERP_LAGRANGE, STRAY_INTERP_HERMITE,
		    STRAY_INTERP_LINEAR };

#define STRAY_OEM_DEGREE_MAX 15

struct stray_oem {
	size_t n;		/* records */
	double *t;		/* TT seconds since J2000.0, increasing */
	double (*r)[3];		/* position [km] */
	double (*v)[3];		/* velocity [km/s] */
	int interp;		/* enum stray_interp */
	int degree;
	int time_system;	/* enum stray_time_system, of the file */
	double gap_s;		/* longer steps are gaps (stray_ccsds_gap_s) */
	char object_name[64], ref_frame[16];
};

/*
 * Parse the text buf[0..len) (file names it in errors).  On success the
 * caller owns oem (stray_oem_free).  STRAY_EPARSE/EINVAL with the line
 * and keyword in err for a malformed or unsupported message.
 */
int stray_oem_parse(const char *buf, size_t len, const char *file,
		    struct stray_oem *oem, struct stray_error *err);
int stray_oem_read(const char *path, struct stray_oem *oem,
		   struct stray_error *err);
void stray_oem_free(struct stray_oem *oem);

/*
 * State at t (TT s since J2000) by the header's interpolation: Lagrange
 * of degree d on the d+1 records around t (position and velocity each);
 * Hermite on m = max(2, ceil((d+1)/2)) records with their velocities
 * (degree 2m-1, exact on polynomials up to it, velocity its derivative).
 * Never across a gap (stray_ccsds_gap_s): the records of t's side only.
 * STRAY_ERANGE outside the records or inside a gap.
 */
int stray_oem_state(const struct stray_oem *oem, double t, double r[3],
		    double v[3]);

/* Write records as one OEM segment (EME2000, time system ts). */
int stray_oem_write(FILE *f, const char *object, int ts, const double *t,
		    const double (*r)[3], const double (*v)[3], size_t n,
		    int interp, int degree);

#endif /* STRAY_OEM_H */
