/* SPDX-License-Identifier: MIT */
/* samples_mirror.c -- the mirror set of a sample set: every pair of samples
 * with one model value merged into one sample, so that a fit's passes on all
 * samples read about half as many (brdffit_fit, brdffit_error_of).
 *
 * Every model here is isotropic and reciprocal, so f at (theta_h, theta_d,
 * phi_d) equals f at (theta_h, theta_d, pi - phi_d): mirroring wi and wo in
 * the plane of N and H takes phi_d to -phi_d, and exchanging them takes it on
 * to pi - phi_d.  On MERL's grid (phi_d = k pi / 180) the bins k and 180 - k
 * of a (theta_h, theta_d) row are such a pair for k = 1 .. 89; k = 0 and 90
 * have none (nor has a bin whose partner is masked or beyond the cutoff).
 *
 * A pass's moments (kernels/bf_layout.h) are sums of a2 times products of
 * K, its partials G_j and e = rho - f, where rho is a sample's value and
 * a2 its weight.  K, G_j and f are one for both samples of a pair, so one
 * sample with weight a2 = a2_1 + a2_2 and value rho = (a2_1 rho_1 + a2_2
 * rho_2) / a2 adds to every moment what the two add, except to sum a2 e^2,
 * where the two add a2_1 a2_2 (rho_1 - rho_2)^2 / a2 more per channel,
 * whatever f is.  The mirror set keeps that sum in pair_see and every pass
 * adds it (bf_driver_run), so its sums are the set's up to rounding: the
 * merged sample is evaluated at bin k's directions, which give the pair's
 * f to ~1e-13 relative at grazing angles, ~1e-16 elsewhere. */
#include "grid.h"
#include "internal.h"
#include "samples.h"

#include <stdlib.h>

/* The phi_d index of the mirror partner of index k (its own for k = 0 and 90). */
static int partner_k(int k)
{
    return k == 0 ? 0 : BF_NPD - k;
}

/* Of the samples of src, which the mirror set takes (keep[0..*n-1], table
 * order) and the partner each takes along (mate, -1 for none): the samples
 * of each (theta_h, theta_d) row with k <= 90, and those with k > 90 whose
 * partner is not in the set. */
static void choose_pairs(const brdffit_samples *src, size_t *keep, long *mate, size_t *n)
{
    long at[BF_NPD];
    *n = 0;
    for (size_t i = 0; i < src->n;) {
        const int row = src->bin[i] / BF_NPD;
        size_t e = i;
        for (int k = 0; k < BF_NPD; k++)
            at[k] = -1;
        for (; e < src->n && src->bin[e] / BF_NPD == row; e++)
            at[src->bin[e] % BF_NPD] = (long)e;
        for (size_t q = i; q < e; q++) {
            const int k = src->bin[q] % BF_NPD, kp = partner_k(k);
            if (k > BF_NPD / 2 && at[kp] >= 0)
                continue; /* taken along by its partner */
            keep[*n] = q;
            mate[*n] = k != kp ? at[kp] : -1;
            (*n)++;
        }
        i = e;
    }
}

/* Merge sample q of the mirror set m with src's sample p, its partner. */
static void merge_pair(brdffit_samples *m, size_t q, const brdffit_samples *src, size_t p)
{
    double *a2 = m->data + (size_t)BF_F_A2 * m->npad + q;
    const double a2p = src->data[(size_t)BF_F_A2 * src->npad + p], sum = *a2 + a2p;
    if (!(sum > 0.0))
        return; /* neither adds to any sum */
    for (int c = 0; c < 3; c++) {
        double *rho = m->data + (size_t)(BF_F_R + c) * m->npad + q;
        const double rhop = src->data[(size_t)(BF_F_R + c) * src->npad + p], diff = *rho - rhop;
        m->pair_see[c] += (*a2 * a2p) * (diff * diff) / sum;
        *rho = (*a2 * *rho + a2p * rhop) / sum;
    }
    *a2 = sum;
    m->w[q] += src->w[p];
}

brdffit_status bf_samples_mirror(const brdffit_samples *src, brdffit_samples **out,
                                 brdffit_error *err)
{
    *out = NULL;
    size_t *keep = bf_alloc_aligned(src->n * sizeof *keep), n = 0;
    long *mate = bf_alloc_aligned(src->n * sizeof *mate);
    brdffit_status st = BRDFFIT_OK;
    if (!keep || !mate) {
        st = bf_fail(err, BRDFFIT_E_NO_MEMORY, "the mirror set of %zu samples: out of memory",
                     src->n);
        goto done;
    }
    choose_pairs(src, keep, mate, &n);
    st = bf_samples_take(src, keep, n, out, err);
    if (st != BRDFFIT_OK)
        goto done;
    for (size_t q = 0; q < n; q++)
        if (mate[q] >= 0)
            merge_pair(*out, q, src, (size_t)mate[q]);
    (*out)->sum_w = src->sum_w; /* what its merged weights add up to, to rounding */
    (*out)->sum_a2 = src->sum_a2;
done:
    bf_free_aligned(keep);
    bf_free_aligned(mate);
    return st;
}
