/*
 * indi_fits.c - the camera's BLOB (a FITS file in memory, INDI's
 * CCD_TRANSFER_FORMAT FITS) into a rig_image: the rows of camera.rows
 * out of the window asked for (indi_lab.c sets CCD_FRAME to cover them),
 * and the EXPTIME the camera wrote, the exposure's read-back.  A frame
 * of another size than asked is RIG_EPROTO: not the frame we asked for.
 */
#include <fitsio.h>
#include <stdlib.h>
#include <string.h>

#include "indi_props.h"

int rig_indi_fits_image(const unsigned char *data, size_t len,
			const struct rig_camera_cfg *cam, const char *dev,
			struct rig_image *img, double *exptime_s,
			struct rig_error *err)
{
	long want_h = cam->rows[cam->n_rows - 1] - cam->rows[0] + 1;
	long naxes[2] = { 0, 0 };
	void *mem = malloc(len);
	size_t size = len;
	fitsfile *f = NULL;
	int status = 0, naxis = 0, i, bitpix = 0;
	char msg[FLEN_STATUS] = "";

	if (!mem)
		return rig_error_set(err, RIG_ENOMEM, "camera: no memory");
	memcpy(mem, data, len);
	*exptime_s = -1;
	fits_open_memfile(&f, "blob.fits", READONLY, &mem, &size, 0, NULL,
			  &status);
	if (!status)
		fits_get_img_param(f, 2, &bitpix, &naxis, naxes, &status);
	if (!status && (naxis != 2 || naxes[0] != cam->n_cols ||
			naxes[1] != want_h)) {
		fits_close_file(f, &status);
		free(mem);
		return rig_error_set(err, RIG_EPROTO,
			"camera: '%s' sent a %ldx%ld frame, asked %dx%ld "
			"(camera.n_cols x camera.rows' span)", dev, naxes[0],
			naxis == 2 ? naxes[1] : 0, cam->n_cols, want_h);
	}
	if (!status) {
		int st = 0;

		fits_read_key(f, TDOUBLE, "EXPTIME", exptime_s, NULL, &st);
		if (st)
			*exptime_s = -1;	/* no read-back */
	}
	for (i = 0; !status && i < cam->n_rows; i++) {
		long first[2] = { 1, (long)(cam->rows[i] - cam->rows[0]) + 1 };

		fits_read_pix(f, TUSHORT, first, cam->n_cols, NULL,
			      img->px + (size_t)i * cam->n_cols, NULL,
			      &status);
		img->rows[i] = cam->rows[i];
	}
	if (f) {
		int st = 0;

		fits_close_file(f, &st);
	}
	free(mem);
	if (status) {
		fits_get_errstatus(status, msg);
		return rig_error_set(err, RIG_EPROTO,
				     "camera: '%s': BLOB is not a readable "
				     "FITS image: %s", dev, msg);
	}
	img->n_rows = cam->n_rows;
	img->n_cols = cam->n_cols;
	img->col0 = cam->col0;
	img->bits = bitpix == 8 ? 8 : 16;
	return RIG_OK;
}
