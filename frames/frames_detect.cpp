/*
 * frames_detect.cpp - the two star detectors of frames_detect.h with
 * OpenCV core/imgproc (connected components).
 */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "frames/frames_detect.h"

extern "C" void frames_detect_tiles(int cols, int rows, int tile_px,
				    int *tiles_x, int *tiles_y)
{
	*tiles_x = (cols + tile_px - 1) / tile_px;
	*tiles_y = (rows + tile_px - 1) / tile_px;
}

/* Clipped mean of one tile: median and the 15.9 % quantile (1 sigma
 * below) from every other pixel, then the mean within 5 sigma. */
static float tile_mean(const cv::Mat &e, cv::Rect r, std::vector<float> &buf)
{
	size_t n, k16;
	float med, sig, lo, hi;
	double sum = 0.0;
	long cnt = 0;

	buf.clear();
	for (int y = r.y; y < r.y + r.height; y += 2) {
		const float *p = e.ptr<float>(y);
		for (int x = r.x; x < r.x + r.width; x += 2)
			buf.push_back(p[x]);
	}
	n = buf.size();
	std::nth_element(buf.begin(), buf.begin() + n / 2, buf.end());
	med = buf[n / 2];
	k16 = (size_t)(0.1587 * n);
	std::nth_element(buf.begin(), buf.begin() + k16, buf.begin() + n / 2);
	sig = std::max(med - buf[k16], 1.0f);
	lo = med - 5.0f * sig;
	hi = med + 5.0f * sig;
	for (int y = r.y; y < r.y + r.height; y++) {
		const float *p = e.ptr<float>(y);
		for (int x = r.x; x < r.x + r.width; x++)
			if (p[x] > lo && p[x] < hi) {
				sum += p[x];
				cnt++;
			}
	}
	return cnt ? (float)(sum / cnt) : med;
}

/* Interpolation weights along one axis: tile i centred on its own pixels
 * (the last tile may be short), linear between centres and linearly
 * extrapolated past the outer ones (a ramp stays a ramp to the edge). */
static void axis_weights(int n, int tile, int nt, std::vector<int> &i0,
			 std::vector<float> &w)
{
	std::vector<float> c(nt);

	for (int i = 0; i < nt; i++)
		c[i] = i * tile + 0.5f * std::min(tile, n - i * tile);
	i0.resize(n);
	w.resize(n);
	for (int x = 0, k = 0; x < n; x++) {
		float p = x + 0.5f;
		while (k < nt - 2 && p > c[k + 1])
			k++;
		i0[x] = nt > 1 ? k : 0;
		w[x] = nt > 1 ? (p - c[k]) / (c[k + 1] - c[k]) : 0.0f;
	}
}

/* Background per tile, then bilinear between tile centres. */
static void background(const cv::Mat &e, int tile, cv::Mat &bg,
		       float *tiles_out)
{
	int tx, ty, cols = e.cols, rows = e.rows;
	std::vector<float> buf, wx, wy;
	std::vector<int> x0, y0;

	frames_detect_tiles(cols, rows, tile, &tx, &ty);
	cv::Mat t(ty, tx, CV_32F);
	for (int j = 0; j < ty; j++)
		for (int i = 0; i < tx; i++) {
			cv::Rect r(i * tile, j * tile, std::min(tile, cols - i * tile),
				   std::min(tile, rows - j * tile));
			t.at<float>(j, i) = tile_mean(e, r, buf);
			if (tiles_out)
				tiles_out[j * tx + i] = t.at<float>(j, i);
		}
	axis_weights(cols, tile, tx, x0, wx);
	axis_weights(rows, tile, ty, y0, wy);
	bg.create(rows, cols, CV_32F);
	for (int y = 0; y < rows; y++) {
		int j0 = y0[y], j1 = std::min(j0 + 1, ty - 1);
		const float *a = t.ptr<float>(j0), *b = t.ptr<float>(j1);
		float *o = bg.ptr<float>(y);
		for (int x = 0; x < cols; x++) {
			int i0 = x0[x], i1 = std::min(i0 + 1, tx - 1);
			float top = a[i0] + wx[x] * (a[i1] - a[i0]);
			float bot = b[i0] + wx[x] * (b[i1] - b[i0]);
			o[x] = top + wy[y] * (bot - top);
		}
	}
}

/* Components of a mask into detections of min_px and up, at the
 * centroid of the region weighted by w (the background-subtracted
 * signal, or the window sums). */
static void components(const cv::Mat &mask, const cv::Mat &w, int min_px,
		       double off_x, double off_y,
		       struct frames_detect_out *out)
{
	cv::Mat labels, stats, cent;
	int n = cv::connectedComponentsWithStats(mask, labels, stats, cent, 8,
						 CV_32S);
	std::vector<double> sw(n, 0.0), sx(n, 0.0), sy(n, 0.0);

