/*
 * indi_props.h - private to rig/indi: the device conversation (indi_props.c)
 * and the FITS BLOB reader (indi_fits.c).
 */
#ifndef RIG_INDI_PROPS_H
#define RIG_INDI_PROPS_H

#include "rig/devices.h"

struct rig_lab;

#define ICFG(lab) (&(lab)->cfg->indi)

/* indi_props.c: the server connected (a client made when none); the
 * device on it and connected; its property defined (key: the config key
 * that named it, for the message when it never comes). */
int ilab_server(struct rig_lab *lab, const char *dev, struct rig_error *err);
int ilab_device(struct rig_lab *lab, const char *dev, struct rig_error *err);
int ilab_property(struct rig_lab *lab, const char *dev, const char *prop,
		  const char *key, struct rig_error *err);
/* Wait on the client until t_end (HAL clock) for any change. */
int ilab_wait(struct rig_lab *lab, unsigned long *gen, double t_end,
	      const char *dev, const char *prop, struct rig_error *err);
/* Send n elements of a number vector and wait for the device's answer
 * (updated, not Busy); *rb = the first element read back.  Alert is
 * RIG_EDEVICE with the device's last message. */
int ilab_numbers(struct rig_lab *lab, const char *dev, const char *prop,
		 int n, const char *const *el, const double *v,
		 double timeout_s, double *rb, struct rig_error *err);
/* Turn a switch element on and read it back on. */
int ilab_switch_on(struct rig_lab *lab, const char *dev, const char *prop,
		   const char *elem, const char *key, struct rig_error *err);

/* The rows of cam out of a FITS file in memory of the window CCD_FRAME
 * was set to (camera.n_cols x the span of camera.rows); *exptime_s = the
 * file's EXPTIME, -1 without one.  RIG_EPROTO names dev. */
int rig_indi_fits_image(const unsigned char *data, size_t len,
			const struct rig_camera_cfg *cam, const char *dev,
			struct rig_image *img, double *exptime_s,
			struct rig_error *err);

#endif /* RIG_INDI_PROPS_H */
