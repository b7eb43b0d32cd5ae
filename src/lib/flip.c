/* SPDX-License-Identifier: MIT */
/* flip.c -- LDR FLIP (Andersson et al., "FLIP: A Difference Evaluator for
 * Alternating Images", HPG 2020), as NVIDIA's reference implementation
 * (github.com/NVlabs/flip, FLIP.h) computes it: sRGB -> linear -> YCxCz;
 * the colour pipeline (contrast sensitivity filters, separable, the
 * blue-yellow one as two Gaussians; clamp to the RGB cube; CIELab with the
 * Hunt adjustment; HyAB distance^q_c, redistributed to [0, 1]); the feature
 * pipeline (edges and points of the normalised Y by the first and second
 * derivatives of a Gaussian); their combination per pixel
 * colour^(1 - feature).  Single precision, as the reference; the mean is
 * summed in double.  brdffit_flip: include/brdffit.h. */
#include "internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define FLIP_QC 0.7f
#define FLIP_PC 0.4f
#define FLIP_PT 0.95f
#define FLIP_W 0.082f
#define FLIP_QF 0.5f
#define FLIP_PI 3.14159265358979f
/* Planes are rows of a multiple of FLIP_LANES floats (blocks the compiler vectorises). */
#define FLIP_LANES 8

/* ------------------------------------------------------------------ colour */

