/* SPDX-License-Identifier: MIT */
/* samples.c -- the valid samples of a MERL table, prepared for a data pass
 * (struct brdffit_samples in samples.h). */
#include "internal.h"
#include "grid.h"
#include "samples.h"

#include "bf_models.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* cos(theta) >= cos(cutoff) - COS_TOL counts as within the cutoff */
#define COS_TOL 1e-12

void brdffit_sample_options_init(brdffit_sample_options *opt, size_t size)
{
    brdffit_sample_options d;
    memset(&d, 0, sizeof d);
    d.size = sizeof d;
    d.cutoff_deg = 80.0;
    d.scale = BRDFFIT_SCALE_STANDARD;
    bf_options_init(BRDFFIT_STRUCT_SAMPLE_OPTIONS, &d, opt, size);
}

void brdffit_samples_free(brdffit_samples *samples)
{
    if (!samples)
        return;
    bf_derived_free(samples);
    bf_free_aligned(samples->data);
    bf_free_aligned(samples->w);
    bf_free_aligned(samples->bin);
    free(samples);
}

/* The options in force (opt or the defaults), checked. */
static brdffit_status check_options(const brdffit_sample_options *opt, brdffit_sample_options *o,
                                    brdffit_error *err)
{
    brdffit_sample_options_default(o);
    brdffit_status st = bf_options_read(BRDFFIT_STRUCT_SAMPLE_OPTIONS, opt, o, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!isfinite(o->cutoff_deg) || !(o->cutoff_deg > 0) || !(o->cutoff_deg <= 90))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "sample options: cutoff %g deg must be in (0, 90]", o->cutoff_deg);
    if (!bf_scale_known(o->scale))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "sample options: unknown scale %d",
                       (int)o->scale);
    return BRDFFIT_OK;
}

/* From the values alone: the bins masked (a negative value in some channel);
 * a non-finite value, or one above BRDFFIT_VALUE_MAX,
 * is an error naming its bin. */
static brdffit_status count_bins(const double *v, size_t *masked, brdffit_error *err)
{
    *masked = 0;
    for (size_t b = 0; b < BF_NBINS; b++) {
        double r = v[b], g = v[BF_NBINS + b], bl = v[2 * BF_NBINS + b];
        if (!isfinite(r) || !isfinite(g) || !isfinite(bl)) {
            int c = !isfinite(r) ? 0 : !isfinite(g) ? 1 : 2, i, j, k;
            bf_bin_ijk(b, &i, &j, &k);
            return bf_fail(err, BRDFFIT_E_FILE_NONFINITE,
                           "table holds a non-finite value (channel %c, bin %d,%d,%d)",
                           bf_channel_name[c], i, j, k);
        }
        if (r > BRDFFIT_VALUE_MAX || g > BRDFFIT_VALUE_MAX || bl > BRDFFIT_VALUE_MAX) {
            int c = r > BRDFFIT_VALUE_MAX ? 0 : g > BRDFFIT_VALUE_MAX ? 1 : 2, i, j, k;
            double x = v[(size_t)c * BF_NBINS + b];
            bf_bin_ijk(b, &i, &j, &k);
            return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                           "table holds %.17g (channel %c, bin %d,%d,%d), above %g, the largest a "
                           "table may hold",
                           x, bf_channel_name[c], i, j, k, BRDFFIT_VALUE_MAX);
        }
        if (r < 0 || g < 0 || bl < 0)
            ++*masked;
    }
    return BRDFFIT_OK;
}

static size_t padded(size_t n)
{
    size_t np = (n + BF_PAD - 1) / BF_PAD * BF_PAD;
    return np ? np : BF_PAD;
}

/* Room for cap samples: fields at stride padded(cap), weights, bins. */
static brdffit_status alloc_samples(brdffit_samples *samples, size_t cap, brdffit_error *err)
{
    samples->npad = padded(cap);
    samples->data = bf_alloc_aligned((size_t)BF_NFIELDS * samples->npad * sizeof(double));
    /* each ~12 MB for a MERL table: huge pages, as the fields (page faults) */
    samples->w = bf_alloc_aligned(cap * sizeof *samples->w);
    samples->bin = bf_alloc_aligned(cap * sizeof *samples->bin);
    if (!samples->data || !samples->w || !samples->bin)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY,
                       "brdffit_samples_create: cannot allocate %zu samples", cap);
    return BRDFFIT_OK;
}

/* Bin b's directions; 1 when it is within the cutoff (both directions above
 * the horizon and at cos(theta) >= cosc). */
