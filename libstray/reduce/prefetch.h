/*
 * prefetch.h - the frame files of a reduction read and hashed one ahead
 * by a second thread, in the order the passes will ask for them (private
 * to libstray/reduce).  The reading thread touches no cfitsio: it only
 * fills a buffer and checks its SHA-256; the caller decodes.
 */
#ifndef STRAY_REDUCE_PREFETCH_H
#define STRAY_REDUCE_PREFETCH_H

#include <pthread.h>
#include <stddef.h>

#include "stray/error.h"
#include "stray/sweep_store.h"

#define STRAY_PREFETCH_SLOTS 2
#define STRAY_PREFETCH_NOT_NEXT (-1)

struct stray_prefetch_slot {
	struct stray_sweep_buf buf;
	size_t k;		/* sequence index held */
	int state;		/* 0 free, 1 ready */
	int rc;
	struct stray_error err;
};

struct stray_prefetch {
	const char *dir;
	const struct stray_sweep_entry **seq;	/* owned */
	size_t n, next;		/* next: what the caller takes next */
	int verify, stop, running;
	pthread_t thread;
	pthread_mutex_t mu;
	pthread_cond_t cv;
	struct stray_prefetch_slot slot[STRAY_PREFETCH_SLOTS];
};

/* Start reading seq[0..n) (the array is taken over, freed by stop
 * whatever happens).  Not running (the caller reads itself) when the
 * thread cannot be started. */
void stray_prefetch_start(struct stray_prefetch *p, const char *dir,
			  const struct stray_sweep_entry **seq, size_t n,
			  int verify);

/*
 * The bytes of e when e is the next in the sequence: STRAY_OK with *buf
 * set (checked against its SHA-256 when verify), the reader's error, or
 * STRAY_PREFETCH_NOT_NEXT with nothing said when e is not next (read it
 * yourself).  Release the buffer before asking again.
 */
int stray_prefetch_take(struct stray_prefetch *p,
			const struct stray_sweep_entry *e,
			struct stray_sweep_buf **buf, struct stray_error *err);
void stray_prefetch_release(struct stray_prefetch *p);

/* Stop the thread (wherever it is) and free everything. */
void stray_prefetch_stop(struct stray_prefetch *p);

#endif /* STRAY_REDUCE_PREFETCH_H */
