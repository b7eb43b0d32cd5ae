/* SPDX-License-Identifier: MIT */
/* samples_derived.c -- what fits derive from a sample set and share: kept
 * with the set, made once by the first fit that asks (a screening subset
 * takes ~8 ms, reading the whole set, and every model's fit of a table
 * needs one; He's fit its bin table too). */
#include "internal.h"
#include "samples.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct bf_derived {
    int kind, key[3];
    void *data;
    bf_derived_free_fn free_fn;
    struct bf_derived *next;
} bf_derived;

void bf_derived_init(brdffit_samples *s)
{
    pthread_mutex_init(&s->derived_lock, NULL);
    s->derived = NULL;
}

void bf_derived_free(brdffit_samples *s)
{
    bf_derived *d = s->derived;
    while (d) {
        bf_derived *next = d->next;
        d->free_fn(d->data);
        free(d);
        d = next;
    }
    s->derived = NULL;
    pthread_mutex_destroy(&s->derived_lock);
}

brdffit_status bf_derived_get(const brdffit_samples *s, int kind, const int key[3],
                              bf_derive_fn make, bf_derived_free_fn free_fn, const void **out,
                              brdffit_error *err)
{
    /* the set is the caller's const: only its lock and list change, and
     * only under the lock */
    brdffit_samples *ms = (brdffit_samples *)(uintptr_t)s;
    *out = NULL;
    brdffit_status st = BRDFFIT_OK;
    pthread_mutex_lock(&ms->derived_lock);
    bf_derived *d = ms->derived;
    while (d && !(d->kind == kind && memcmp(d->key, key, sizeof d->key) == 0))
        d = d->next;
    if (!d) {
        void *data = NULL;
        d = malloc(sizeof *d);
        st = d ? make(s, key, &data, err)
               : bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for a sample set's subset");
        if (st == BRDFFIT_OK) {
            *d = (bf_derived){ .kind = kind, .data = data, .free_fn = free_fn, .next = ms->derived };
            memcpy(d->key, key, sizeof d->key);
            ms->derived = d;
        } else {
            free(d);
            d = NULL;
        }
    }
    if (d)
        *out = d->data;
    pthread_mutex_unlock(&ms->derived_lock);
    return st;
}

size_t bf_derived_count(const brdffit_samples *s)
{
    brdffit_samples *ms = (brdffit_samples *)(uintptr_t)s;
    size_t n = 0;
    pthread_mutex_lock(&ms->derived_lock);
    for (const bf_derived *d = ms->derived; d; d = d->next)
        n++;
    pthread_mutex_unlock(&ms->derived_lock);
    return n;
}

static void samples_free_any(void *data)
{
    brdffit_samples_free(data);
}

static brdffit_status make_every(const brdffit_samples *s, const int key[3], void **out,
                                 brdffit_error *err)
{
    brdffit_samples *sub = NULL;
    brdffit_status st = bf_samples_every(s, (size_t)key[0], &sub, err);
    *out = sub;
    return st;
}

static brdffit_status make_bins(const brdffit_samples *s, const int key[3], void **out,
                                brdffit_error *err)
{
    brdffit_samples *sub = NULL;
    brdffit_status st = bf_samples_bins(s, key, &sub, err);
    *out = sub;
    return st;
}

static brdffit_status make_mirror(const brdffit_samples *s, const int key[3], void **out,
                                  brdffit_error *err)
{
    (void)key;
    brdffit_samples *m = NULL;
    brdffit_status st = bf_samples_mirror(s, &m, err);
    *out = m;
    return st;
}

brdffit_status bf_samples_every_kept(const brdffit_samples *src, size_t stride,
                                     const brdffit_samples **out, brdffit_error *err)
{
    const int key[3] = { stride > INT32_MAX ? INT32_MAX : (int)stride, 0, 0 };
    const void *d = NULL;
    brdffit_status st = bf_derived_get(src, BF_DERIVED_EVERY, key, make_every, samples_free_any, &d, err);
    *out = d;
    return st;
}

brdffit_status bf_samples_bins_kept(const brdffit_samples *src, const int step[3],
                                    const brdffit_samples **out, brdffit_error *err)
{
    const void *d = NULL;
    brdffit_status st = bf_derived_get(src, BF_DERIVED_BINS, step, make_bins, samples_free_any, &d, err);
    *out = d;
    return st;
}

brdffit_status bf_samples_mirror_kept(const brdffit_samples *src, const brdffit_samples **out,
                                      brdffit_error *err)
{
    const int key[3] = { 0, 0, 0 };
    const void *d = NULL;
    brdffit_status st = bf_derived_get(src, BF_DERIVED_MIRROR, key, make_mirror, samples_free_any, &d,
                                       err);
    *out = d;
    return st;
}
