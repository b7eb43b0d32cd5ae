/* SPDX-License-Identifier: MIT */
/* compare_images.c -- what the comparison images of a material are made of:
 * the reference's masked pixels filled from covered neighbours, the signed
 * lightness difference of a model's PNG from the reference's, its shared
 * full scale, the FLIP map in magma, and the colour bars saying what the
 * colours mean (image_io.h). */
#include "image_io.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Fill the masked pixels with a measured pixel (A = 1) within r (a square
 * of side 2 r + 1) with their mean, marked A = -1; the count filled. */
static size_t fill_pass(float *rgba, int n, int r)
{
    size_t filled = 0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            float *p = rgba + 4 * ((size_t)y * (size_t)n + (size_t)x);
            if (p[3] != BRDFFIT_COVERAGE_MASKED)
                continue;
            double s[3] = { 0, 0, 0 };
            int k = 0;
            for (int yy = y - r; yy <= y + r; yy++)
                for (int xx = x - r; xx <= x + r; xx++) {
                    if (yy < 0 || yy >= n || xx < 0 || xx >= n)
                        continue;
                    const float *q = rgba + 4 * ((size_t)yy * (size_t)n + (size_t)xx);
                    if (q[3] != 1.0f)
                        continue; /* measured values only, never a filled one */
                    for (int c = 0; c < 3; c++)
                        s[c] += q[c];
                    k++;
                }
            if (k == 0)
                continue;
            for (int c = 0; c < 3; c++)
                p[c] = (float)(s[c] / k);
            p[3] = -1.0f;
            filled++;
        }
    return filled;
}

size_t ci_fill_masked(float *rgba, int n)
{
    size_t filled = fill_pass(rgba, n, 1);
    filled += fill_pass(rgba, n, 2);
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++)
        if (rgba[4 * i + 3] == -1.0f)
            rgba[4 * i + 3] = 1.0f;
    return filled;
}

/* CIE L* of an 8-bit sRGB code triple (D65 white, Y of linear sRGB). */
static float lightness8(const unsigned char *q, const float lin[256])
{
    double Y = 0.2126 * lin[q[0]] + 0.7152 * lin[q[1]] + 0.0722 * lin[q[2]];
    double f = Y > 216.0 / 24389.0 ? cbrt(Y) : (24389.0 / 27.0 * Y + 16.0) / 116.0;
    return (float)(116.0 * f - 16.0);
}

void ci_lightness(const unsigned char *rgb8, const float *ref_rgba, int n, float *l)
{
    float lin[256];
    for (int i = 0; i < 256; i++) {
        double v = i / 255.0;
        lin[i] = (float)(v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
    }
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++)
        l[i] = ref_rgba[4 * i + 3] == 1.0f ? lightness8(rgb8 + 3 * i, lin) : NAN;
}

#define HIST_BINS 10001 /* |dL*| in steps of 0.01 up to 100, and one for more */

double ci_diff_scale(const float *dl, size_t count)
{
    unsigned *hist = calloc(HIST_BINS, sizeof *hist);
    size_t m = 0;
    for (size_t i = 0; hist && i < count; i++)
        if (isfinite(dl[i])) {
            double b = fabs((double)dl[i]) * 100.0;
            hist[b < HIST_BINS - 1 ? (size_t)b : HIST_BINS - 1]++;
            m++;
        }
    double p = 0; /* the 95th percentile (rank floor(0.95 (m - 1))), to the bin's upper edge */
    if (m > 0 && hist) {
        size_t rank = (size_t)floor(0.95 * (double)(m - 1)), seen = 0, k = 0;
        while ((seen += hist[k]) <= rank)
            k++;
        p = (double)(k + 1) / 100.0;
    }
    free(hist);
    static const double nice[] = { 1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100 };
    for (size_t k = 0; k < sizeof nice / sizeof nice[0]; k++)
        if (p <= nice[k])
            return nice[k];
    return 100;
}

