/*
 * aem.h - CCSDS Attitude Ephemeris Message (504.0-B-2, KVN form) with
 * ATTITUDE_TYPE QUATERNION: reader, SLERP, writer.
 *
 * Quaternions mean what 504.0 says: q = (q_c, e), and with
 * ATTITUDE_DIR = A2B its direction-cosine matrix
 *   M(q) = (q_c^2 - e.e) I + 2 e e^T - 2 q_c [e x]
 * maps frame-A coordinates to frame-B coordinates.  QUATERNION_TYPE
 * FIRST (q_c first) or LAST, and ATTITUDE_DIR A2B or B2A are honoured;
 * one of REF_FRAME_A and REF_FRAME_B must be inertial (EME2000, ICRF,
 * GCRF) or Earth-fixed or of date (stray/ccsds.h: converted at each
 * epoch), the other is the body.  Version 2.0 has no ATTITUDE_DIR nor
 * QUATERNION_TYPE (refused there): A to B, q_c last.  Euler angles are
 * in the data line in rotation order (angle about the sequence's first
 * axis first), M = R_a3 R_a2 R_a1; spin is the 3-1-3 rotation
 * (90 + alpha, 90 - delta, phi), as Orekit reads both.  The reader
 * stores every record as q_ib = (q_c, e1, e2, e3) with
 * v_body = M(q_ib) v_inertial; segments as stray/ccsds.h says.
 */
#ifndef STRAY_AEM_H
#define STRAY_AEM_H

#include <stddef.h>
#include <stdio.h>

#include "stray/ccsds.h"
#include "stray/error.h"
#include "stray/quaternion.h"

struct stray_aem {
	size_t n;
	double *t;		/* TT seconds since J2000.0, increasing */
	double (*q)[4];		/* q_ib (q_c, e1, e2, e3), unit, hemisphere-continuous */
	int time_system;
	double gap_s;		/* the first segment's gap rule */
	struct stray_ccsds_cover cover;	/* segments, what each one owns */
	double version;
	char object_name[64];
};

int stray_aem_parse(const char *buf, size_t len, const char *file,
		    struct stray_aem *aem, struct stray_error *err);
int stray_aem_read(const char *path, struct stray_aem *aem,
		   struct stray_error *err);
void stray_aem_free(struct stray_aem *aem);

/* q_ib at t by SLERP between the records around it, in the segment that
 * owns t; STRAY_ERANGE where no segment covers t or inside a gap (a step
 * over twice the median, never bridged: stray_ccsds_gap_s). */
int stray_aem_attitude(const struct stray_aem *aem, double t, double q[4]);

/* Write one segment: EME2000 -> SC_BODY_1, A2B, QUATERNION_TYPE LAST. */
int stray_aem_write(FILE *f, const char *object, int ts, const double *t,
		    const double (*q)[4], size_t n);

#endif /* STRAY_AEM_H */