static float srgb_to_linear(float v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

static void linear_to_xyz(const float c[3], float x[3])
{
    x[0] = 10135552.0f / 24577794.0f * c[0] + 8788810.0f / 24577794.0f * c[1] +
           4435075.0f / 24577794.0f * c[2];
    x[1] = 2613072.0f / 12288897.0f * c[0] + 8788810.0f / 12288897.0f * c[1] +
           887015.0f / 12288897.0f * c[2];
    x[2] = 1425312.0f / 73733382.0f * c[0] + 8788810.0f / 73733382.0f * c[1] +
           70074185.0f / 73733382.0f * c[2];
}

static void xyz_to_linear(const float x[3], float c[3])
{
    c[0] = 3.241003275f * x[0] - 1.537398934f * x[1] - 0.498615861f * x[2];
    c[1] = -0.969224334f * x[0] + 1.875930071f * x[1] + 0.041554224f * x[2];
    c[2] = 0.055639423f * x[0] - 0.204011202f * x[1] + 1.057148933f * x[2];
}

static const float inv_white[3] = { 1.052156925f, 1.000000000f, 0.918357670f };
static const float white[3] = { 0.950428545f, 1.000000000f, 1.088900371f };

/* The cube root of t > 0: a guess from the float's bits, two Halley steps
 * in double (correct to float precision, without libm's frexp and scalbn). */
static float cube_root(float t)
{
    union { float f; uint32_t u; } g = { t };
    g.u = g.u / 3 + 709921077u;
    double x = t, y = g.f;
    for (int i = 0; i < 2; i++) {
        double y3 = y * y * y;
        y *= (y3 + 2 * x) / (2 * y3 + x);
    }
    return (float)y;
}

static float lab_f(float t)
{
    const float d = 6.0f / 29.0f, d3 = d * d * d;
    return t > d3 ? cube_root(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
}

/* Linear RGB (clamped to the unit cube) to Hunt-adjusted CIELab. */
static void linear_to_lab_hunt(const float c[3], float lab[3])
{
    float x[3];
    linear_to_xyz(c, x);
    float fx = lab_f(x[0] * inv_white[0]), fy = lab_f(x[1]), fz = lab_f(x[2] * inv_white[2]);
    float L = 116.0f * fy - 16.0f;
    lab[0] = L;
    lab[1] = 0.01f * L * (500.0f * (fx - fy));
    lab[2] = 0.01f * L * (200.0f * (fy - fz));
}

static float hyab(const float a[3], const float b[3])
{
    float da = a[1] - b[1], db = a[2] - b[2];
    return fabsf(a[0] - b[0]) + sqrtf(da * da + db * db);
}

/* cmax: the q_c-th power of the HyAB distance of green and blue. */
static float max_distance(void)
{
    static const float green[3] = { 0, 1, 0 }, blue[3] = { 0, 0, 1 };
    float g[3], b[3];
    linear_to_lab_hunt(green, g);
    linear_to_lab_hunt(blue, b);
    return powf(hyab(g, b), FLIP_QC);
}

/* ------------------------------------------------------------------ filters */

/* The separable contrast sensitivity filters: taps (2 r + 1) of Y, Cx and
 * the blue-yellow pair (a sum of two Gaussians, each split into square-root
 * factors, normalised together). */
typedef struct csf_filters {
    int r;
    float *y, *cx, *cz1, *cz2;
} csf_filters;

static float gauss_ab(float x2, float a, float b)
{
    return a * sqrtf(FLIP_PI / b) * expf(-FLIP_PI * FLIP_PI * x2 / b);
}

static float gauss_sqrt(float x2, float a, float b)
{
    return sqrtf(a * sqrtf(FLIP_PI / b)) * expf(-FLIP_PI * FLIP_PI * x2 / b);
}

static void csf_set(csf_filters *f, float ppd)
{
    float sy = 0, scx = 0, s1 = 0, s2 = 0, dx = 1.0f / ppd;
    int n = 2 * f->r + 1;
    for (int i = 0; i < n; i++) {
        float x = (float)(i - f->r) * dx, x2 = x * x;
        sy += f->y[i] = gauss_ab(x2, 1.0f, 0.0047f);
        scx += f->cx[i] = gauss_ab(x2, 1.0f, 0.0053f);
        s1 += f->cz1[i] = gauss_sqrt(x2, 34.1f, 0.04f);
        s2 += f->cz2[i] = gauss_sqrt(x2, 13.5f, 0.025f);
    }
    float nz = 1.0f / sqrtf(s1 * s1 + s2 * s2);
    for (int i = 0; i < n; i++) {
        f->y[i] /= sy;
        f->cx[i] /= scx;
        f->cz1[i] *= nz;
        f->cz2[i] *= nz;
    }
}

/* The feature filters: Gaussian g, first derivative dg, second ddg (2 r + 1
 * taps; dg's and ddg's positive taps sum to 1, their negative ones to -1). */
typedef struct feature_filters {
    int r;
    float *g, *dg, *ddg;
} feature_filters;

static void feature_set(feature_filters *f, float sd)
{
    int n = 2 * f->r + 1;
    float gs = 0, dp = 0, dn = 0, ddp = 0, ddn = 0;
    for (int i = 0; i < n; i++) {
        float x = (float)(i - f->r);
        float g = expf(-(x * x) / (2.0f * sd * sd));
        float dg = -x * g, ddg = (x * x / (sd * sd) - 1.0f) * g;
        gs += f->g[i] = g;
        f->dg[i] = dg;
        f->ddg[i] = ddg;
        if (dg > 0) dp += dg; else dn -= dg;
        if (ddg > 0) ddp += ddg; else ddn -= ddg;
    }
    for (int i = 0; i < n; i++) {
        f->g[i] /= gs;
        f->dg[i] /= f->dg[i] > 0 ? dp : dn;
        f->ddg[i] /= f->ddg[i] > 0 ? ddp : ddn;
    }
}

/* out[x] = sum_i k[i] in[clamp(x + i - r)], x < wp (a multiple of FLIP_LANES),
 * along a row of w values (pad: wp + 2 r floats of scratch). */
static void conv_row(const float *in, int w, int wp, const float *k, int r, float *restrict pad,
                     float *restrict out)
{
    for (int i = 0; i < wp + 2 * r; i++) {
        int x = i - r;
        pad[i] = in[x < 0 ? 0 : x >= w ? w - 1 : x];
    }
    memset(out, 0, sizeof(float) * (size_t)wp);
    for (int i = 0; i <= 2 * r; i++) {
        const float ki = k[i], *p = pad + i;
        for (int x = 0; x < wp; x += FLIP_LANES)
            for (int j = 0; j < FLIP_LANES; j++)
                out[x + j] += ki * p[x + j];
    }
}

/* Row y of the vertical convolution of plane in (h rows of w, a multiple of
 * FLIP_LANES) with k into out[w]. */
static void conv_col(const float *in, int w, int h, int y, const float *k, int r,
                     float *restrict out)
{
    memset(out, 0, sizeof(float) * (size_t)w);
    for (int i = 0; i <= 2 * r; i++) {
        int yy = y + i - r;
        const float ki = k[i];
        const float *restrict row = in + (size_t)(yy < 0 ? 0 : yy >= h ? h - 1 : yy) * (size_t)w;
        for (int x = 0; x < w; x += FLIP_LANES)
            for (int j = 0; j < FLIP_LANES; j++)
                out[x + j] += ki * row[x + j];
    }
}

/* ------------------------------------------------------------------ one image */

/* What FLIP compares of an image, planes of h rows of wp floats: the
 * Hunt-adjusted Lab of the filtered image (0..2), edge and point magnitudes
 * of its normalised Y (3, 4). */
#define FLIP_PLANES 5

struct brdffit_flip_ref {
    int w, h, wp;        /* wp: w rounded up to FLIP_LANES */
    float cmax;
    float code[256];     /* q / 255                                           */
    float lut[256];      /* srgb_to_linear(q / 255): 8-bit images without powf */
    csf_filters csf;
    feature_filters feat;
    float *view[FLIP_PLANES];
    float *block;        /* everything above, in one allocation */
};

typedef struct flip_work {
    const brdffit_flip_ref *R;
    float *ycc[3];       /* the image in YCxCz     */
    float *hor[4];       /* horizontal passes      */
    float *row[4];       /* one row of vertical passes */
    float *pad;          /* a padded row           */
    float *block;
} flip_work;

/* srgb_to_linear(v), from R's table when v is an 8-bit code q / 255. */
static float linear_of(const brdffit_flip_ref *R, float v)
{
    if (v >= 0 && v <= 1) {
        int q = (int)(v * 255.0f + 0.5f);
        if (R->code[q] == v)
            return R->lut[q];
    }
    return srgb_to_linear(v);
}

static void to_ycxcz(flip_work *k, const float *rgb, size_t stride)
{
    const brdffit_flip_ref *R = k->R;
    for (int y = 0; y < R->h; y++)
        for (int x = 0; x < R->w; x++) {
            const float *p = rgb + (size_t)y * stride + 3 * (size_t)x;
            float c[3] = { linear_of(R, p[0]), linear_of(R, p[1]), linear_of(R, p[2]) }, v[3];
            linear_to_xyz(c, v);
            size_t i = (size_t)y * (size_t)R->wp + (size_t)x;
            v[0] *= inv_white[0];
            v[2] *= inv_white[2];
            k->ycc[0][i] = 116.0f * v[1] - 16.0f;
            k->ycc[1][i] = 500.0f * (v[0] - v[1]);
            k->ycc[2][i] = 200.0f * (v[1] - v[2]);
        }
}

/* Horizontal pass of plane in with taps k (radius r) into out, every row. */
static void conv_rows(flip_work *k, const float *in, const float *taps, int r, float *out)
{
    const brdffit_flip_ref *R = k->R;
    for (int y = 0; y < R->h; y++)
        conv_row(in + (size_t)y * (size_t)R->wp, R->w, R->wp, taps, r, k->pad,
                 out + (size_t)y * (size_t)R->wp);
}

static void colour_view(flip_work *k, float *const view[FLIP_PLANES])
{
    const brdffit_flip_ref *R = k->R;
    int wp = R->wp, r = R->csf.r;
    const float *taps[4] = { R->csf.y, R->csf.cx, R->csf.cz1, R->csf.cz2 };
    for (int c = 0; c < 4; c++)
        conv_rows(k, k->ycc[c < 2 ? c : 2], taps[c], r, k->hor[c]);
    for (int y = 0; y < R->h; y++) {
        for (int c = 0; c < 4; c++)
            conv_col(k->hor[c], wp, R->h, y, taps[c], r, k->row[c]);
        for (int x = 0; x < R->w; x++) {
            float yy = (k->row[0][x] + 16.0f) / 116.0f;
            float xyz[3] = { (yy + k->row[1][x] / 500.0f) * white[0], yy,
                             (yy - (k->row[2][x] + k->row[3][x]) / 200.0f) * white[2] };
            float c[3], lab[3];
            xyz_to_linear(xyz, c);
            for (int i = 0; i < 3; i++)
                c[i] = c[i] < 0 ? 0 : c[i] > 1 ? 1 : c[i];
            linear_to_lab_hunt(c, lab);
            for (int i = 0; i < 3; i++)
                view[i][(size_t)y * (size_t)wp + (size_t)x] = lab[i];
        }
    }
}

static void feature_view(flip_work *k, float *const view[FLIP_PLANES])
{
    const brdffit_flip_ref *R = k->R;
    int wp = R->wp, r = R->feat.r;
    float *gray = k->ycc[1]; /* Cx is no longer needed: the normalised Y in its place */
    for (int y = 0; y < R->h; y++)
        for (int x = 0; x < R->w; x++) {
            size_t i = (size_t)y * (size_t)wp + (size_t)x;
            gray[i] = k->ycc[0][i] * (1.0f / 116.0f) + 16.0f / 116.0f;
        }
    conv_rows(k, gray, R->feat.dg, r, k->hor[0]);
    conv_rows(k, gray, R->feat.ddg, r, k->hor[1]);
    conv_rows(k, gray, R->feat.g, r, k->hor[2]);
    for (int y = 0; y < R->h; y++) {
        conv_col(k->hor[0], wp, R->h, y, R->feat.g, r, k->row[0]);   /* d/dx   */
        conv_col(k->hor[1], wp, R->h, y, R->feat.g, r, k->row[1]);   /* d2/dx2 */
        conv_col(k->hor[2], wp, R->h, y, R->feat.dg, r, k->row[2]);  /* d/dy   */
        conv_col(k->hor[2], wp, R->h, y, R->feat.ddg, r, k->row[3]); /* d2/dy2 */
        for (int x = 0; x < R->w; x++) {
            size_t i = (size_t)y * (size_t)wp + (size_t)x;
            view[3][i] = sqrtf(k->row[0][x] * k->row[0][x] + k->row[2][x] * k->row[2][x]);
            view[4][i] = sqrtf(k->row[1][x] * k->row[1][x] + k->row[3][x] * k->row[3][x]);
        }
    }
}

/* The scratch of one view: 3 + 4 planes, 4 rows, the padded row. */
static int work_alloc(flip_work *k, const brdffit_flip_ref *R)
{
    int rmax = R->csf.r > R->feat.r ? R->csf.r : R->feat.r;
    size_t n = (size_t)R->wp * (size_t)R->h;
    float *p = calloc(7 * n + 5 * (size_t)R->wp + 2 * (size_t)rmax, sizeof(float));
    k->R = R;
    k->block = p;
    if (!p)
        return -1;
    for (int i = 0; i < 3; i++, p += n)
        k->ycc[i] = p;
    for (int i = 0; i < 4; i++, p += n)
        k->hor[i] = p;
    for (int i = 0; i < 4; i++, p += R->wp)
        k->row[i] = p;
    k->pad = p;
    return 0;
}

static brdffit_status make_view(const brdffit_flip_ref *R, const float *rgb, size_t stride,
                                float *const view[FLIP_PLANES], brdffit_error *err)
{
    flip_work k;
    if (work_alloc(&k, R) != 0)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_flip: no memory for %d x %d pixels",
                       R->w, R->h);
    to_ycxcz(&k, rgb, stride);
    colour_view(&k, view);
    feature_view(&k, view);
    free(k.block);
    return BRDFFIT_OK;
}

/* ------------------------------------------------------------------ the API */

static brdffit_status check_image(const float *img, int w, int h, size_t stride, const char *name,
                                  brdffit_error *err)
{
    if (!img)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_flip: %s is NULL", name);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < 3 * w; x++)
            if (!isfinite(img[(size_t)y * stride + (size_t)x]))
                return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                               "brdffit_flip: %s pixel (col %d, row %d) channel %c is not finite",
                               name, x / 3, y, "RGB"[x % 3]);
    return BRDFFIT_OK;
}

