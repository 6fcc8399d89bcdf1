/*
 * image_cv.h - false-colour images through OpenCV (whose C API is gone in
 * OpenCV 4: image_cv.cpp wraps the C++ one behind this C interface).
 */
#ifndef STRAY_FRAMES_IMAGE_CV_H
#define STRAY_FRAMES_IMAGE_CV_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Write rows x cols floats (row-major) as a false-colour PNG (inferno
 * map), on a log10 scale when log_scale (non-positive pixels black),
 * enlarged by whole pixels to at least min_width columns.  Returns 0, or
 * -1 with a reason in msg.
 */
int image_cv_false_colour(const char *path, const float *img, size_t rows,
			  size_t cols, int log_scale, size_t min_width,
			  char *msg, size_t msg_size);

#ifdef __cplusplus
}
#endif

#endif /* STRAY_FRAMES_IMAGE_CV_H */