static int bin_within(const bf_grid_trig *gt, size_t b, double cosc, double wi[3], double wo[3],
                      int *i, int *j)
{
    int k;
    bf_bin_ijk(b, i, j, &k);
    bf_bin_dirs_trig(gt, *i, *j, k, wi, wo);
    return wi[2] > 0 && wo[2] > 0 && wi[2] >= cosc && wo[2] >= cosc;
}

static int bin_masked(const double *v, size_t b)
{
    return v[b] < 0 || v[BF_NBINS + b] < 0 || v[2 * BF_NBINS + b] < 0;
}

/* How many unmasked bins are within the cutoff (the samples); the others
 * count as beyond it (samples->beyond_cutoff). */
static size_t count_within(brdffit_samples *samples, const double *v, double cosc, const bf_grid_trig *gt)
{
    size_t n = 0;
    for (size_t b = 0; b < BF_NBINS; b++) {
        double wi[3], wo[3];
        int i, j;
        if (bin_masked(v, b))
            continue;
        if (bin_within(gt, b, cosc, wi, wo, &i, &j))
            n++;
        else
            samples->beyond_cutoff++;
    }
    return n;
}

/* The unmasked bins within the cutoff become samples 0..n-1 (n as
 * count_within found), fields at stride samples->npad; sets samples->sum_w. */
static void take_bins(brdffit_samples *samples, const double *v, double cosc, const bf_grid_trig *gt)
{
    double f[3];
    bf_scale_factors(samples->opt.scale, f);
    const size_t stride = samples->npad;
    double *F = samples->data;
    size_t m = 0;
    double sum_w = 0;
    for (size_t b = 0; b < BF_NBINS && m < samples->n; b++) {
        double wi[3], wo[3];
        int i, j;
        if (bin_masked(v, b) || !bin_within(gt, b, cosc, wi, wo, &i, &j))
            continue;
        bf_geom g = { wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], 0, 0 };
        bf_geom_derive(&g);
        F[BF_F_IX * stride + m] = wi[0];
        F[BF_F_IY * stride + m] = wi[1];
        F[BF_F_IZ * stride + m] = wi[2];
        F[BF_F_OX * stride + m] = wo[0];
        F[BF_F_OY * stride + m] = wo[1];
        F[BF_F_OZ * stride + m] = wo[2];
        F[BF_F_NH * stride + m] = g.nh;
        F[BF_F_VH * stride + m] = g.vh;
        F[BF_F_R * stride + m] = v[b] * f[0];
        F[BF_F_G * stride + m] = v[BF_NBINS + b] * f[1];
        F[BF_F_B * stride + m] = v[2 * BF_NBINS + b] * f[2];
        samples->bin[m] = (int)b;
        samples->w[m] = gt->w[i][j];
        sum_w += samples->w[m];
        m++;
    }
    samples->sum_w = sum_w;
}

void bf_samples_pad_geom(bf_geom *g)
{
    const bf_geom pg = { 0, 0, 1, 0, 0, 1, 0, 0 };
    *g = pg;
    bf_geom_derive(g);
}

/* The padding: harmless samples (n .. npad-1) that add exactly 0 to every sum. */
static void pad_fields(brdffit_samples *samples)
{
    const size_t stride = samples->npad;
    double *F = samples->data;
    bf_geom pg;
    bf_samples_pad_geom(&pg);
    const double pad[BF_NFIELDS] = {
        [BF_F_IZ] = 1, [BF_F_OZ] = 1, [BF_F_NH] = pg.nh, [BF_F_VH] = pg.vh,
    };
    for (int q = 0; q < BF_NFIELDS; q++)
        for (size_t m = samples->n; m < stride; m++)
            F[q * stride + m] = pad[q];
}

/* The metric weight of each sample, and the padding. */
static void finish_fields(brdffit_samples *samples)
{
    const size_t stride = samples->npad;
    double *F = samples->data;
    samples->sum_a2 = 0.0;
    for (size_t m = 0; m < samples->n; m++) {
        double iz = F[BF_F_IZ * stride + m];
        F[BF_F_A2 * stride + m] = samples->w[m] * iz * iz / (3.0 * samples->sum_w);
        samples->sum_a2 += F[BF_F_A2 * stride + m];
    }
    pad_fields(samples);
}

