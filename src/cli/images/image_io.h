/* SPDX-License-Identifier: MIT */
/* image_io.h -- image files of the program: OpenEXR (OpenEXR's C API) and PNG
 * (libpng), and the transfer from linear radiance to display values.
 *
 *   exr_io.c    linear RGBA float EXR out; RGB (half, float or uint) EXR in
 *   png_io.c    8-bit RGB PNG out
 *   tonemap.c   exposure, the sRGB transfer curve, the difference false colour
 *
 * Files are written whole into an open directory (outdir.h: a temporary
 * renamed over the name; no link followed).
 * Failures fill a brdffit_error (status BRDFFIT_E_FILE_*) with the path and
 * the reason, and return -1; nothing is printed. */
#ifndef BRDFFIT_IMAGE_IO_H
#define BRDFFIT_IMAGE_IO_H

#include "brdffit.h"
#include "outdir.h"

#include <stddef.h>

/* ---- exr_io.c ---- */

/* Write width x height RGBA float pixels (stride floats from one row to the
 * next, 0: 4 width; row 0 at the top) as a scanline OpenEXR file with
 * channels R, G, B, A (32-bit float, RLE compression), name in dir.  0 or -1. */
int exr_write_rgba(const out_dir *dir, const char *name, const float *rgba, int width, int height,
                   size_t stride, brdffit_error *err);

/* Read an OpenEXR file's R, G, B channels (half, float or uint; one part,
 * scanline or tiled, any size; a file with only Y is read as grey) into a new
 * buffer of width x height x 3 floats, row 0 at the top of the data window.
 * Non-finite values are refused (the texel is named).  Free *rgb with free().
 * When rgba is not NULL also the A channel (1 where absent) is returned in a
 * second buffer of width x height floats.  0 or -1. */
int exr_read_rgb(const char *path, float **rgb, float **alpha, int *width, int *height,
                 brdffit_error *err);

/* ---- png_io.c ---- */

/* Write width x height 8-bit RGB pixels (3 width bytes a row, row 0 at the
 * top), name in dir. */
int png_write_rgb8(const out_dir *dir, const char *name, const unsigned char *rgb, int width,
                   int height, brdffit_error *err);

/* ---- tonemap.c ---- */

/* The sRGB transfer curve (IEC 61966-2-1) of a linear value clamped to [0, 1],
 * as an 8-bit code (rounded). */
unsigned char tm_srgb8(double linear);

/* The exposure rule: 1 / (the 99th percentile of max(R, G, B) over the pixels
 * of rgba with A > 0), so that 1% of the sphere may clip to white; 1 when
 * that is 0 (a black reference). */
double tm_auto_exposure(const float *rgba, int width, int height, size_t stride);

/* rgba (linear) to 8-bit RGB: sRGB(exposure x value) per channel; pixels with
 * A = 0 (off the sphere) are black. */
void tm_to_srgb8(const float *rgba, int width, int height, size_t stride, double exposure,
                 unsigned char *rgb);

/* The difference image: per pixel e = max_c |img_c - ref_c| / scale, clamped
 * to [0, 1], through a false-colour map (black 0 -> blue -> red -> yellow ->
 * white 1); off the sphere black; where ref is masked (A not 1) grey
 * (128, 128, 128). */
void tm_difference8(const float *ref, const float *img, int width, int height, size_t stride,
                    double scale, unsigned char *rgb);
/* The false colour of e in [0, 1] into rgb[3] (the difference images' map). */
void tm_false_colour(double e, unsigned char rgb[3]);

#endif
