/*
 * indi_props.c - the INDI lab's conversation with its devices (indi_props.h):
 * the server reached, a device connected, a property defined, a number
 * vector or a switch set and the device's answer waited for.  Each names
 * the device and property in its one-line error; a device gone (deleted
 * properties, CONNECT off, the server lost) is RIG_EDISCONNECT, which
 * lab.c's retries reconnect.
 */
#include <math.h>
#include <string.h>

#include "indi_props.h"
#include "rig/lab.h"

int ilab_server(struct rig_lab *lab, const char *dev, struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);

	if (!lab->indi) {
		lab->indi = rig_indi_new(c->host, c->port);
		if (!lab->indi)
			return rig_error_set(err, RIG_ENOMEM, "indi: no memory");
		rig_indi_want_blobs(lab->indi, c->camera.device);
	}
	if (rig_indi_server(lab->indi, c->connect_timeout_s) != RIG_OK)
		return rig_error_set(err, RIG_EDISCONNECT,
			"indi: '%s': server %s:%d does not answer (is "
			"indiserver running?)", dev, c->host, c->port);
	return RIG_OK;
}

/* Wait on the client for up to *left s; RIG_OK when something changed. */
int ilab_wait(struct rig_lab *lab, unsigned long *gen, double t_end,
		       const char *dev, const char *prop, struct rig_error *err)
{
	double left = t_end - rig_hal_now(lab->hal);
	int rc = left > 0 ? rig_indi_wait(lab->indi, gen, left) : RIG_ETIMEOUT;

	if (rc == RIG_EDISCONNECT)
		return rig_error_set(err, rc, "indi: '%s' %s: server %s:%d "
				     "lost", dev, prop, ICFG(lab)->host,
				     ICFG(lab)->port);
	return rc;
}

/* The device on the server and connected (CONNECTION.CONNECT on). */
int ilab_device(struct rig_lab *lab, const char *dev, struct rig_error *err)
{
	double t_end = rig_hal_now(lab->hal) + ICFG(lab)->connect_timeout_s;
	struct rig_indi_prop p;
	unsigned long gen;
	int rc = ilab_server(lab, dev, err), on = 0, sent = 0;

	/* A driver indiserver restarted (-r, or its FIFO's start) defines
	 * its properties only when asked: a device long connected to and now
	 * unknown is asked for again by a fresh connection (getProperties). */
	if (rc == RIG_OK && rig_indi_age(lab->indi) > 1.0 &&
	    rig_indi_prop(lab->indi, dev, "CONNECTION", &p) == RIG_OK &&
	    !p.defined) {
		rig_indi_drop(lab->indi);
		rc = ilab_server(lab, dev, err);
	}
	while (rc == RIG_OK) {
		gen = rig_indi_gen(lab->indi);
		rc = rig_indi_switch(lab->indi, dev, "CONNECTION", "CONNECT",
				     &on, &p);
		if (rc == RIG_OK && on && p.state != RIG_INDI_BUSY &&
		    p.state != RIG_INDI_ALERT)
			return RIG_OK;
		if (rc == RIG_OK && sent && p.state == RIG_INDI_ALERT)
			return rig_error_set(err, RIG_EDISCONNECT,
				"indi: '%s' CONNECTION: the driver could not "
				"connect to its device (Alert)", dev);
		if (rc == RIG_OK && !sent) {
			rig_indi_send_switch(lab->indi, dev, "CONNECTION",
					     "CONNECT");
			sent = 1;
			/* A driver connecting resets its chip's window. */
			if (strcmp(dev, ICFG(lab)->camera.device) == 0)
				lab->indi_cam_fresh = 1;
		}
		if (rc != RIG_OK && rc != RIG_ESTATE && rc != RIG_EINVAL)
			break;
		rc = ilab_wait(lab, &gen, t_end, dev, "CONNECTION", err);
	}
	if (rc == RIG_ETIMEOUT)
		return rig_error_set(err, RIG_EDISCONNECT,
			"indi: '%s': %s within %.1f s on %s:%d; check the "
			"driver runs and the device name in the config", dev,
			sent ? "not connected" : "no such device",
			ICFG(lab)->connect_timeout_s, ICFG(lab)->host,
			ICFG(lab)->port);
	return rig_error_set(err, rc, "indi: '%s': %s", dev,
			     rig_status_text(rc));
}

/* The device connected and its property defined; key names the config
 * key that named the property, for the message when it never comes. */
