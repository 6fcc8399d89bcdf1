/*
 * prefetch.c - frame files read and hashed one ahead (prefetch.h): while
 * the caller decodes and accumulates frame k, the thread reads frame
 * k + 1 and computes its SHA-256, so the hash (the largest single cost
 * of a frame after the arithmetic) overlaps the arithmetic.  Errors are
 * handed over in sequence order: the caller meets them where it would
 * have met them reading alone.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "prefetch.h"

static void fill(struct stray_prefetch *p, struct stray_prefetch_slot *s,
		 size_t k)
{
	char path[4096 + STRAY_SWEEP_FILE_MAX];	/* as sweep.c names it */
	const struct stray_sweep_entry *e = p->seq[k];

	stray_error_clear(&s->err);
	snprintf(path, sizeof(path), "%s/%s", p->dir, e->file);
	s->rc = stray_sweep_file_load(path, &s->buf, &s->err);
	if (s->rc == STRAY_OK && p->verify)
		s->rc = stray_sweep_sha256_check_mem(path, s->buf.data,
						     s->buf.len, e->sha256,
						     &s->err);
}

static void *reader(void *arg)
{
	struct stray_prefetch *p = arg;
	size_t k;

	for (k = 0; k < p->n; k++) {
		struct stray_prefetch_slot *s = &p->slot[k %
						STRAY_PREFETCH_SLOTS];
		int failed;

		pthread_mutex_lock(&p->mu);
		while (s->state != 0 && !p->stop)
			pthread_cond_wait(&p->cv, &p->mu);
		if (p->stop) {
			pthread_mutex_unlock(&p->mu);
			break;
		}
		pthread_mutex_unlock(&p->mu);
		fill(p, s, k);	/* the slot is ours while free */
		failed = s->rc != STRAY_OK;
		pthread_mutex_lock(&p->mu);
		s->k = k;
		s->state = 1;
		pthread_cond_broadcast(&p->cv);
		pthread_mutex_unlock(&p->mu);
		if (failed)
			break;	/* the caller stops there */
	}
	return NULL;
}

void stray_prefetch_start(struct stray_prefetch *p, const char *dir,
			  const struct stray_sweep_entry **seq, size_t n,
			  int verify)
{
	memset(p, 0, sizeof(*p));
	p->dir = dir;
	p->seq = seq;
	p->n = seq ? n : 0;
	p->verify = verify;
	if (p->n == 0 || pthread_mutex_init(&p->mu, NULL) != 0)
		return;
	if (pthread_cond_init(&p->cv, NULL) != 0) {
		pthread_mutex_destroy(&p->mu);
		return;
	}
	if (pthread_create(&p->thread, NULL, reader, p) != 0) {
		pthread_cond_destroy(&p->cv);
		pthread_mutex_destroy(&p->mu);
		return;
	}
	p->running = 1;
}

int stray_prefetch_take(struct stray_prefetch *p,
			const struct stray_sweep_entry *e,
			struct stray_sweep_buf **buf, struct stray_error *err)
{
	struct stray_prefetch_slot *s;
	int rc;

	if (!p->running || p->next >= p->n || p->seq[p->next] != e)
		return STRAY_PREFETCH_NOT_NEXT;
	s = &p->slot[p->next % STRAY_PREFETCH_SLOTS];
	pthread_mutex_lock(&p->mu);
	while (s->state != 1)
		pthread_cond_wait(&p->cv, &p->mu);
	pthread_mutex_unlock(&p->mu);
	rc = s->rc;
	if (rc != STRAY_OK) {
		if (err)
			*err = s->err;
		return rc;
	}
	*buf = &s->buf;
	return STRAY_OK;
}

void stray_prefetch_release(struct stray_prefetch *p)
{
	struct stray_prefetch_slot *s;

	if (!p->running || p->next >= p->n)
		return;
	s = &p->slot[p->next % STRAY_PREFETCH_SLOTS];
	pthread_mutex_lock(&p->mu);
	s->state = 0;
	p->next++;
	pthread_cond_broadcast(&p->cv);
	pthread_mutex_unlock(&p->mu);
}

void stray_prefetch_stop(struct stray_prefetch *p)
{
	int i;

	if (p->running) {
		pthread_mutex_lock(&p->mu);
		p->stop = 1;
		pthread_cond_broadcast(&p->cv);
		pthread_mutex_unlock(&p->mu);
		pthread_join(p->thread, NULL);
		pthread_cond_destroy(&p->cv);
		pthread_mutex_destroy(&p->mu);
	}
	for (i = 0; i < STRAY_PREFETCH_SLOTS; i++)
		stray_sweep_buf_free(&p->slot[i].buf);
	free(p->seq);
	memset(p, 0, sizeof(*p));
}