/* The filters and view planes of R, in one block. */
static int ref_alloc(brdffit_flip_ref *R, int w, int h, float ppd)
{
    const float maxb = 0.04f; /* the largest scale parameter of the CSFs (blue-yellow b1) */
    R->w = w;
    R->h = h;
    R->wp = (w + FLIP_LANES - 1) / FLIP_LANES * FLIP_LANES;
    R->csf.r = (int)ceilf(3.0f * sqrtf(maxb / (2.0f * FLIP_PI * FLIP_PI)) * ppd);
    float sd = 0.5f * FLIP_W * ppd;
    R->feat.r = (int)ceilf(3.0f * sd);
    size_t n = (size_t)R->wp * (size_t)h, nc = 2 * (size_t)R->csf.r + 1,
           nf = 2 * (size_t)R->feat.r + 1;
    float *p = calloc(FLIP_PLANES * n + 4 * nc + 3 * nf, sizeof(float));
    R->block = p;
    if (!p)
        return -1;
    for (int i = 0; i < FLIP_PLANES; i++, p += n)
        R->view[i] = p;
    float **ct[4] = { &R->csf.y, &R->csf.cx, &R->csf.cz1, &R->csf.cz2 };
    for (int i = 0; i < 4; i++, p += nc)
        *ct[i] = p;
    float **ft[3] = { &R->feat.g, &R->feat.dg, &R->feat.ddg };
    for (int i = 0; i < 3; i++, p += nf)
        *ft[i] = p;
    csf_set(&R->csf, ppd);
    feature_set(&R->feat, sd);
    R->cmax = max_distance();
    for (int q = 0; q < 256; q++)
        R->lut[q] = srgb_to_linear(R->code[q] = (float)q / 255.0f);
    return 0;
}

