/*
 * fdr_field.h - the FDR model extended to what a real star detector does
 * (issue 13 item 5).  Freestanding C99, no heap.
 *
 * The thesis counts n_tot / n_pps independent windows (eq. 2.18).  A
 * detector that slides the n_pps window over every pixel and reports one
 * star per connected above-threshold region sees a smoothed Gaussian
 * field; its false stars are the excursion blobs of that field above u.
 * A blob is counted once, at its first pixel in raster order: a pixel
 * above u whose four already-scanned neighbours (left, up-left, up,
 * up-right) are below u.  This is the lattice form of the Euler-
 * characteristic (Rice upcrossing) count of excursion sets (Adler 1981,
 * "The Geometry of Random Fields", Wiley, ch. 4; Worsley 1996, Adv. Appl.
 * Prob. 28, 943), exact for blobs that are convex along rows.  Given the
 * pixel value x, the neighbours are taken as conditionally independent
 * normals N(rho_i x, 1 - rho_i^2), rho_i the window overlap at that
 * offset (white pixel noise), so
 *
 *   rate = n_tot Pr_fd(u) g(u),
 *   g(u) = (1/Q(u)) int_u^inf phi(x) prod_i Phi((u - rho_i x)/sqrt(1 - rho_i^2)) dx,
 *
 * g -> 1/(blob size in pixels); the thesis has g = 1/n_pps.
 *
 * The open star-tracker detector (threshold on single pixels, connected
 * components of at least m pixels) has, for pixel exceedance probability
 * p, n_tot sum_{s>=m} a_s p^s (1 - p)^(b_s) false stars: a_s fixed
 * 8-connected lattice animals of s cells (fixed polyplets), b_s their
 * mean 8-neighbour perimeter (both by enumeration; the low-density
 * cluster expansion of site percolation, Stauffer & Aharony 1994,
 * "Introduction to Percolation Theory", ch. 2).
 */
#ifndef STRAY_FDR_FIELD_H
#define STRAY_FDR_FIELD_H

#include "stray/fdr.h"

/* Neighbour correlations of a sliding window sum of white pixel noise. */
struct stray_window_corr {
	stray_real n_px;	/* pixels of the window */
	stray_real rho[4];	/* offsets (-1,0), (-1,-1), (0,-1), (1,-1) */
};

/* Largest cluster size summed by the pixel-cluster model. */
#define STRAY_CLUSTER_SIZE_MAX 10

/*
 * The disk window of radius r_px (pixel centres within r of the centre
 * pixel's: 113 px for r = 6, the st16-like 12 px window) and its
 * neighbour correlations |W n (W + d)| / |W|.
 */
int stray_window_disk_corr(stray_real r_px, struct stray_window_corr *c,
			   struct stray_error *err);

/* g(u) above: blobs per above-threshold pixel, u in window sigmas. */
int stray_fdr_blob_factor(const struct stray_window_corr *c, stray_real u,
			  stray_real *g, struct stray_error *err);

/*
 * ln of the extended rate for the sliding-window detector: eq. 2.17's
 * Pr_fd of the model m (Gaussian or Poisson, with its detector noise and
 * map) times n_tot g(u), u = I_sdt / sigma_window, summed over the map.
 */
int stray_fdr_log_rate_sliding(const struct stray_fdr_model *m,
			       const struct stray_window_corr *c,
			       stray_real alpha, stray_real i_sdt,
			       stray_real *log_fdr, struct stray_error *err);

/*
 * The attenuation (in the model's own eq. 2.3 units, k_px folded into
 * alpha by the caller) at which the sliding-window detector sees `rate`
 * false stars per frame of m->n_tot pixels (fig. 2.7 for the real
 * detector): a bracketed root search on ln rate(ln alpha).
 */
int stray_fdr_alpha_required_sliding(const struct stray_fdr_model *m,
				     const struct stray_window_corr *c,
				     stray_real i_sdt, stray_real rate,
				     stray_real *alpha_req,
				     struct stray_error *err);

/* Fixed 8-connected lattice animals of s cells, s = 1..10 (0 outside). */
stray_real stray_polyplets_fixed(unsigned s);

/*
 * ln of the expected clusters of >= min_px 8-connected pixels each above
 * a pixel threshold t_e (e- above the mean) for n_px pixels whose counts
 * are Poisson of mean mu_e plus Gaussian noise of variance var_e (shifted
 * Poisson, as in fdr.c).
 */
int stray_fdr_log_rate_clusters(stray_real n_px, stray_real mu_e,
				stray_real var_e, stray_real t_e,
				unsigned min_px, stray_real *log_fdr,
				struct stray_error *err);

#endif /* STRAY_FDR_FIELD_H */
