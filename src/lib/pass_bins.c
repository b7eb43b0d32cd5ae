/* SPDX-License-Identifier: MIT */
/* pass_bins.c -- the bin table of a sample set (BF_B_* in kernels/bf_he_rows.h) for a
 * model whose pass makes bin rows (He: bf_he_bin_rows in kernels/bf_he_rows.h):
 * each sample's (theta_h, theta_d) bin, one geometry per bin, its
 * flatness bounds and the sums a pass takes a wholly flat bin from (made
 * once and kept with the set), and a driver's room for the rows. */
#include "pass.h"
#include "grid.h"
#include "samples.h"

#include "bf_lobe_pass.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(BF_F_VH - BF_F_IX == 7 && BF_B_VH - BF_B_IX == 7 && BF_F_OZ - BF_F_IX == BF_B_OZ - BF_B_IX,
               "a sample's geometry fields and a bin's are in the same order");

void bf_pass_bins_free(bf_pass_bins *b)
{
    free(b->rows); /* hd and table are the sample set's */
    memset(b, 0, sizeof *b);
}

/* A sample set's bin table: each sample's bin (hd) and the bins' geometry
 * and flatness bounds (table); kept with the set (bf_derived_get). */
typedef struct bin_table {
    double *hd;    /* npad */
    double *table; /* BF_BFIELDS x BF_NHD_PAD */
} bin_table;

static void bin_table_free(void *data)
{
    bin_table *t = data;
    if (!t)
        return;
    bf_free_aligned(t->hd);
    free(t->table);
    free(t);
}

/* Every bin the pad geometry (wi = wo = the normal: finite everywhere),
 * COT 0 (never flat) and COTW -1, until a sample says otherwise. */
static void table_clear(double *t)
{
    bf_geom pg;
    bf_samples_pad_geom(&pg);
    const double pad[BF_BFIELDS] = {
        [BF_B_IZ] = 1, [BF_B_OZ] = 1, [BF_B_NH] = pg.nh, [BF_B_VH] = pg.vh,
        [BF_B_COTW] = -1, /* never summed whole (bf_he_bin_whole) */
    };
    for (int f = 0; f < BF_BFIELDS; f++)
        for (int h = 0; h < BF_NHD_PAD; h++)
            t[f * BF_NHD_PAD + h] = pad[f];
}

/* The samples' bins into b->hd and each bin's first geometry and its
 * largest and smallest min(cos ti, cos to) into b->table. */
static brdffit_status table_fill(const brdffit_samples *s, bin_table *b, brdffit_error *err)
{
    const double *F = s->data;
    const size_t np = s->npad;
    char seen[BF_NHD] = { 0 };
    int hd = 0, lo = 0; /* the bin of the samples lo .. lo + BF_NPD - 1 (a set in table order
                         * walks one bin's samples in a row: no division for most) */
    for (size_t i = 0; i < s->n; i++) {
        if (s->bin[i] < lo || s->bin[i] >= lo + BF_NPD) {
            hd = s->bin[i] / BF_NPD;
            lo = hd * BF_NPD;
        }
        if (s->bin[i] < 0 || hd >= BF_NHD) /* every set comes from a table: cannot happen */
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "sample %zu has no MERL bin (%d)", i,
                           s->bin[i]);
        double *t = b->table;
        /* the largest and smallest min(cos ti, cos to) for now: their
         * cotangents below */
        double ci = F[BF_F_IZ * np + i], co = F[BF_F_OZ * np + i], c = ci < co ? ci : co;
        if (!seen[hd]) { /* the bin's first sample */
            for (int f = 0; f < 8; f++)
                t[(BF_B_IX + f) * BF_NHD_PAD + hd] = F[(BF_F_IX + f) * np + i];
            t[BF_B_COTLO * BF_NHD_PAD + hd] = c;
            seen[hd] = 1;
        }
        if (c > t[BF_B_COT * BF_NHD_PAD + hd])
            t[BF_B_COT * BF_NHD_PAD + hd] = c;
        if (c < t[BF_B_COTLO * BF_NHD_PAD + hd])
            t[BF_B_COTLO * BF_NHD_PAD + hd] = c;
        b->hd[i] = (double)hd;
    }
    for (int h = 0; h < BF_NHD; h++)
        if (seen[h]) {
            double *t = b->table;
            t[BF_B_COT * BF_NHD_PAD + h] = bf_he_cot_of_cos(t[BF_B_COT * BF_NHD_PAD + h]);
            t[BF_B_COTLO * BF_NHD_PAD + h] = bf_he_cot_of_cos(t[BF_B_COTLO * BF_NHD_PAD + h]);
        }
    /* padding: the last sample's bin, which then always has its row (the
     * padding's wi = wo = N is flat at any point) */
    if (np > s->n) {
        const double hl = s->n ? b->hd[s->n - 1] : 0.0;
        for (size_t i = s->n; i < np; i++)
            b->hd[i] = hl;
        double *cot = b->table + BF_B_COT * BF_NHD_PAD + (int)hl;
        *cot = fmax(*cot, bf_he_cot_of_cos(1.0));
    }
    return BRDFFIT_OK;
}

