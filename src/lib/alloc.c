/* SPDX-License-Identifier: MIT */
/* alloc.c -- the library's large aligned arrays: on huge pages, and kept in a
 * small process-wide pool when freed, for the next array of about their size.
 *
 * Why the pool: the kernel zeroes every fresh page it maps.  `brdffit fit`
 * over a database makes each table's arrays anew (the table's values, its
 * sample set's fields, weights and bins, the mirror set's and the subsets'),
 * ~200 MB a MERL table, and zeroing them takes ~70 ms of system time a
 * table, in the thread that reads the next table beside the fits, which it
 * slows.  Reusing the freed arrays takes most of that away and changes no
 * fit (docs/performance.md). */
#define _DEFAULT_SOURCE /* madvise's MADV_HUGEPAGE */
#include "internal.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* From this size on, bf_alloc_aligned asks for huge pages and the pool
 * keeps what is freed. */
#define HUGE_FROM ((size_t)4 << 20)
#define HUGE_PAGE ((size_t)2 << 20)
/* The pool: at most this many freed arrays, this many bytes in all; a freed
 * array serves a request of at least 1 / POOL_SLACK its size. */
#define POOL_BLOCKS 16
#define POOL_BYTES ((size_t)1 << 30)
#define POOL_SLACK 2
/* The large arrays alive, with their sizes (the pool needs a freed array's
 * size); one allocated while this table is full is freed, not pooled. */
#define LIVE_MAX 1024

/* Under AddressSanitizer freed arrays go back to the allocator, so that a
 * use after free is still reported. */
#if defined(__SANITIZE_ADDRESS__)
#define POOL_ON 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define POOL_ON 0
#endif
#endif
#ifndef POOL_ON
#define POOL_ON 1
#endif

typedef struct block {
    void *p;
    size_t bytes;
} block;

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static block live[LIVE_MAX];     /* guarded by lock */
static block pool[POOL_BLOCKS];  /* guarded by lock */
static size_t pool_bytes;        /* guarded by lock: the sum of pool[].bytes */

static void *huge_new(size_t bytes)
{
    void *p = NULL;
    if (posix_memalign(&p, HUGE_PAGE, bytes) != 0)
        return NULL;
#ifdef MADV_HUGEPAGE
    /* before the first touch: a sample set's ~90 MB then takes ~45 page
     * faults instead of ~22000, and a pass over it as many TLB entries;
     * only a hint (no transparent huge pages: nothing changes) */
    (void)madvise(p, bytes & ~(HUGE_PAGE - 1), MADV_HUGEPAGE);
#endif
    return p;
}

/* The smallest pooled array of at least `bytes` and at most POOL_SLACK times
 * that, taken out of the pool; NULL if none.  With lock held. */
static void *pool_take(size_t bytes, size_t *got)
{
    int best = -1;
    for (int i = 0; i < POOL_BLOCKS; i++)
        if (pool[i].p && pool[i].bytes >= bytes && pool[i].bytes / POOL_SLACK <= bytes
            && (best < 0 || pool[i].bytes < pool[best].bytes))
            best = i;
    if (best < 0)
        return NULL;
    void *p = pool[best].p;
    *got = pool[best].bytes;
    pool[best].p = NULL;
    pool_bytes -= *got;
    return p;
}

/* Puts b into the pool if it has room: 1, else 0.  With lock held. */
static int pool_put(block b)
{
    if (!POOL_ON || pool_bytes + b.bytes > POOL_BYTES)
        return 0;
    for (int i = 0; i < POOL_BLOCKS; i++)
        if (!pool[i].p) {
            pool[i] = b;
            pool_bytes += b.bytes;
            return 1;
        }
    return 0;
}

/* Enters p (got bytes) in the live table; with lock held. */
static void live_add(void *p, size_t got)
{
    for (int i = 0; i < LIVE_MAX; i++)
        if (!live[i].p) {
            live[i] = (block){ p, got };
            return;
        }
}

void *bf_alloc_aligned(size_t bytes)
{
    void *p = NULL;
    if (bytes == 0)
        bytes = 64;
    if (bytes < HUGE_FROM)
        return posix_memalign(&p, 64, bytes) == 0 ? p : NULL;
    size_t got = bytes;
    pthread_mutex_lock(&lock);
    p = pool_take(bytes, &got);
    if (p)
        live_add(p, got);
    pthread_mutex_unlock(&lock);
    if (p)
        return p;
    if (!(p = huge_new(bytes)))
        return NULL;
    pthread_mutex_lock(&lock);
    live_add(p, got);
    pthread_mutex_unlock(&lock);
    return p;
}

void bf_free_aligned(void *p)
{
    if (!p)
        return;
    if ((uintptr_t)p % HUGE_PAGE != 0) { /* not a large array (huge_new aligns those) */
        free(p);
        return;
    }
    pthread_mutex_lock(&lock);
    for (int i = 0; i < LIVE_MAX; i++)
        if (live[i].p == p) {
            block b = live[i];
            live[i].p = NULL;
            if (pool_put(b))
                p = NULL;
            break;
        }
    pthread_mutex_unlock(&lock);
    free(p);
}

size_t bf_alloc_pooled(void)
{
    pthread_mutex_lock(&lock);
    size_t n = pool_bytes;
    pthread_mutex_unlock(&lock);
    return n;
}

int bf_alloc_pool_on(void)
{
    return POOL_ON;
}

size_t bf_alloc_pool_fill(unsigned char byte)
{
    size_t n = 0;
    pthread_mutex_lock(&lock);
    for (int i = 0; i < POOL_BLOCKS; i++)
        if (pool[i].p) {
            memset(pool[i].p, byte, pool[i].bytes);
            n++;
        }
    pthread_mutex_unlock(&lock);
    return n;
}

size_t brdffit_release_memory(void)
{
    block out[POOL_BLOCKS];
    size_t n = 0;
    pthread_mutex_lock(&lock);
    for (int i = 0; i < POOL_BLOCKS; i++) {
        out[i] = pool[i];
        n += pool[i].p ? pool[i].bytes : 0;
        pool[i].p = NULL;
    }
    pool_bytes = 0;
    pthread_mutex_unlock(&lock);
    for (int i = 0; i < POOL_BLOCKS; i++)
        free(out[i].p);
    return n;
}
