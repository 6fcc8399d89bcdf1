/*
 * devlock.h - a lab-wide lock per device: a flock on
 * lock_dir/straylight-<bus id>.lock for every device the config names,
 * taken before any device is opened and held for the daemon's life, so
 * two daemons (socket or --sweep, any socket, any folder) never drive
 * the same hardware.  lock_dir "" (the simulator's default) takes none.
 */
#ifndef RIG_DEVLOCK_H
#define RIG_DEVLOCK_H

#include "rig/config.h"

#define RIG_DEVLOCK_MAX 8

struct rig_devlock {
	int fd[RIG_DEVLOCK_MAX];
	int n;
};

/* Take every device's lock or none: RIG_ESTATE naming the device and
 * the holder when another daemon has one, RIG_EIO with the errno text
 * when the lock file cannot be made.  owner is written into each. */
int rig_devlock_take(struct rig_devlock *l, const struct rig_config *cfg,
		     const char *owner, struct rig_error *err);
void rig_devlock_release(struct rig_devlock *l);

#endif /* RIG_DEVLOCK_H */
