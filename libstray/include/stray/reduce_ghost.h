/*
 * reduce_ghost.h - internal reflections ("ghosts", the A and B of thesis
 * fig. 3.8-3.9): secondary maxima of the row-collapsed profile of J at
 * each angle, tracked across angles.
 *
 * A peak is a local maximum of the profile above its background (the
 * smooth illumination gradient, which off axis runs along the rows): the
 * mean of the medians of two side bands, window/6 to window/2 columns
 * either side, so a straight gradient leaves no residual and a bump
 * narrower than the gap is not in its own background;
 * after a [1 2 2 2 1]/8 kernel that cancels the Bayer colour and channel
 * periods (2 and 4 columns), where the excess is min_z standard errors of
 * the profile and min_rel of the local level.  A track links peaks
 * of consecutive angles whose column follows the track's last motion
 * within a gate.  No heap: caller arrays.
 */
#ifndef STRAY_REDUCE_GHOST_H
#define STRAY_REDUCE_GHOST_H

#include <stddef.h>

#define STRAY_GHOST_PEAKS_MAX 8

struct stray_ghost_opts {
	size_t window;		/* background window, columns (odd) */
	double min_z;		/* significance of a peak */
	double min_rel;		/* peak excess over the local level */
	double gate_cols;	/* track gate, columns */
	size_t min_points;	/* shortest track reported */
};

void stray_ghost_opts_default(struct stray_ghost_opts *o);

struct stray_ghost_peak {
	double column;		/* centroid, stored-column index */
	double excess;		/* profile excess summed over the peak */
	double z;		/* peak excess / its standard error */
};

/* Scratch doubles stray_ghost_find needs for n_cols columns. */
size_t stray_ghost_scratch(size_t n_cols, const struct stray_ghost_opts *o);

/*
 * Peaks of one profile, strongest first, at most max_peaks.  The excess
 * is in profile units times columns (multiply by the rows for power).
 */
size_t stray_ghost_find(const double *profile, const double *var_profile,
			size_t n_cols, const struct stray_ghost_opts *o,
			double *scratch, struct stray_ghost_peak *peaks,
			size_t max_peaks);

struct stray_ghost_point {
	double theta_deg;
	double column;
	double excess;		/* power in the ghost, J units */
	double power;		/* P(theta) of that angle */
};

struct stray_ghost_track {
	size_t n, cap;
	struct stray_ghost_point *pt;	/* caller array of cap points */
	size_t last_step;	/* angle step of the last point */
};

struct stray_ghost_tracker {
	struct stray_ghost_opts opts;
	struct stray_ghost_track *tracks;
	size_t n_tracks, max_tracks;
	size_t step;		/* angles added so far */
	size_t n_dropped;	/* peaks with no room for a new track */
};

void stray_ghost_tracker_init(struct stray_ghost_tracker *t,
			      const struct stray_ghost_opts *o,
			      struct stray_ghost_track *tracks,
			      size_t max_tracks);

/* Add the peaks of the next angle (angles must increase). */
void stray_ghost_tracker_add(struct stray_ghost_tracker *t, double theta_deg,
			     const struct stray_ghost_peak *peaks,
			     size_t n_peaks, double n_rows, double power);

/* Drop tracks shorter than opts.min_points; returns the tracks kept. */
size_t stray_ghost_tracker_finish(struct stray_ghost_tracker *t);

#endif /* STRAY_REDUCE_GHOST_H */
