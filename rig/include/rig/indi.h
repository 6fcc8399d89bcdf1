/*
 * indi.h - the INDI backend (issue 26): the lab's camera, filter wheel,
 * stage and lamp driven through an indiserver with libindi's client
 * library, for labs whose hardware has INDI drivers and not ours.
 *
 * INDI speaks in properties, not bytes, so this backend sits at the
 * device level of the lab (rig_lab_ops, lab.h), not under the byte HAL:
 *   rig/indi/indi_client.cpp  INDI::BaseClient and a copy of the
 *                             properties it is told of, behind the C
 *                             calls below (the only C++ of the rig)
 *   rig/indi/indi_lab.c       stage, wheel, switches and camera
 *   rig/indi/indi_fits.c      the camera's FITS BLOB into a rig_image
 *   rig/indi/indi_config.c    the config's "indi" section
 * See docs/rig-indi.md and docs/rig-config.md.
 */
#ifndef RIG_INDI_H
#define RIG_INDI_H

#include <stddef.h>

#include "rig/hal.h"
#include "rig/status.h"

#define RIG_INDI_NAME_MAX 48	/* INDI names (MAXINDINAME is 64) */

/* A switch that is the lamp or the beam block: the element set for on
 * and the one set for off (a one-of-many switch, as a flat panel's). */
struct rig_indi_switch_cfg {
	char device[RIG_INDI_NAME_MAX];
	char property[RIG_INDI_NAME_MAX];
	char on[RIG_INDI_NAME_MAX];
	char off[RIG_INDI_NAME_MAX];
};

struct rig_indi_cfg {
	char host[RIG_INDI_NAME_MAX];
	int port;
	double connect_timeout_s;	/* server and device connection */
	double timeout_s;		/* a property's answer, beyond a move */
	struct {
		char device[RIG_INDI_NAME_MAX];
		char exposure[RIG_INDI_NAME_MAX];	/* CCD_EXPOSURE */
		char exposure_element[RIG_INDI_NAME_MAX];
		char blob[RIG_INDI_NAME_MAX];		/* CCD1 */
		char frame[RIG_INDI_NAME_MAX];		/* CCD_FRAME */
		char frame_type[RIG_INDI_NAME_MAX];	/* CCD_FRAME_TYPE */
		char light[RIG_INDI_NAME_MAX];		/* shutter open */
		char dark[RIG_INDI_NAME_MAX];		/* shutter closed */
	} camera;
	struct {
		char device[RIG_INDI_NAME_MAX];
		char property[RIG_INDI_NAME_MAX];	/* FILTER_SLOT */
		char element[RIG_INDI_NAME_MAX];
		int first_slot;		/* INDI's number of our slot 0 */
	} wheel;
	struct {
		char device[RIG_INDI_NAME_MAX];
		char property[RIG_INDI_NAME_MAX];	/* ABS_ROTATOR_ANGLE */
		char element[RIG_INDI_NAME_MAX];
		char abort[RIG_INDI_NAME_MAX];	/* ROTATOR_ABORT_MOTION */
		char abort_element[RIG_INDI_NAME_MAX];
		int wrap360;		/* 1: the device takes 0..360 deg */
	} stage;
	struct rig_indi_switch_cfg lamp, beam_block;
};

void rig_indi_cfg_defaults(struct rig_indi_cfg *c);
/* The "indi" object over the defaults (NULL: none given); every name
 * must be non-empty.  RIG_EPARSE naming the file and key. */
struct cJSON;
int rig_indi_config_parse(struct rig_indi_cfg *c, const struct cJSON *o,
			  const char *name, struct rig_error *err);

/* The HAL of an INDI lab: only its clock (monotonic, and the system's
 * UTC); nothing below the seam is ours. */
void rig_hal_indi_init(struct rig_hal *hal);

/* ---- the client (indi_client.cpp) ---- */

/* Property states, as INDI's IPState. */
enum { RIG_INDI_IDLE, RIG_INDI_OK, RIG_INDI_BUSY, RIG_INDI_ALERT };

struct rig_indi;

/* What the client last heard of a property. */
struct rig_indi_prop {
	int defined;		/* 0: never defined, or deleted since */
	int state;		/* RIG_INDI_* */
	unsigned long gen;	/* bumped at each definition or update */
};

struct rig_indi *rig_indi_new(const char *host, int port);
void rig_indi_free(struct rig_indi *c);
/* Connected to the server, connecting (again) if not: RIG_OK, or
 * RIG_EDISCONNECT when the server cannot be reached in timeout_s. */
int rig_indi_server(struct rig_indi *c, double timeout_s);
int rig_indi_alive(struct rig_indi *c);
/* End the connection (the next rig_indi_server makes a new one), and
 * how long the present one has been up, s (0: none). */
void rig_indi_drop(struct rig_indi *c);
double rig_indi_age(struct rig_indi *c);
/* Ask for dev's BLOBs (B_ALSO) on this connection. */
void rig_indi_want_blobs(struct rig_indi *c, const char *dev);

/* A property's state; RIG_EDISCONNECT without a server. */
int rig_indi_prop(struct rig_indi *c, const char *dev, const char *prop,
		  struct rig_indi_prop *p);
/* An element's value (and range) or switch; RIG_ESTATE when the
 * property is not defined, RIG_EINVAL when it has no such element. */
int rig_indi_number(struct rig_indi *c, const char *dev, const char *prop,
		    const char *elem, double *v, double *min, double *max,
		    struct rig_indi_prop *p);
int rig_indi_switch(struct rig_indi *c, const char *dev, const char *prop,
		    const char *elem, int *on, struct rig_indi_prop *p);
/* The BLOB last received for (dev, prop) when its gen is above
 * after_gen: a malloc'd copy (RIG_EAGAIN: none newer yet). */
int rig_indi_blob(struct rig_indi *c, const char *dev, const char *prop,
		  unsigned long after_gen, unsigned char **data, size_t *len,
		  unsigned long *gen);
/* Send n elements of a number vector in one message, or turn one switch
 * element on; RIG_ESTATE/RIG_EINVAL as above, nothing sent then. */
int rig_indi_send_numbers(struct rig_indi *c, const char *dev,
			  const char *prop, int n, const char *const *elems,
			  const double *values);
int rig_indi_send_switch(struct rig_indi *c, const char *dev,
			 const char *prop, const char *elem);
/* Wait until something of dev changes after gen (*gen updated: the
 * client's change counter), the server goes (RIG_EDISCONNECT) or
 * timeout_s passes (RIG_ETIMEOUT). */
int rig_indi_wait(struct rig_indi *c, unsigned long *gen, double timeout_s);
/* The device's last message (its driver's words, as "2026-...: text"),
 * "" when none came. */
void rig_indi_message(struct rig_indi *c, const char *dev, char *buf,
		      size_t size);
/* The client's change counter now. */
unsigned long rig_indi_gen(struct rig_indi *c);

#endif /* RIG_INDI_H */
