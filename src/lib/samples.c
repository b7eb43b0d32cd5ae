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

void brdffit_sample_options_default(brdffit_sample_options *opt)
{
    if (!opt)
        return;
    opt->cutoff_deg = 80.0;
    opt->scale = BRDFFIT_SCALE_STANDARD;
}

void brdffit_samples_free(brdffit_samples *samples)
{
    if (!samples)
        return;
    bf_free_aligned(samples->data);
    free(samples->w);
    free(samples->bin);
    free(samples);
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
    brdffit_sample_options_default(&o);
    if (opt)
        o = *opt;
    if (!isfinite(o.cutoff_deg) || !(o.cutoff_deg > 0) || !(o.cutoff_deg <= 90))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "sample options: cutoff %g deg must be in (0, 90]", o.cutoff_deg);
    if (o.scale != BRDFFIT_SCALE_STANDARD && o.scale != BRDFFIT_SCALE_FLAT)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "sample options: unknown scale %d",
                       (int)o.scale);

    const double *v = brdffit_table_values_const(table);
    const double cosc = cos(o.cutoff_deg * (BF_PI / 180.0)) - COS_TOL;
    static const char ch[3] = { 'R', 'G', 'B' };

    brdffit_samples *s = calloc(1, sizeof *s);
    int *bins = malloc(BF_NBINS * sizeof *bins);
    if (!s || !bins) {
        free(s);
        free(bins);
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_samples_create: out of memory");
    }
    s->opt = o;

    /* pass 1: classify every bin */
    size_t n = 0;
    for (size_t b = 0; b < BF_NBINS; b++) {
        double r = v[b], g = v[BF_NBINS + b], bl = v[2 * BF_NBINS + b];
        if (!isfinite(r) || !isfinite(g) || !isfinite(bl)) {
            int c = !isfinite(r) ? 0 : !isfinite(g) ? 1 : 2, i, j, k;
            bf_bin_ijk(b, &i, &j, &k);
            free(s);
            free(bins);
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "table holds a non-finite value (channel %c, bin %d,%d,%d)", ch[c], i,
                           j, k);
        }
        if (r > BRDFFIT_VALUE_MAX || g > BRDFFIT_VALUE_MAX || bl > BRDFFIT_VALUE_MAX) {
            int c = r > BRDFFIT_VALUE_MAX ? 0 : g > BRDFFIT_VALUE_MAX ? 1 : 2, i, j, k;
            double x = v[(size_t)c * BF_NBINS + b];
            bf_bin_ijk(b, &i, &j, &k);
            free(s);
            free(bins);
            return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                           "table holds %.17g (channel %c, bin %d,%d,%d), above %g, the largest a "
                           "table may hold",
                           x, ch[c], i, j, k, BRDFFIT_VALUE_MAX);
        }
        if (r < 0 || g < 0 || bl < 0) {
            s->masked++;
            continue;
        }
        int i, j, k;
        double wi[3], wo[3];
        bf_bin_ijk(b, &i, &j, &k);
        brdffit_bin_directions(i, j, k, wi, wo);
        if (wi[2] > 0 && wo[2] > 0 && wi[2] >= cosc && wo[2] >= cosc)
            bins[n++] = (int)b;
        else
            s->beyond_cutoff++;
    }
    if (n == 0) {
        size_t masked = s->masked, beyond = s->beyond_cutoff;
        free(s);
        free(bins);
        return bf_fail(err, BRDFFIT_E_NO_SAMPLES,
                       "no valid samples (%zu bins masked, %zu beyond the %g deg cutoff or the "
                       "horizon)",
                       masked, beyond, o.cutoff_deg);
    }

    /* pass 2: the sample arrays */
    size_t npad = (n + BF_PAD - 1) / BF_PAD * BF_PAD;
    s->n = n;
    s->npad = npad;
    s->bin = realloc(bins, n * sizeof *bins);
    if (!s->bin)
        s->bin = bins; /* shrinking failed: keep the larger block */
    s->w = malloc(n * sizeof *s->w);
    s->data = bf_alloc_aligned((size_t)BF_NFIELDS * npad * sizeof(double));
    if (!s->w || !s->data) {
        brdffit_samples_free(s);
        return bf_fail(err, BRDFFIT_E_NO_MEMORY,
                       "brdffit_samples_create: cannot allocate %zu samples", n);
    }
    double f[3];
    bf_scale_factors(o.scale, f);
    double *F[BF_NFIELDS];
    for (int q = 0; q < BF_NFIELDS; q++)
        F[q] = s->data + (size_t)q * npad;

    double sum_w = 0;
    for (size_t m = 0; m < n; m++) {
        int b = s->bin[m], i, j, k;
        bf_bin_ijk((size_t)b, &i, &j, &k);
        double wi[3], wo[3];
        brdffit_bin_directions(i, j, k, wi, wo);
        bf_geom g = { wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], 0, 0 };
        bf_geom_derive(&g);
        F[BF_F_IX][m] = wi[0];
        F[BF_F_IY][m] = wi[1];
        F[BF_F_IZ][m] = wi[2];
        F[BF_F_OX][m] = wo[0];
        F[BF_F_OY][m] = wo[1];
        F[BF_F_OZ][m] = wo[2];
        F[BF_F_NH][m] = g.nh;
        F[BF_F_VH][m] = g.vh;
        F[BF_F_R][m] = v[(size_t)b] * f[0];
        F[BF_F_G][m] = v[BF_NBINS + (size_t)b] * f[1];
        F[BF_F_B][m] = v[2 * BF_NBINS + (size_t)b] * f[2];
        s->w[m] = brdffit_bin_weight(i, j);
        sum_w += s->w[m];
    }
    s->sum_w = sum_w;
    for (size_t m = 0; m < n; m++) {
        double iz = F[BF_F_IZ][m];
        F[BF_F_A2][m] = s->w[m] * iz * iz / (3.0 * sum_w);
    }
    /* padding: harmless samples that add exactly 0 to every sum */
    bf_geom pg = { 0, 0, 1, 0, 0, 1, 0, 0 };
    bf_geom_derive(&pg);
    for (size_t m = n; m < npad; m++) {
        F[BF_F_IX][m] = 0;
        F[BF_F_IY][m] = 0;
        F[BF_F_IZ][m] = 1;
        F[BF_F_OX][m] = 0;
        F[BF_F_OY][m] = 0;
        F[BF_F_OZ][m] = 1;
        F[BF_F_NH][m] = pg.nh;
        F[BF_F_VH][m] = pg.vh;
        F[BF_F_R][m] = 0;
        F[BF_F_G][m] = 0;
        F[BF_F_B][m] = 0;
        F[BF_F_A2][m] = 0;
    }
    *out = s;
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
                                   brdffit_sample *out)
{
    if (!samples || !out || index >= samples->n)
        return BRDFFIT_E_INVALID_ARGUMENT;
    const double *d = samples->data;
    size_t np = samples->npad;
    for (int c = 0; c < 3; c++) {
        out->wi[c] = d[(size_t)(BF_F_IX + c) * np + index];
        out->wo[c] = d[(size_t)(BF_F_OX + c) * np + index];
        out->rgb[c] = d[(size_t)(BF_F_R + c) * np + index];
    }
    out->weight = samples->w[index];
    bf_bin_ijk((size_t)samples->bin[index], &out->i, &out->j, &out->k);
    return BRDFFIT_OK;
}

void brdffit_samples_options(const brdffit_samples *samples, brdffit_sample_options *out)
{
    if (!out)
        return;
    if (samples)
        *out = samples->opt;
    else
        brdffit_sample_options_default(out);
}

/* Two geometries closer than this in every invariant are the same one. */
#define GEOM_TOL 1e-9

size_t bf_samples_geometries(const brdffit_samples *s, size_t need)
{
    /* the invariants of an isotropic, reciprocal BRDF's arguments: the two
     * cosines (in either order) and wi . wo */
    double seen[BF_GEOM_NEED_MAX][3];
    size_t found = 0;
    if (need > BF_GEOM_NEED_MAX)
        need = BF_GEOM_NEED_MAX;
    const double *d = s->data;
    size_t np = s->npad;
    for (size_t m = 0; m < s->n && found < need; m++) {
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
