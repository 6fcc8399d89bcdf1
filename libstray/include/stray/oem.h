/*
 * oem.h - CCSDS Orbit Ephemeris Message (502.0-B-3, KVN form): reader,
 * interpolation as its header says, writer.
 *
 * Accepted: versions 1.0 to 3.0 (CLASSIFICATION, MESSAGE_ID), values in
 * any case; CENTER_NAME EARTH, REF_FRAME EME2000/ICRF/GCRF/J2000 or an
 * Earth-fixed or of-date frame (ITRF..., GTOD, TOD, MOD, TEME: converted
 * to inertial once, stray/ccsds.h), TIME_SYSTEM UTC/TAI/TT/GPS,
 * INTERPOLATION LAGRANGE/HERMITE/LINEAR with INTERPOLATION_DEGREE;
 * several segments as the standard means them (stray/ccsds.h: useable
 * spans, a later segment wins where they overlap, no interpolation
 * across segments or across a hole); covariance blocks parsed and
 * checked (6 rows of 1..6 numbers after an EPOCH, variances >= 0,
 * correlations within 1); positions above the Earth's surface and under
 * 1e7 km, speeds up to 25 km/s; a step longer than the interpolation
 * window is a gap, never bridged.  Anything else is refused with the
 * line and keyword named.
 */
#ifndef STRAY_OEM_H
#define STRAY_OEM_H

#include <stddef.h>
#include <stdio.h>

#include "stray/ccsds.h"
#include "stray/error.h"

enum stray_interp { STRAY_INTERP_LAGRANGE, STRAY_INTERP_HERMITE,
		    STRAY_INTERP_LINEAR };

#define STRAY_OEM_DEGREE_MAX 15

struct stray_oem {
	size_t n;		/* records, segment after segment */
	double *t;		/* TT seconds since J2000.0, increasing in a segment */
	double (*r)[3];		/* position [km] */
	double (*v)[3];		/* velocity [km/s] */
	int interp;		/* enum stray_interp */
	int degree;
	int time_system;	/* enum stray_time_system, of the file */
	double gap_s;		/* the first segment's gap rule */
	struct stray_ccsds_cover cover;	/* segments, what each one owns */
	double version;
	char object_name[64], ref_frame[24];	/* the first segment's */
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
 * Never across a gap (stray_ccsds_gap_s): the records of t's side only,
 * of the segment that owns t.  STRAY_ERANGE where no segment covers t
 * or inside a gap.
 */
int stray_oem_state(const struct stray_oem *oem, double t, double r[3],
		    double v[3]);

/* Write records as one OEM segment (EME2000, time system ts). */
int stray_oem_write(FILE *f, const char *object, int ts, const double *t,
		    const double (*r)[3], const double (*v)[3], size_t n,
		    int interp, int degree);

#endif /* STRAY_OEM_H */
