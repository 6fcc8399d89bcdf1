/*
 * ccsds.h - what the CCSDS KVN readers (stray/oem.h, stray/aem.h) share:
 * epochs in the supported time systems, reduced to TT seconds since
 * J2000.0 (2000-01-01T12:00:00 TT), and the line splitter of the KVN form
 * (CCSDS 502.0-B-3 §7, 504.0-B-2 §6: "KEY = value", COMMENT lines, blank
 * lines, data lines of white-space separated fields).
 */
#ifndef STRAY_CCSDS_H
#define STRAY_CCSDS_H

#include <stddef.h>

#include "stray/error.h"

enum stray_time_system { STRAY_TS_UTC, STRAY_TS_TAI, STRAY_TS_TT,
			 STRAY_TS_GPS };

/* The time system named by text (UTC, TAI, TT, GPS); -1 if unsupported. */
int stray_ccsds_time_system(const char *text);

/* An inertial frame the readers accept (EME2000, ICRF, GCRF, J2000). */
int stray_ccsds_inertial_frame(const char *text);

/*
 * "YYYY-MM-DDThh:mm:ss[.f]" or "YYYY-DDDThh:mm:ss[.f]" (an optional
 * trailing Z) in time system ts, to TT seconds since J2000.0.  UTC takes
 * the leap seconds of 1972-2017 (TAI - UTC = 37 s since 2017-01-01).
 * Returns 0, -1 if the text is not an epoch, -2 if its second is 60 where
 * no leap second is (only UTC has them, at 23:59:60 of the days of the
 * table).
 */
int stray_ccsds_epoch(const char *text, int ts, double *t_tt);

/*
 * The gap rule (docs/limits.md): a step between records is a gap when it
 * is longer than the interpolation window's nominal span, (nodes - 1)
 * times the median step and never under 2 of them; interpolation never
 * crosses one.  stray_ccsds_gap_s gives that length for records t[0..n)
 * (-1 out of memory); stray_ccsds_gaps counts the gaps.
 */
double stray_ccsds_gap_s(const double *t, size_t n, size_t nodes);
size_t stray_ccsds_gaps(const double *t, size_t n, double gap_s);

/*
 * The records around `at` that interpolation may use: t[*lo .. *hi], no
 * gap among them, at most `reach` records to either side of the step
 * holding `at`.  Returns 0, or -1 when `at` is outside t[0 .. n-1] or
 * inside a gap (a record on a gap's edge is covered, alone if need be).
 */
int stray_ccsds_piece(const double *t, size_t n, double gap_s, double at,
		      size_t reach, size_t *lo, size_t *hi);

/* Days from 2000-01-01 to the civil date y-m-d (negative before). */
long stray_ccsds_days_from_2000(long y, long m, long d);

/* The inverse for writing: t_tt to "YYYY-MM-DDThh:mm:ss.ffffff" in ts. */
void stray_ccsds_format_epoch(double t_tt, int ts, char *buf, size_t size);

/* A finite decimal number, [+-]d[.d][E[+-]d] and nothing after it (no
 * hex float, INF or NAN, which strtod alone takes): 1, else 0. */
int stray_kvn_number(const char *s, double *x);

/* One KVN line split in place (the line buffer is modified). */
struct stray_kvn_line {
	int kind;		/* STRAY_KVN_* */
	char *key, *value;	/* KEY = value */
	char *field[16];	/* data fields */
	int n_field;
};
enum { STRAY_KVN_BLANK, STRAY_KVN_COMMENT, STRAY_KVN_KEYVAL,
       STRAY_KVN_DATA, STRAY_KVN_WORD };

/*
 * Split the next line of buf[*pos .. len) into line (copied into scratch
 * of size scratch_size, a line longer than that is an error); *lineno
 * counts lines.  Returns 1 for a line, 0 at the end, -1 for a line too
 * long or holding a NUL byte (err names file and line).
 */
int stray_kvn_next(const char *buf, size_t len, size_t *pos, long *lineno,
		   char *scratch, size_t scratch_size,
		   struct stray_kvn_line *line, const char *file,
		   struct stray_error *err);

/*
 * Feed each line of buf[0 .. len) but blank and COMMENT ones to
 * fn(ctx, line), in order, until fn returns other than STRAY_OK;
 * *lineno counts lines (for fn's own messages).  Returns STRAY_OK, what
 * fn returned, or STRAY_EPARSE for a line stray_kvn_next refuses.
 */
int stray_kvn_each(const char *buf, size_t len, const char *file,
		   long *lineno,
		   int (*fn)(void *ctx, const struct stray_kvn_line *line),
		   void *ctx, struct stray_error *err);

/* A keyword of the message header the readers pass over (CREATION_DATE,
 * ORIGINATOR, MESSAGE_ID, CLASSIFICATION of OEM 3.0 / AEM 2.0): 1,
 * else 0. */
int stray_kvn_header_key(const char *key);

/* Sets err to "file:line: keyword `key`: why" with text; STRAY_EPARSE. */
int stray_kvn_fail(struct stray_error *err, const char *file, long line,
		   const char *key, const char *why, const char *text);

/*
 * Reference frames of a state or an attitude's external frame.  The
 * inertial ones (EME2000, ICRF, GCRF, J2000) are taken as one (their
 * 23 mas frame bias, under 1 m at LEO, is neglected); the others are
 * converted to it once, on reading, with ERFA (IAU 2000B precession-
 * nutation, 1 mas): ITRF/ITRFxx/ITRF-xx (Earth-fixed: polar motion,
 * Earth rotation), GTOD (Greenwich true of date, no polar motion), TOD,
 * MOD, TEME.  UT1 - UTC and the pole come from the table
 * stray_ccsds_eop_load read, zero without one (docs/availability.md:
 * up to 0.9 s of UT1 - UTC, 0.45 km along a LEO track).
 */
