/*
 * lanes.h - sums over a full frame's pixels in STRAY_LANES independent
 * partial sums (pixel i into lane i % STRAY_LANES), added in lane order
 * at the end.  One running double sum is a chain of dependent additions,
 * bound by the adder's latency (~4 cycles a pixel, 20 M cycles a frame);
 * eight chains run at the adder's throughput and vectorise, and the
 * order stays fixed, so a result does not depend on the machine.
 */
#ifndef STRAY_REDUCE_LANES_H
#define STRAY_REDUCE_LANES_H

#define STRAY_LANES 8

static inline double stray_lanes_total(const double *lane)
{
	double s = 0.0;
	int k;

	for (k = 0; k < STRAY_LANES; k++)
		s += lane[k];
	return s;
}

#endif /* STRAY_REDUCE_LANES_H */