brdffit_status brdffit_flip_ref_create(const float *ref, int width, int height, size_t stride,
                                       double ppd, brdffit_flip_ref **out, brdffit_error *err)
{
    static const char fn[] = "brdffit_flip";
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s: %d x %d pixels (each must be in 1..65536)", fn, width, height);
    if (stride == 0)
        stride = 3 * (size_t)width;
    if (stride < 3 * (size_t)width)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s: stride %zu floats is less than a row's 3 x %d", fn, stride, width);
    if (ppd == 0)
        ppd = BRDFFIT_FLIP_PPD;
    if (!(ppd >= 1 && ppd <= 1000))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s: %g pixels per degree (must be in 1..1000, or 0: the default)", fn, ppd);
    brdffit_status st = check_image(ref, width, height, stride, "ref", err);
    if (st != BRDFFIT_OK)
        return st;
    brdffit_flip_ref *R = calloc(1, sizeof *R);
    if (!R || ref_alloc(R, width, height, (float)ppd) != 0) {
        brdffit_flip_ref_free(R);
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "%s: no memory for %d x %d pixels", fn, width,
                       height);
    }
    st = make_view(R, ref, stride, R->view, err);
    if (st != BRDFFIT_OK) {
        brdffit_flip_ref_free(R);
        return st;
    }
    *out = R;
    bf_ok(err);
    return BRDFFIT_OK;
}