enum stray_ccsds_frame { STRAY_FRAME_INERTIAL, STRAY_FRAME_ITRF,
			 STRAY_FRAME_GTOD, STRAY_FRAME_TOD, STRAY_FRAME_MOD,
			 STRAY_FRAME_TEME };

/* The frame named by text (case-insensitive), -1 if not supported. */
int stray_ccsds_frame(const char *text);

/* m maps inertial (GCRS) coordinates to the frame's at t_tt; w is the
 * frame's rotation rate in its own axes [rad/s] (zero but for the
 * Earth-fixed ones). */
void stray_ccsds_frame_dcm(int frame, double t_tt, double m[3][3],
			   double w[3]);

/* r [km], v [km/s] (v may be NULL) in `frame` at t_tt, to inertial. */
void stray_ccsds_to_inertial(int frame, double t_tt, double r[3],
			     double v[3]);

/* The same for a reader's run of records: the precession-nutation and
 * the equation of the equinoxes taken on a 600 s grid and interpolated
 * (0.3 microarcsec), ~10 times faster.  A cache is the caller's (zero
 * it first), one per thread. */
struct stray_ccsds_frame_slot { double node; int have; double v[2][9]; };
struct stray_ccsds_frame_cache { struct stray_ccsds_frame_slot npb, ee; };
void stray_ccsds_frame_dcm_cached(struct stray_ccsds_frame_cache *c,
				  int frame, double t_tt, double m[3][3],
				  double w[3]);
void stray_ccsds_to_inertial_cached(struct stray_ccsds_frame_cache *c,
				    int frame, double t_tt, double r[3],
				    double v[3]);

/*
 * Earth orientation from an IERS table (finals2000A.all / finals.data
 * fixed columns: MJD, x_p, y_p [arcsec], UT1 - UTC [s]), linear between
 * days; without a table, or outside it, all three are zero.  Replaces
 * the table held (process-wide); STRAY_EPARSE/EIO with the line named.
 */
int stray_ccsds_eop_load(const char *path, struct stray_error *err);
void stray_ccsds_eop_clear(void);
/* x_p, y_p [rad], UT1 - UTC [s] at MJD (UTC); 1 if from the table. */
int stray_ccsds_eop_at(double mjd, double *xp, double *yp, double *dut1);

/* Values are case-insensitive (502.0-B-3 §7.5.2, 504.0-B-2 §6.5.1:
 * `CENTER_NAME = Earth`): ASCII case folded, 1 when a and b are equal. */
int stray_kvn_eq(const char *a, const char *b);

/*
 * Segments as the standard means them (502.0-B-3 §5.2.2, 504.0-B-2
 * §4.2.4): each covers its useable span (USEABLE_START_TIME ..
 * USEABLE_STOP_TIME, else its first to last record); where spans
 * overlap the later segment wins inside its useable span (as Orekit
 * does); interpolation uses one segment's records only, and time no
 * segment covers is a hole, never interpolated across.
 */
#define STRAY_CCSDS_SEG_MAX 10000

struct stray_ccsds_seg {
	size_t lo, n;		/* its records: [lo, lo + n) of the arrays */
	double u0, u1;		/* useable span, TT s (set, or its records') */
	int have_u0, have_u1;
	double gap_s;		/* its gap rule (stray_ccsds_gap_s) */
	size_t nodes;		/* its interpolation window, 0: the build's */
	int interp, degree;	/* the OEM's INTERPOLATION of this segment */
	int frame;		/* enum stray_ccsds_frame, as the file says */
	int time_system;
	long line;		/* its META_START */
	size_t n_cov;		/* covariance matrices read (OEM) */
	char frame_name[24];	/* REF_FRAME, or the AEM's external frame */
	char kind[24];		/* the AEM's ATTITUDE_TYPE */
};

/* A stretch [a, b] that segment `seg` owns; pieces are sorted, disjoint
 * but for shared ends, where the later one (higher index) wins. */
struct stray_ccsds_piece { double a, b; size_t seg; };

struct stray_ccsds_cover {
	struct stray_ccsds_seg *seg;
	size_t n_seg, cap_seg;
	struct stray_ccsds_piece *piece;
	size_t n_piece;
	double t0, t1;		/* first and last covered epoch */
};

/* A new segment at the end (its fields zeroed); NULL out of memory. */
struct stray_ccsds_seg *stray_ccsds_cover_add(struct stray_ccsds_cover *c);

/*
 * Once every record is read: each segment's gap rule for an
 * interpolation window of its `nodes` records (`nodes` where unset), its useable span checked
 * against its records (-1 with *bad the segment that has a useable span
 * outside its records or empty), the owned pieces.  0, -1 as said, -2
 * out of memory.
 */
int stray_ccsds_cover_build(struct stray_ccsds_cover *c, const double *t,
			    size_t nodes, size_t *bad);

/* stray_ccsds_cover_build with its refusal said as the readers say it:
 * a KVN error of file at the bad segment's META_START line (bad input),
 * or out of memory. */
int stray_ccsds_cover_finish(struct stray_ccsds_cover *c, const double *t,
			     size_t nodes, const char *file,
			     struct stray_error *err);

/* The segment that owns epoch `at`, or -1 where none does. */
long stray_ccsds_cover_find(const struct stray_ccsds_cover *c, double at);

/* Stretches inside [t0, t1] interpolation will not cross: time owned by
 * no segment, and gaps (the gap rule) inside the owned pieces. */
size_t stray_ccsds_cover_holes(const struct stray_ccsds_cover *c,
			       const double *t);

void stray_ccsds_cover_free(struct stray_ccsds_cover *c);

#endif /* STRAY_CCSDS_H */