brdffit_status brdffit_samples_create(const brdffit_table *table,
                                      const brdffit_sample_options *opt,
                                      brdffit_samples **out, brdffit_error *err)
{
    if (out)
        *out = NULL;
    if (!table || !out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_samples_create: %s is NULL",
                       !table ? "table" : "out");
    brdffit_sample_options o;
    brdffit_status st = check_options(opt, &o, err);
    if (st != BRDFFIT_OK)
        return st;
    const double *v = brdffit_table_values_const(table);
    size_t masked;
    st = count_bins(v, &masked, err);
    if (st != BRDFFIT_OK)
        return st;

    bf_grid_trig *gt = NULL;
    brdffit_samples *samples = calloc(1, sizeof *samples);
    if (!samples)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_samples_create: out of memory");
    bf_derived_init(samples);
    samples->opt = o;
    samples->masked = masked;
    gt = malloc(sizeof *gt);
    if (!gt) {
        st = bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_samples_create: out of memory");
        goto done;
    }
    bf_grid_trig_init(gt);
    double cosc = cos(o.cutoff_deg * (BF_PI / 180.0)) - COS_TOL;
    samples->n = count_within(samples, v, cosc, gt);
    if (samples->n == 0) {
        st = bf_fail(err, BRDFFIT_E_NO_SAMPLES,
                     "no valid samples (%zu bins masked, %zu beyond the %g deg cutoff or the "
                     "horizon)",
                     samples->masked, samples->beyond_cutoff, o.cutoff_deg);
        goto done;
    }
    st = alloc_samples(samples, samples->n, err);
    if (st != BRDFFIT_OK)
        goto done;
    take_bins(samples, v, cosc, gt);
    finish_fields(samples);
done:
    free(gt);
    if (st != BRDFFIT_OK) {
        brdffit_samples_free(samples);
        return st;
    }
    *out = samples;
    bf_ok(err);
    return BRDFFIT_OK;
}

size_t brdffit_samples_count(const brdffit_samples *samples)
{
    return samples ? samples->n : 0;
}

size_t brdffit_samples_masked(const brdffit_samples *samples)
{
    return samples ? samples->masked : 0;
}

size_t brdffit_samples_beyond_cutoff(const brdffit_samples *samples)
{
    return samples ? samples->beyond_cutoff : 0;
}

brdffit_status brdffit_samples_get(const brdffit_samples *samples, size_t index,
                                   brdffit_sample *out, brdffit_error *err)
{
    if (!samples || !out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_samples_get: %s is NULL",
                       !samples ? "samples" : "out");
    if (index >= samples->n)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "brdffit_samples_get: index %zu, but the set has %zu samples", index,
                       samples->n);
    brdffit_sample one;
    memset(&one, 0, sizeof one);
    one.size = sizeof one;
    const double *d = samples->data;
    size_t np = samples->npad;
    for (int c = 0; c < 3; c++) {
        one.wi[c] = d[(size_t)(BF_F_IX + c) * np + index];
        one.wo[c] = d[(size_t)(BF_F_OX + c) * np + index];
        one.rgb[c] = d[(size_t)(BF_F_R + c) * np + index];
    }
    one.weight = samples->w[index];
    bf_bin_ijk((size_t)samples->bin[index], &one.i, &one.j, &one.k);
    brdffit_status st = bf_options_write(BRDFFIT_STRUCT_SAMPLE, &one, out, err);
    if (st == BRDFFIT_OK)
        bf_ok(err);
    return st;
}

brdffit_status brdffit_samples_options(const brdffit_samples *samples,
                                       brdffit_sample_options *out, brdffit_error *err)
{
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_samples_options: out is NULL");
    brdffit_sample_options dflt;
    brdffit_sample_options_default(&dflt);
    brdffit_status st = bf_options_write(BRDFFIT_STRUCT_SAMPLE_OPTIONS,
                                         samples ? &samples->opt : &dflt, out, err);
    if (st == BRDFFIT_OK)
        bf_ok(err);
    return st;
}

/* Two geometries closer than this in every invariant are the same one. */
#define GEOM_TOL 1e-9

size_t bf_samples_geometries(const brdffit_samples *samples, size_t need)
{
    /* the invariants of an isotropic, reciprocal BRDF's arguments: the two
     * cosines (in either order) and wi . wo */
    double seen[BF_GEOM_NEED_MAX][3];
    size_t found = 0;
    if (need > BF_GEOM_NEED_MAX)
        need = BF_GEOM_NEED_MAX;
    const double *d = samples->data;
    size_t np = samples->npad;
    for (size_t m = 0; m < samples->n && found < need; m++) {
        double iz = d[BF_F_IZ * np + m], oz = d[BF_F_OZ * np + m];
        double dot = d[BF_F_IX * np + m] * d[BF_F_OX * np + m] +
                     d[BF_F_IY * np + m] * d[BF_F_OY * np + m] + iz * oz;
        double key[3] = { iz < oz ? iz : oz, iz < oz ? oz : iz, dot };
        size_t q = 0;
        for (; q < found; q++)
            if (fabs(seen[q][0] - key[0]) <= GEOM_TOL && fabs(seen[q][1] - key[1]) <= GEOM_TOL &&
                fabs(seen[q][2] - key[2]) <= GEOM_TOL)
                break;
        if (q == found)
            memcpy(seen[found++], key, sizeof key);
    }
    return found;
}