	for (int y = 0; y < labels.rows; y++) {
		const int *l = labels.ptr<int>(y);
		const float *v = w.ptr<float>(y);
		for (int x = 0; x < labels.cols; x++)
			if (l[x] > 0) {
				double q = std::max(v[x], 0.0f);
				sw[l[x]] += q;
				sx[l[x]] += q * x;
				sy[l[x]] += q * y;
			}
	}
	out->n = 0;
	for (int k = 1; k < n; k++) {
		int area = stats.at<int>(k, cv::CC_STAT_AREA);
		if (area < min_px)
			continue;
		if (out->n < out->max) {
			struct frames_detection *d = &out->det[out->n];
			bool ok = sw[k] > 0.0;
			d->x = (ok ? sx[k] / sw[k] : cent.at<double>(k, 0)) + off_x;
			d->y = (ok ? sy[k] / sw[k] : cent.at<double>(k, 1)) + off_y;
			d->n_px = area;
			d->x0 = stats.at<int>(k, cv::CC_STAT_LEFT) + off_x;
			d->y0 = stats.at<int>(k, cv::CC_STAT_TOP) + off_y;
			d->x1 = d->x0 + stats.at<int>(k, cv::CC_STAT_WIDTH) - 1;
			d->y1 = d->y0 + stats.at<int>(k, cv::CC_STAT_HEIGHT) - 1;
		}
		out->n++;
	}
}

/* eq. 2.7-2.11: the background-subtracted sum of the disk window of
 * radius r at every pixel whose window fits, by row prefix sums. */
static void window_sums(const cv::Mat &res, double radius, cv::Mat &mask,
			cv::Mat &sums, double i_sdt)
{
	int R = (int)radius, cols = res.cols, rows = res.rows;
	std::vector<int> w(2 * R + 1);
	cv::Mat pre(rows, cols + 1, CV_32F);

	for (int d = -R; d <= R; d++)
		w[d + R] = (int)std::floor(std::sqrt(radius * radius - d * d) + 1e-9);
	for (int y = 0; y < rows; y++) {
		const float *p = res.ptr<float>(y);
		float *q = pre.ptr<float>(y), acc = 0.0f;
		q[0] = 0.0f;
		for (int x = 0; x < cols; x++)
			q[x + 1] = (acc += p[x]);
	}
	mask = cv::Mat::zeros(std::max(rows - 2 * R, 1), std::max(cols - 2 * R, 1),
			      CV_8U);
	sums = cv::Mat::zeros(mask.size(), CV_32F);
	for (int y = R; y < rows - R; y++) {
		unsigned char *m = mask.ptr<unsigned char>(y - R);
		float *o = sums.ptr<float>(y - R);
		for (int x = R; x < cols - R; x++) {
			float s = 0.0f;
			for (int d = -R; d <= R; d++) {
				const float *q = pre.ptr<float>(y + d);
				s += q[x + w[d + R] + 1] - q[x - w[d + R]];
			}
			o[x - R] = s - (float)i_sdt;
			m[x - R] = s > i_sdt ? 255 : 0;	/* eq. 2.16 */
		}
	}
}

static void set_msg(char *msg, size_t size, const char *text)
{
	if (msg && size)
		std::snprintf(msg, size, "%s", text);
}

extern "C" int frames_detect(const uint16_t *dn, int cols, int rows,
			     const struct frames_detect_cfg *c, int which,
			     struct frames_detect_out out[2], float *bg_tiles,
			     char *msg, size_t msg_size)
{
	try {
		cv::Mat raw(rows, cols, CV_16U, const_cast<uint16_t *>(dn));
		cv::Mat e, bg, res, mask, sums;

		/* DN to photo-electrons with the camera's bias and gain */
		raw.convertTo(e, CV_32F, c->gain_e_per_dn,
			      -c->bias_dn * c->gain_e_per_dn);
		background(e, c->tile_px, bg, bg_tiles);
		res = e - bg;	/* eq. 2.11: re-centred on the background */
		if (which & FRAMES_DET_THESIS) {
			int R = (int)c->window_radius_px;
			window_sums(res, c->window_radius_px, mask, sums,
				    c->i_sdt_e);
			components(mask, sums, 1, R + 0.5, R + 0.5, &out[0]);
		}
		if (which & FRAMES_DET_THRESHOLD) {
			cv::compare(res, c->pixel_threshold_e, mask, cv::CMP_GT);
			components(mask, res, c->min_px, 0.5, 0.5, &out[1]);
		}
	} catch (const cv::Exception &ex) {
		set_msg(msg, msg_size, ex.what());
		return -1;
	}
	return 0;
}