void brdffit_flip_ref_free(brdffit_flip_ref *ref)
{
    if (ref)
        free(ref->block);
    free(ref);
}

static float flip_pixel(const float *const a[FLIP_PLANES], const float *const b[FLIP_PLANES],
                        size_t i, float cmax)
{
    float la[3] = { a[0][i], a[1][i], a[2][i] }, lb[3] = { b[0][i], b[1][i], b[2][i] };
    float pccmax = FLIP_PC * cmax, c = powf(hyab(la, lb), FLIP_QC);
    c = c < pccmax ? c * (FLIP_PT / pccmax)
                   : FLIP_PT + (c - pccmax) / (cmax - pccmax) * (1.0f - FLIP_PT);
    float de = fabsf(a[3][i] - b[3][i]), dp = fabsf(a[4][i] - b[4][i]);
    float f = sqrtf((de > dp ? de : dp) * 0.70710678f); /* q_f = 0.5 */
    return powf(c, 1.0f - f);
}

brdffit_status brdffit_flip_compare(const brdffit_flip_ref *ref, const float *test, size_t stride,
                                    float *map, double *mean, brdffit_error *err)
{
    if (!ref || !mean)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_flip: %s is NULL",
                       !ref ? "ref" : "mean");
    *mean = 0;
    if (stride == 0)
        stride = 3 * (size_t)ref->w;
    if (stride < 3 * (size_t)ref->w)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "brdffit_flip: stride %zu floats is less than a row's 3 x %d", stride,
                       ref->w);
    brdffit_status st = check_image(test, ref->w, ref->h, stride, "test", err);
    if (st != BRDFFIT_OK)
        return st;
    size_t n = (size_t)ref->wp * (size_t)ref->h;
    float *block = calloc(FLIP_PLANES * n, sizeof(float));
    if (!block)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_flip: no memory for %d x %d pixels",
                       ref->w, ref->h);
    float *view[FLIP_PLANES];
    for (int i = 0; i < FLIP_PLANES; i++)
        view[i] = block + (size_t)i * n;
    st = make_view(ref, test, stride, view, err);
    double sum = 0;
    for (int y = 0; st == BRDFFIT_OK && y < ref->h; y++)
        for (int x = 0; x < ref->w; x++) {
            float e = flip_pixel((const float *const *)ref->view, (const float *const *)view,
                                 (size_t)y * (size_t)ref->wp + (size_t)x, ref->cmax);
            sum += e;
            if (map)
                map[(size_t)y * (size_t)ref->w + (size_t)x] = e;
        }
    free(block);
    if (st != BRDFFIT_OK)
        return st;
    *mean = sum / ((double)ref->w * (double)ref->h);
    bf_ok(err);
    return BRDFFIT_OK;
}

brdffit_status brdffit_flip(const float *ref, const float *test, int width, int height,
                            size_t stride, double ppd, float *map, double *mean,
                            brdffit_error *err)
{
    brdffit_flip_ref *R;
    if (!mean)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_flip: mean is NULL");
    *mean = 0;
    brdffit_status st = brdffit_flip_ref_create(ref, width, height, stride, ppd, &R, err);
    if (st != BRDFFIT_OK)
        return st;
    st = brdffit_flip_compare(R, test, stride, map, mean, err);
    brdffit_flip_ref_free(R);
    return st;
}