/* Field by field, one of src's arrays at a time, a run of consecutive
 * samples (a mirror set's) at a time.  A strided subset still reads most of
 * src's cache lines: every 12th sample of a full table takes ~9 ms (sample
 * by sample, with the keep test made twice a sample, ~17 ms). */
brdffit_status bf_samples_take(const brdffit_samples *src, const size_t *idx, size_t n,
                               brdffit_samples **out, brdffit_error *err)
{
    *out = NULL;
    brdffit_samples *sub = calloc(1, sizeof *sub);
    if (!sub)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "a sample subset: out of memory");
    bf_derived_init(sub);
    brdffit_status st = alloc_samples(sub, n, err);
    if (st != BRDFFIT_OK) {
        brdffit_samples_free(sub);
        return st;
    }
    sub->opt = src->opt;
    sub->n = n;
    for (int q = 0; q < BF_NFIELDS; q++) {
        const double *from = src->data + (size_t)q * src->npad;
        double *to = sub->data + (size_t)q * sub->npad;
        for (size_t m = 0, e; m < n; m = e) { /* a run of consecutive samples at a time */
            for (e = m + 1; e < n && idx[e] == idx[e - 1] + 1; e++)
                ;
            memcpy(to + m, from + idx[m], (e - m) * sizeof *to);
        }
    }
    for (size_t m = 0; m < n; m++) {
        sub->w[m] = src->w[idx[m]];
        sub->bin[m] = src->bin[idx[m]];
        sub->sum_w += sub->w[m];
        sub->sum_a2 += sub->data[BF_F_A2 * sub->npad + m];
    }
    pad_fields(sub); /* a2 stays the full set's */
    *out = sub;
    return BRDFFIT_OK;
}

/* Room for the indices of a subset of up to n samples. */
static size_t *index_alloc(size_t n, brdffit_error *err)
{
    size_t *idx = bf_alloc_aligned(n * sizeof *idx);
    if (!idx)
        bf_fail(err, BRDFFIT_E_NO_MEMORY, "a sample subset: out of memory");
    return idx;
}

brdffit_status bf_samples_every(const brdffit_samples *src, size_t stride, brdffit_samples **out,
                                brdffit_error *err)
{
    *out = NULL;
    if (stride < 1)
        stride = 1;
    const size_t n = (src->n + stride - 1) / stride;
    size_t *idx = index_alloc(n, err);
    if (!idx)
        return BRDFFIT_E_NO_MEMORY;
    for (size_t m = 0; m < n; m++)
        idx[m] = m * stride;
    brdffit_status st = bf_samples_take(src, idx, n, out, err);
    bf_free_aligned(idx);
    return st;
}

brdffit_status bf_samples_bins(const brdffit_samples *src, const int step[3],
                               brdffit_samples **out, brdffit_error *err)
{
    *out = NULL;
    size_t *idx = index_alloc(src->n, err);
    if (!idx)
        return BRDFFIT_E_NO_MEMORY;
    /* A set in table order walks each (theta_h, theta_d) bin's samples in a
     * row (bins increasing): theta_h's and theta_d's test once per run, and
     * a run not kept is passed over by a bisection for its end (a fraction
     * of a millisecond for a full table, where three divisions a sample
     * take several: docs/performance.md) */
    char keep_k[BF_NPD];
    for (int k = 0; k < BF_NPD; k++)
        keep_k[k] = k % step[2] == 0;
    size_t n = 0;
    for (size_t i = 0; i < src->n;) {
        int h, j, k; /* theta_h, theta_d, phi_d of the run's first sample */
        bf_bin_ijk((size_t)src->bin[i], &h, &j, &k);
        const int lo = src->bin[i] - k, end = lo + BF_NPD;
        size_t e = i + 1, hi = src->n - i < BF_NPD ? src->n : i + BF_NPD; /* the run: i .. e-1 */
        while (e < hi) { /* the first index in [e, hi) with bin >= end, or hi */
            size_t mid = e + (hi - e) / 2;
            if (src->bin[mid] >= end)
                hi = mid;
            else
                e = mid + 1;
        }
        if (h % step[0] == 0 && j % step[1] == 0)
            for (size_t q = i; q < e; q++)
                if (keep_k[src->bin[q] - lo])
                    idx[n++] = q;
        i = e;
    }
    brdffit_status st = bf_samples_take(src, idx, n, out, err);
    bf_free_aligned(idx);
    return st;
}