/* q = 1 / (cos ti cos to) of sample i, as the rows serve it (bf_he_bin_q). */
static double sample_q(const double *F, size_t np, size_t i)
{
    bf_geom g;
    memset(&g, 0, sizeof g);
    g.iz = F[BF_F_IZ * np + i];
    g.oz = F[BF_F_OZ * np + i];
    bf_he_flat f;
    bf_he_flat_cos(&g, &f);
    return bf_he_bin_q(&f);
}

#define T(f, h) t[(f) * BF_NHD_PAD + (h)]
#define LINE(c, f) T(BF_B_LINE + (c) * BF_BL_FIELDS + (f), h)

/* The sums of bin h from its run of samples lo .. hi - 1 (BF_B_START1 ..
 * the lines: bf_he_rows.h), in three walks: the sums of a^2, a^2 q, a^2 q^2
 * and a^2 rho; those about the means; the residuals of the lines. */
static void run_sums(const brdffit_samples *s, size_t lo, size_t hi, double *t, int h)
{
    const double *F = s->data;
    const size_t np = s->npad;
    double sa = 0.0, saq = 0.0, saqq = 0.0, sr[3] = { 0.0, 0.0, 0.0 };
    for (size_t i = lo; i < hi; i++) {
        const double a2 = F[BF_F_A2 * np + i], q = sample_q(F, np, i);
        sa += a2;
        saq += a2 * q;
        saqq += (a2 * q) * q;
        for (int c = 0; c < 3; c++)
            sr[c] += a2 * F[(BF_F_R + c) * np + i];
    }
    const double qbar = sa > 0.0 ? saq / sa : 0.0;
    double rbar[3], sq1 = 0.0, sqc = 0.0, cov[3] = { 0.0, 0.0, 0.0 };
    for (int c = 0; c < 3; c++)
        rbar[c] = sa > 0.0 ? sr[c] / sa : 0.0;
    for (size_t i = lo; i < hi; i++) {
        const double a2 = F[BF_F_A2 * np + i], dq = sample_q(F, np, i) - qbar;
        sq1 += a2 * dq;
        sqc += (a2 * dq) * dq;
        for (int c = 0; c < 3; c++)
            cov[c] += (a2 * dq) * (F[(BF_F_R + c) * np + i] - rbar[c]);
    }
    double beta[3], r[3] = { 0.0, 0.0, 0.0 }, rqc[3] = { 0.0, 0.0, 0.0 }, rr[3] = { 0.0, 0.0, 0.0 };
    for (int c = 0; c < 3; c++) {
        beta[c] = sqc > 0.0 ? cov[c] / sqc : 0.0;
        if (!isfinite(beta[c]))
            beta[c] = 0.0;
    }
    for (size_t i = lo; i < hi; i++) {
        const double a2 = F[BF_F_A2 * np + i], dq = sample_q(F, np, i) - qbar;
        for (int c = 0; c < 3; c++) {
            const double e = F[(BF_F_R + c) * np + i] - rbar[c] - beta[c] * dq;
            r[c] += a2 * e;
            rqc[c] += (a2 * e) * dq;
            rr[c] += (a2 * e) * e;
        }
    }
    T(BF_B_START1, h) = (double)lo + 1.0;
    T(BF_B_COTW, h) = T(BF_B_COTLO, h);
    T(BF_B_COUNT, h) = (double)(hi - lo);
    T(BF_B_SA, h) = sa;
    T(BF_B_SAQ, h) = saq;
    T(BF_B_SAQQ, h) = saqq;
    T(BF_B_QBAR, h) = qbar;
    T(BF_B_SQ1, h) = sq1;
    T(BF_B_SQC, h) = sqc;
    for (int c = 0; c < 3; c++) {
        LINE(c, BF_BL_RBAR) = rbar[c];
        LINE(c, BF_BL_BETA) = beta[c];
        LINE(c, BF_BL_R) = r[c];
        LINE(c, BF_BL_RQC) = rqc[c];
        LINE(c, BF_BL_RR) = rr[c];
    }
}

