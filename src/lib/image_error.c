/* SPDX-License-Identifier: MIT */
/* image_error.c -- the relative RMS difference of two renders over the
 * pixels the reference covers (brdffit_image_error; include/brdffit.h). */
#include "internal.h"

#include <math.h>
#include <stddef.h>

/* The first covered pixel (ref A = 1) with a non-finite channel in ref or img. */
static brdffit_status fail_nonfinite(const float *ref, const float *img, int width, int height,
                                     size_t stride, brdffit_error *err)
{
    for (int row = 0; row < height; row++)
        for (int col = 0; col < width; col++) {
            const float *a = ref + (size_t)row * stride + 4 * (size_t)col;
            const float *b = img + (size_t)row * stride + 4 * (size_t)col;
            for (int c = 0; c < 3 && a[3] == 1.0f; c++)
                if (!isfinite(a[c]) || !isfinite(b[c]))
                    return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                                   "brdffit_image_error: %s pixel (col %d, row %d) channel %c = %g",
                                   isfinite(a[c]) ? "img" : "ref", col, row, "RGB"[c],
                                   isfinite(a[c]) ? (double)b[c] : (double)a[c]);
        }
    return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                   "brdffit_image_error: the squared differences overflow a double");
}

brdffit_status brdffit_image_error(const float *ref, const float *img, int width, int height,
                                   size_t stride, double *error, size_t *covered,
                                   brdffit_error *err)
{
    static const char fn[] = "brdffit_image_error";
    if (!ref || !img || !error)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: %s is NULL", fn,
                       !ref ? "ref" : !img ? "img" : "error");
    if (width < 1 || height < 1)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: %d x %d pixels (both must be >= 1)",
                       fn, width, height);
    if (stride == 0)
        stride = 4 * (size_t)width;
    if (stride < 4 * (size_t)width)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s: stride %zu floats is less than a row's 4 x %d", fn, stride, width);
    double sd = 0, sr = 0;
    size_t n = 0;
    for (int row = 0; row < height; row++) {
        const float *a = ref + (size_t)row * stride, *b = img + (size_t)row * stride;
        for (int col = 0; col < width; col++, a += 4, b += 4) {
            if (a[3] != 1.0f)
                continue;
            n++;
            for (int c = 0; c < 3; c++) {
                double d = (double)b[c] - (double)a[c];
                sd += d * d;
                sr += (double)a[c] * (double)a[c];
            }
        }
    }
    if (covered)
        *covered = n;
    *error = 0;
    if (!isfinite(sd) || !isfinite(sr))
        return fail_nonfinite(ref, img, width, height, stride, err);
    if (n == 0)
        return bf_fail(err, BRDFFIT_E_NO_SAMPLES,
                       "%s: no pixel of the reference is covered (A = 1)", fn);
    if (!(sr > 0))
        return bf_fail(err, BRDFFIT_E_NO_SAMPLES,
                       "%s: the reference is black on all %zu covered pixels", fn, n);
    *error = sqrt(sd / sr);
    bf_ok(err);
    return BRDFFIT_OK;
}
