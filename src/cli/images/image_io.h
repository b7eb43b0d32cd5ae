/* SPDX-License-Identifier: MIT */
/* image_io.h -- image files of the program: OpenEXR (OpenEXR's C API) and PNG
 * (libpng), and the transfer from linear radiance to display values.
 *
 *   exr_io.c    linear RGBA float EXR out; RGB (half, float or uint) EXR in
 *   png_io.c    8-bit RGB PNG out
 *   tonemap.c   exposure, the sRGB transfer curve
 *   colour_maps.c  magma and the blue-white-red diverging map
 *   compare_images.c  masked pixels filled, signed lightness differences, FLIP maps, colour bars
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

/* ---- colour_maps.c ---- */

/* Magma (NVIDIA's FLIP tool's error-map colours) of v in [0, 1] (clamped). */
void cm_magma(double v, unsigned char rgb[3]);
/* The blue-white-red diverging map (ColorBrewer RdBu) of t in [-1, 1]
 * (clamped): -1 dark blue, 0 white, +1 dark red. */
void cm_diverging(double t, unsigned char rgb[3]);

/* ---- compare_images.c ---- */

/* Reference pixels whose lookups met a masked bin (A = BRDFFIT_COVERAGE_MASKED)
 * take the mean RGB of the measured pixels (A = 1) among their 8 neighbours,
 * or failing that within 2 pixels, and A = 1; the count of such pixels is
 * returned.  Others keep their A.  rgba: n x n, stride 4 n. */
size_t ci_fill_masked(float *rgba, int n);

/* CIE L* (0..100) of each 8-bit sRGB pixel of the display image rgb8 (n x n)
 * where the reference rgba is covered (A = 1), NaN elsewhere, into l. */
void ci_lightness(const unsigned char *rgb8, const float *ref_rgba, int n, float *l);

/* The full scale of the signed difference images: the 95th percentile of
 * |dl| over the count finite values of dl, rounded up to the next of 1, 1.5,
 * 2, 3, 5, 7 times a power of ten, in [1, 100] (1 when there is none). */
double ci_diff_scale(const float *dl, size_t count);

/* The signed difference image of dl = L*(model) - L*(reference): the
 * diverging map of dl / scale where the reference is covered; black off the
 * sphere (A = 0); grey (128, 128, 128) where the reference stays masked. */
void ci_diff_image(const float *dl, const float *ref_rgba, int n, double scale, unsigned char *rgb);

/* The FLIP map (n x n values in [0, 1]) in magma. */
void ci_flip_image(const float *map, int n, unsigned char *rgb);

/* The colour bars of the comparison images, SVG files in dir:
 * diff-scale.svg (-scale..+scale L*, darker / brighter) and flip-scale.svg
 * (FLIP 0..1, magma).  0 or -1 with err. */
int ci_write_bars(const out_dir *dir, double scale, brdffit_error *err);

#endif
