/*
 * bigmem.c - zeroed full-frame buffers (bigmem.h).  A full frame's
 * per-pixel buffers are ~150 MB: on 4 KiB pages their first touch costs
 * ~40 000 page faults, more than the arithmetic.  Large buffers are
 * mapped directly (the kernel's pages come zeroed: no second memset),
 * aligned to 2 MiB and marked for transparent huge pages, a 512th of
 * the faults.  Small ones are plain calloc.
 */
#define _DEFAULT_SOURCE		/* MAP_ANONYMOUS, MADV_HUGEPAGE */
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

#include "bigmem.h"

#define HUGE_PAGE ((size_t)2 << 20)
#define BIG (2 * HUGE_PAGE)

static size_t round_up(size_t bytes)
{
	return (bytes + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
}

void *stray_big_alloc(size_t bytes)
{
	size_t len = round_up(bytes), lead;
	unsigned char *p;

	if (bytes < BIG)
		return calloc(1, bytes ? bytes : 1);
	p = mmap(NULL, len + HUGE_PAGE, PROT_READ | PROT_WRITE,
		 MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
	if (p == MAP_FAILED)
		return NULL;
	/* keep the 2 MiB-aligned len bytes, give back the rest */
	lead = (HUGE_PAGE - (uintptr_t)p % HUGE_PAGE) % HUGE_PAGE;
	if (lead)
		munmap(p, lead);
	if (HUGE_PAGE - lead)
		munmap(p + lead + len, HUGE_PAGE - lead);
	p += lead;
#ifdef MADV_HUGEPAGE
	madvise(p, len, MADV_HUGEPAGE);
#endif
	return p;
}

void stray_big_free(void *p, size_t bytes)
{
	if (!p)
		return;
	if (bytes < BIG)
		free(p);
	else
		munmap(p, round_up(bytes));
}