/* Every bin's sums from its run of samples (hd: each sample's bin, in
 * table order: nondecreasing, so that each bin is one run, as the rows also
 * need).  A set whose bins are out of that order (the library makes none)
 * has no bin summed whole: START1 0 and COTW -1 everywhere. */
static void table_sums(const brdffit_samples *s, const double *hd, double *t)
{
    for (size_t i = 1; i < s->n; i++)
        if (hd[i] < hd[i - 1])
            return;
    for (size_t lo = 0, hi; lo < s->n; lo = hi) {
        const int h = (int)hd[lo];
        for (hi = lo + 1; hi < s->n && (int)hd[hi] == h; hi++)
            ;
        run_sums(s, lo, hi, t, h);
    }
}

#undef LINE
#undef T

static brdffit_status bin_table_make(const brdffit_samples *s, const int key[3], void **out,
                                     brdffit_error *err)
{
    (void)key;
    *out = NULL;
    bin_table *b = calloc(1, sizeof *b);
    if (b) {
        b->hd = bf_alloc_aligned(s->npad * sizeof *b->hd); /* a kernel buffer's host memory */
        b->table = malloc((size_t)BF_BFIELDS * BF_NHD_PAD * sizeof *b->table);
    }
    if (!b || !b->hd || !b->table) {
        bin_table_free(b);
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for the bin table");
    }
    table_clear(b->table);
    brdffit_status st = table_fill(s, b, err);
    if (st == BRDFFIT_OK)
        table_sums(s, b->hd, b->table);
    if (st != BRDFFIT_OK) {
        bin_table_free(b);
        return st;
    }
    *out = b;
    return BRDFFIT_OK;
}

static brdffit_status bin_table_kept(const brdffit_samples *s, const bin_table **out,
                                     brdffit_error *err)
{
    static const int key[3] = { 0, 0, 0 };
    const void *kept = NULL;
    brdffit_status st = bf_derived_get(s, BF_DERIVED_BIN_TABLE, key, bin_table_make, bin_table_free,
                                       &kept, err);
    *out = kept;
    return st;
}

brdffit_status bf_pass_bins_prepare(const brdffit_samples *s, brdffit_error *err)
{
    const bin_table *t;
    return bin_table_kept(s, &t, err);
}

brdffit_status bf_pass_bins_make(const brdffit_samples *s, int row_runs, bf_pass_bins *b,
                                 brdffit_error *err)
{
    memset(b, 0, sizeof b[0]);
    const bin_table *t = NULL;
    brdffit_status st = bin_table_kept(s, &t, err);
    if (st != BRDFFIT_OK)
        return st;
    b->nrows = BF_NHD_PAD + 8 * (row_runs > 0 ? row_runs : 1);
    b->rows = calloc((size_t)BF_BK_FIELDS * (size_t)b->nrows, sizeof *b->rows);
    if (!b->rows)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for the bin rows");
    b->hd = t->hd;
    b->table = t->table;
    return BRDFFIT_OK;
}