void ci_diff_image(const float *dl, const float *ref_rgba, int n, double scale, unsigned char *rgb)
{
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++) {
        unsigned char *q = rgb + 3 * i;
        float a = ref_rgba[4 * i + 3];
        if (a == 0)
            q[0] = q[1] = q[2] = 0;
        else if (a != 1.0f || !isfinite(dl[i]))
            q[0] = q[1] = q[2] = 128;
        else
            cm_diverging(dl[i] / scale, q);
    }
}

void ci_flip_image(const float *map, int n, unsigned char *rgb)
{
    for (size_t i = 0; i < (size_t)n * (size_t)n; i++)
        cm_magma(map[i], rgb + 3 * i);
}

/* ------------------------------------------------------------------ colour bars */

#define BAR_W 360.0
#define BAR_H 74.0
#define BAR_X 20.0
#define BAR_LEN 320.0
#define BAR_STEPS 64

typedef void (*colour_fn)(double t, unsigned char rgb[3]);

/* A bar of BAR_STEPS rectangles coloured by map over t in [t0, t1], ticks at
 * the given values with their labels, a title above and end labels below. */
static int write_bar(const out_dir *dir, const char *name, const char *title, colour_fn map,
                     double t0, double t1, const double *ticks, const char *const *labels,
                     int nticks, const char *left, const char *right, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, name, err) != 0)
        return -1;
    xml_writer w;
    svg_begin(&w, o.f, BAR_W, BAR_H);
    xml_element_text(&w, "title", title);
    svg_text(&w, BAR_W / 2, 13, "middle", 12, title);
    for (int k = 0; k < BAR_STEPS; k++) {
        unsigned char c[3];
        char fill[16];
        map(t0 + (t1 - t0) * (k + 0.5) / BAR_STEPS, c);
        snprintf(fill, sizeof fill, "#%02x%02x%02x", c[0], c[1], c[2]);
        svg_rect(&w, BAR_X + BAR_LEN * k / BAR_STEPS, 20, BAR_LEN / BAR_STEPS + 0.3, 18, fill, NULL);
    }
    svg_rect(&w, BAR_X, 20, BAR_LEN, 18, "none", "#000");
    for (int k = 0; k < nticks; k++) {
        double x = BAR_X + BAR_LEN * (ticks[k] - t0) / (t1 - t0);
        svg_line(&w, x, 38, x, 43, "#000", 1, NULL);
        svg_text(&w, x, 54, "middle", 11, labels[k]);
    }
    svg_text(&w, BAR_X, 70, "start", 11, left);
    svg_text(&w, BAR_X + BAR_LEN, 70, "end", 11, right);
    if (svg_end(&w) != 0 && !ferror(o.f)) {
        out_abandon(&o);
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "%.1800s: cannot write the SVG", o.path);
        return -1;
    }
    return out_commit(&o, err);
}

static void diverging_bar(double t, unsigned char rgb[3])
{
    cm_diverging(t, rgb);
}

static void magma_bar(double t, unsigned char rgb[3])
{
    cm_magma(t, rgb);
}

int ci_write_bars(const out_dir *dir, double scale, brdffit_error *err)
{
    double dt[5] = { -1, -0.5, 0, 0.5, 1 };
    char lab[5][32];
    const char *dl[5];
    for (int k = 0; k < 5; k++) {
        snprintf(lab[k], sizeof lab[k], "%+g", dt[k] * scale);
        dl[k] = k == 2 ? "0" : lab[k];
    }
    static const double ft[5] = { 0, 0.25, 0.5, 0.75, 1 };
    static const char *const fl[5] = { "0", "0.25", "0.5", "0.75", "1" };
    if (write_bar(dir, "diff-scale.svg",
                  "\xce\x94L* = L*(model) \xe2\x88\x92 L*(reference) of the PNGs", diverging_bar,
                  -1, 1, dt, dl, 5, "\xe2\x86\x90 model darker", "model brighter \xe2\x86\x92",
                  err) != 0)
        return -1;
    return write_bar(dir, "flip-scale.svg", "\xea\x9f\xbbLIP (NVIDIA, LDR, 67 pixels per degree)",
                     magma_bar, 0, 1, ft, fl, 5, "no visible difference", "most different", err);
}
