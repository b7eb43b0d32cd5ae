/* SPDX-License-Identifier: MIT */
/* render_files.h -- one material's renders and incidence-plane plots as
 * files in a directory: what `brdffit render`, `brdffit plot` and the batch
 * write.
 *
 *   render_files.c  rf_write_material: the renders, difference images,
 *                   plots and renders.json of a table and its fitted models
 *   plot_svg.c      plot_write_svg: one incidence-plane plot
 *
 * Files written into dir (STEM is the model's name, "ward", unless the fit
 * names another):
 *   reference.exr, reference.png       the measured table (EXR: linear RGBA,
 *                                      A the coverage; PNG: sRGB, 8-bit)
 *   STEM.exr, STEM.png                 each model at its parameters
 *   STEM-diff.png                      L*(model PNG) - L*(reference PNG),
 *                                      blue-white-red, one scale per material
 *   STEM-flip.png                      FLIP of the model PNG against the
 *                                      reference PNG (magma)
 *   diff-scale.svg, flip-scale.svg     the colour bars of the two
 *   renders.json                       exposure, difference scale, image
 *                                      error of every model, lights, settings
 *   plot-measured.svg                  the measured curves alone
 *   plot-STEM.svg                      measured (solid) and model (dashed)
 * Display conventions: one exposure per material, chosen from the reference
 * (tm_auto_exposure: 1 / the 99th percentile of max(R, G, B) over the sphere)
 * unless given; PNG = sRGB transfer curve of exposure x radiance, clamped,
 * 8-bit.  Reference pixels with masked lookups take the mean of the measured
 * pixels within 2 pixels (ci_fill_masked; in every image but reference.exr,
 * which keeps A = 0.5); any with none stay grey in the difference images.
 * Difference: CIE L* of the model's PNG minus the reference's, full scale the 95th percentile of |dL*|
 * over all models' covered pixels rounded up to 1, 1.5, 2, 3, 5, 7 x 10^k
 * (ci_diff_scale), background black.  Image error: the mean FLIP of the
 * model's PNG against the reference's (brdffit_flip). */
#ifndef BRDFFIT_RENDER_FILES_H
#define BRDFFIT_RENDER_FILES_H

#include "brdffit.h"
#include "outdir.h"

#include <stddef.h>

#define RF_MAX_FITS 16
#define RF_MAX_FILES (6 + 5 * RF_MAX_FITS)

typedef struct rf_fit {
    brdffit_model model;
    brdffit_params params;
    double error;        /* its Error (ngan-l2) for captions and titles; NAN: not known */
    const char *stem;    /* file-name stem; NULL: the model's name ("ward")             */
    const char *label;   /* caption label; NULL: the model's title ("Ward")             */
} rf_fit;

typedef enum rf_kind { RF_IMAGE = 0, RF_PLOT = 1, RF_DATA = 2 } rf_kind;

typedef struct rf_file {
    char file[128];      /* its name inside dir                                 */
    char caption[256];   /* "Ward: 0.0562", "Reference (measured)", ...        */
    rf_kind kind;        /* PNG, SVG, or EXR / JSON                             */
    int fit;             /* index into fits; -1: the reference / measured data  */
} rf_file;

typedef struct rf_settings {
    int render, plot;                  /* what to write; default both               */
    brdffit_render_options render_opt; /* default brdffit_render_options_default    */
    brdffit_curve_options curve_opt;   /* default brdffit_curve_options_default     */
    double exposure;                   /* 0 (default): chosen from the reference    */
    const char *env_file;              /* recorded in renders.json; NULL: none      */
} rf_settings;

/* Defaults: render and plot, default options, scale = scale for both. */
void rf_settings_default(rf_settings *s, brdffit_scale scale);

typedef struct rf_result {
    double exposure;                  /* of every PNG of the material              */
    double diff_scale;                /* L* at full scale of the difference images */
    double image_error[RF_MAX_FITS];  /* per fit: mean FLIP of its PNG; NAN: not made */
    double relative_rms[RF_MAX_FITS]; /* per fit: brdffit_image_error; NAN where undefined */
    size_t covered, masked;           /* reference pixels with A = 1 / masked, as rendered */
    size_t filled;                    /* masked pixels filled from covered neighbours */
    double seconds_render, seconds_plot;
    rf_file files[RF_MAX_FILES];      /* every file written, in order              */
    int nfiles;
} rf_result;

/* Write the renders (s->render) and plots (s->plot) of a material's table and
 * its nfits (0..RF_MAX_FITS) fits into the directory dir (made when missing:
 * its parent must exist; od_open).  out may be NULL.  0, or -1 with err naming the file and why
 * (BRDFFIT_E_FILE_WRITE for a directory or file that cannot be written, the
 * library's status for bad parameters or options). */
int rf_write_material(const char *dir, const char *material, const brdffit_table *table,
                      const rf_fit *fits, int nfits, const rf_settings *s, rf_result *out,
                      brdffit_error *err);

/* The same into a directory already open (outdir.h), written with out_file. */
int rf_write_material_at(const out_dir *dir, const char *material, const brdffit_table *table,
                         const rf_fit *fits, int nfits, const rf_settings *s, rf_result *out,
                         brdffit_error *err);

/* ---- plot_svg.c ---- */

/* The plotted y of a point: cube root of the mean of R, G, B; -1 when a
 * channel is masked (negative), so the point is left out. */
double plot_value(const double rgb[3]);

/* One plot, the file name in dir (written whole): the curves of o (theta_o
 * from brdffit_curve_theta_o), measured solid and, when model is not NULL,
 * the model dashed; title at the top and in <title>.  0 or -1 with err. */
int plot_write_svg(const out_dir *dir, const char *name, const char *title, const brdffit_curve_options *o,
                   const double *theta_o, const double *measured, const double *model,
                   size_t stride, brdffit_error *err);

#endif
