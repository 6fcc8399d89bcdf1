/*
 * bigmem.h - zeroed full-frame buffers of the reduction, on 2 MiB pages
 * where the kernel offers them (private to libstray/reduce).
 */
#ifndef STRAY_REDUCE_BIGMEM_H
#define STRAY_REDUCE_BIGMEM_H

#include <stddef.h>

/* Zeroed bytes (NULL when out of memory); free with the same size. */
void *stray_big_alloc(size_t bytes);
void stray_big_free(void *p, size_t bytes);

#endif /* STRAY_REDUCE_BIGMEM_H */
