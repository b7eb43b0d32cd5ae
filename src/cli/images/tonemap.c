/* SPDX-License-Identifier: MIT */
/* tonemap.c -- linear radiance to 8-bit display values: the exposure rule,
 * the sRGB transfer curve. */
#include "image_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

unsigned char tm_srgb8(double v)
{
    if (!(v > 0))
        return 0;
    if (v >= 1)
        return 255;
    double e = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (unsigned char)lrint(e * 255.0);
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

double tm_auto_exposure(const float *rgba, int width, int height, size_t stride)
{
    if (stride == 0)
        stride = 4 * (size_t)width;
    size_t n = 0;
    float *v = malloc(sizeof(float) * (size_t)width * (size_t)height);
    if (!v)
        return 1.0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const float *p = rgba + (size_t)y * stride + 4 * (size_t)x;
            if (p[3] > 0)
                v[n++] = fmaxf(p[0], fmaxf(p[1], p[2]));
        }
    double e = 1.0;
    if (n > 0) {
        qsort(v, n, sizeof *v, cmp_float);
        size_t k = (size_t)floor(0.99 * (double)(n - 1));
        if (v[k] > 0 && isfinite(v[k]))
            e = 1.0 / v[k];
    }
    free(v);
    return e;
}

void tm_to_srgb8(const float *rgba, int width, int height, size_t stride, double exposure,
                 unsigned char *rgb)
{
    if (stride == 0)
        stride = 4 * (size_t)width;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const float *p = rgba + (size_t)y * stride + 4 * (size_t)x;
            unsigned char *q = rgb + 3 * ((size_t)y * (size_t)width + (size_t)x);
            for (int c = 0; c < 3; c++)
                q[c] = p[3] > 0 ? tm_srgb8(exposure * p[c]) : 0;
        }
}