int ilab_property(struct rig_lab *lab, const char *dev, const char *prop,
		    const char *key, struct rig_error *err)
{
	double t_end = rig_hal_now(lab->hal) + ICFG(lab)->connect_timeout_s;
	struct rig_indi_prop p;
	unsigned long gen;
	int rc = ilab_device(lab, dev, err);

	while (rc == RIG_OK) {
		gen = rig_indi_gen(lab->indi);
		rc = rig_indi_prop(lab->indi, dev, prop, &p);
		if (rc == RIG_OK && p.defined)
			return RIG_OK;
		if (rc == RIG_OK)
			rc = ilab_wait(lab, &gen, t_end, dev, prop, err);
	}
	if (rc == RIG_ETIMEOUT)
		return rig_error_set(err, RIG_EINVAL,
			"indi: '%s' has no property %s; check %s", dev, prop,
			key);
	return rc;
}

/* Send a number vector and wait for the device's answer (the property
 * updated, not Busy); *rb = the first element read back.  Alert is
 * RIG_EDEVICE; the property deleted (driver disconnected) EDISCONNECT. */
int ilab_numbers(struct rig_lab *lab, const char *dev, const char *prop,
		   int n, const char *const *el, const double *v,
		   double timeout_s, double *rb, struct rig_error *err)
{
	double t_end = rig_hal_now(lab->hal) + timeout_s;
	struct rig_indi_prop p0, p;
	unsigned long gen = rig_indi_gen(lab->indi);
	int rc = rig_indi_prop(lab->indi, dev, prop, &p0);

	if (rc == RIG_OK)
		rc = rig_indi_send_numbers(lab->indi, dev, prop, n, el, v);
	while (rc == RIG_OK) {
		rc = rig_indi_number(lab->indi, dev, prop, el[0], rb, NULL,
				     NULL, &p);
		if (rc == RIG_ESTATE)
			return rig_error_set(err, RIG_EDISCONNECT,
				"indi: '%s' %s: gone while setting %g "
				"(driver disconnected or restarted)", dev,
				prop, v[0]);
		if (rc == RIG_OK && p.gen > p0.gen &&
		    p.state == RIG_INDI_ALERT) {
			char said[160];

			rig_indi_message(lab->indi, dev, said, sizeof(said));
			return rig_error_set(err, RIG_EDEVICE,
				"indi: '%s' %s: the device refused or failed "
				"%s = %g (Alert)%s%s", dev, prop, el[0], v[0],
				said[0] ? "; it said: " : "", said);
		}
		if (rc == RIG_OK && p.gen > p0.gen &&
		    p.state != RIG_INDI_BUSY)
			return RIG_OK;
		if (rc == RIG_OK)
			rc = ilab_wait(lab, &gen, t_end, dev, prop, err);
	}
	if (rc == RIG_ETIMEOUT)
		return rig_error_set(err, rc, "indi: '%s' %s: %s = %g not "
				     "done within %.1f s", dev, prop, el[0],
				     v[0], timeout_s);
	return rig_error_set(err, rc, "indi: '%s' %s: %s", dev, prop,
			     rig_status_text(rc));
}

/* Turn a switch element on and read it back on. */
int ilab_switch_on(struct rig_lab *lab, const char *dev, const char *prop,
		     const char *elem, const char *key, struct rig_error *err)
{
	double t_end = rig_hal_now(lab->hal) + ICFG(lab)->timeout_s;
	struct rig_indi_prop p0, p;
	unsigned long gen;
	int rc = ilab_property(lab, dev, prop, key, err), on = 0, sent = 0;

	while (rc == RIG_OK) {
		gen = rig_indi_gen(lab->indi);
		rc = rig_indi_switch(lab->indi, dev, prop, elem, &on, &p);
		if (rc == RIG_EINVAL)
			return rig_error_set(err, RIG_EINVAL, "indi: '%s' %s "
				"has no element %s; check %s", dev, prop,
				elem, key);
		if (rc == RIG_ESTATE)
			return rig_error_set(err, RIG_EDISCONNECT,
				"indi: '%s' %s: gone while setting %s",
				dev, prop, elem);
		if (rc != RIG_OK)
			break;
		if (on && p.state != RIG_INDI_BUSY &&
		    p.state != RIG_INDI_ALERT)
			return RIG_OK;
		if (sent && p.gen > p0.gen && p.state == RIG_INDI_ALERT)
			return rig_error_set(err, RIG_EDEVICE,
				"indi: '%s' %s: %s refused (Alert)", dev,
				prop, elem);
		if (!sent) {
			p0 = p;
			rc = rig_indi_send_switch(lab->indi, dev, prop, elem);
			sent = 1;
			continue;
		}
		rc = ilab_wait(lab, &gen, t_end, dev, prop, err);
	}
	if (rc == RIG_ETIMEOUT)
		return rig_error_set(err, rc, "indi: '%s' %s: %s not on "
				     "within %.1f s", dev, prop, elem,
				     ICFG(lab)->timeout_s);
	return rig_error_set(err, rc, "indi: '%s' %s: %s", dev, prop,
			     rig_status_text(rc));
}
