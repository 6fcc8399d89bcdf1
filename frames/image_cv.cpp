/*
 * image_cv.cpp - the C wrapper of image_cv.h: OpenCV's imgproc colour map
 * and imgcodecs PNG writer (fig. 3.8, false-colour J).
 */
#include <cmath>
#include <cstdio>
#include <vector>
#include <cerrno>
#include <cstring>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "frames/image_cv.h"
extern "C" {
#include "stray/file.h"
}

static void set_msg(char *msg, size_t size, const char *text)
{
	if (msg && size)
		std::snprintf(msg, size, "%s", text);
}

/* Scale finite values (log10 when asked) to 1..255; 0 marks no data. */
static cv::Mat to_8bit(const cv::Mat &src, int log_scale)
{
	cv::Mat v(src.size(), CV_32F), out(src.size(), CV_8U, cv::Scalar(0));
	double lo = HUGE_VAL, hi = -HUGE_VAL;

	for (int r = 0; r < src.rows; r++)
		for (int c = 0; c < src.cols; c++) {
			float x = src.at<float>(r, c);
			bool ok = std::isfinite(x) && (!log_scale || x > 0.0f);
			float y = ok ? (log_scale ? std::log10(x) : x) : NAN;

			v.at<float>(r, c) = y;
			if (ok) {
				lo = std::min(lo, (double)y);
				hi = std::max(hi, (double)y);
			}
		}
	if (!(hi > lo))
		hi = lo + 1.0;
	for (int r = 0; r < v.rows; r++)
		for (int c = 0; c < v.cols; c++) {
			float y = v.at<float>(r, c);

			if (std::isfinite(y))
				out.at<unsigned char>(r, c) = (unsigned char)
					(1.0 + 254.0 * (y - lo) / (hi - lo));
		}
	return out;
}

/* Encoded in memory, then written through the one atomic path
 * (stray/file.h): never half a PNG, none left by a failed run. */
static int write_png(const char *path, const cv::Mat &img, char *msg,
		     size_t msg_size)
{
	std::vector<unsigned char> png;
	struct stray_file_out out;
	struct stray_error err;

	if (!cv::imencode(".png", img, png)) {
		set_msg(msg, msg_size, "cannot encode the PNG image");
		return -1;
	}
	stray_error_clear(&err);
	if (stray_file_open_atomic(&out, path, &err) != STRAY_OK) {
		set_msg(msg, msg_size, err.reason ? err.reason
				       : "cannot write the PNG file");
		return -1;
	}
	if (fwrite(png.data(), 1, png.size(), out.f) != png.size()) {
		int saved = errno;

		stray_file_abort(&out);
		set_msg(msg, msg_size, saved ? strerror(saved)
				       : "cannot write the PNG file");
		return -1;
	}
	if (stray_file_commit(&out, &err) != STRAY_OK) {
		/* the errno text ("No space left on device"), not a guess */
		set_msg(msg, msg_size, err.reason ? err.reason
				       : "cannot write the PNG file");
		return -1;
	}
	return 0;
}

extern "C" int image_cv_false_colour(const char *path, const float *img,
				     size_t rows, size_t cols, int log_scale,
				     size_t min_width, char *msg,
				     size_t msg_size)
{
	try {
		cv::Mat src((int)rows, (int)cols, CV_32F,
			    const_cast<float *>(img));
		cv::Mat grey = to_8bit(src, log_scale), colour, big;
		int k = cols ? (int)((min_width + cols - 1) / cols) : 1;

		cv::applyColorMap(grey, colour, cv::COLORMAP_INFERNO);
		if (k > 1)
			cv::resize(colour, big, cv::Size(), k, k,
				   cv::INTER_NEAREST);
		else
			big = colour;
		if (write_png(path, big, msg, msg_size) != 0)
			return -1;
	} catch (const cv::Exception &e) {
		set_msg(msg, msg_size, e.what());
		return -1;
	}
	return 0;
}
