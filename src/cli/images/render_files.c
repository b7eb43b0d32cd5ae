/* SPDX-License-Identifier: MIT */
/* render_files.c -- a material's renders (EXR + PNG), difference images,
 * incidence-plane plots (SVG) and renders.json in one directory.  What the
 * files are and the display conventions: render_files.h. */
#define _POSIX_C_SOURCE 200809L
#include "render_files.h"
#include "cli.h"
#include "image_io.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void rf_settings_default(rf_settings *s, brdffit_scale scale)
{
    memset(s, 0, sizeof *s);
    s->render = 1;
    s->plot = 1;
    brdffit_render_options_default(&s->render_opt);
    brdffit_curve_options_default(&s->curve_opt);
    s->render_opt.scale = scale;
    s->curve_opt.scale = scale;
}

/* ------------------------------------------------------------------ helpers */

/* err gets st and the message (truncated to fit); returns -1. */
static int failf(brdffit_error *err, brdffit_status st, const char *fmt, ...) CLI_PRINTF(3, 4);
static int failf(brdffit_error *err, brdffit_status st, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        err->status = st;
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* s into buf[len], cut at len - 1 bytes. */
static void copy_text(char *buf, size_t len, const char *s)
{
    size_t n = strlen(s);
    if (n >= len)
        n = len - 1;
    memcpy(buf, s, n);
    buf[n] = '\0';
}

static void add_file(rf_result *r, const char *file, const char *caption, rf_kind kind, int fit)
{
    if (r->nfiles >= RF_MAX_FILES)
        return;
    rf_file *f = &r->files[r->nfiles++];
    copy_text(f->file, sizeof f->file, file);
    copy_text(f->caption, sizeof f->caption, caption);
    f->kind = kind;
    f->fit = fit;
}

static const char *stem_of(const rf_fit *f)
{
    return f->stem ? f->stem : brdffit_model_get(f->model)->name;
}

static const char *label_of(const rf_fit *f)
{
    return f->label ? f->label : brdffit_model_get(f->model)->title;
}

/* "Ward: 0.0562" (the paper's caption), or "Ward" when the Error is unknown. */
static void caption_of(const rf_fit *f, char *buf, size_t len)
{
    if (isfinite(f->error))
        snprintf(buf, len, "%s: %.3g", label_of(f), f->error);
    else
        snprintf(buf, len, "%s", label_of(f));
}

/* ------------------------------------------------------------------ renders */

typedef struct render_job {
    const out_dir *dir;
    int n;                   /* image width = height */
    float *ref, *img;        /* RGBA, 4 n^2 floats each (ref: masked pixels filled) */
    const float *raw;        /* the reference as rendered (relative_rms: its covered pixels) */
    unsigned char *rgb8;     /* 3 n^2 */
    rf_result *r;
    brdffit_error *err;
    const float *ref_l;      /* the reference PNG's L* (ci_lightness)             */
    float *dl;               /* n^2 per fit: L*(model) - L*(reference)            */
    const brdffit_flip_ref *flip; /* the reference PNG for FLIP                   */
    float *work;             /* 5 n^2: the model's L*, its PNG as floats, FLIP map */
} render_job;

/* name.exr (linear RGBA). */
static int write_exr(render_job *j, const float *rgba, const char *stem, const char *caption,
                     int fit)
{
    char name[160];
    snprintf(name, sizeof name, "%s.exr", stem);
    if (exr_write_rgba(j->dir, name, rgba, j->n, j->n, 0, j->err) != 0)
        return -1;
    add_file(j->r, name, caption, RF_DATA, fit);
    return 0;
}

/* name.png (display) of rgba, left in j->rgb8. */
static int write_png(render_job *j, const float *rgba, const char *stem, const char *caption,
                     int fit)
{
    char name[160];
    tm_to_srgb8(rgba, j->n, j->n, 0, j->r->exposure, j->rgb8);
    snprintf(name, sizeof name, "%s.png", stem);
    if (png_write_rgb8(j->dir, name, j->rgb8, j->n, j->n, j->err) != 0)
        return -1;
    add_file(j->r, name, caption, RF_IMAGE, fit);
    return 0;
}

/* The model's PNG in j->rgb8 against the reference's: its L* difference
 * (kept for the difference image, written once the scale is known) and its
 * FLIP map, written as STEM-flip.png; the mean FLIP is its image error. */
static int compare_model(render_job *j, const rf_fit *f, int k)
{
    size_t px = (size_t)j->n * (size_t)j->n;
    float *l = j->work, *srgb = l + px, *map = srgb + 3 * px, *dl = j->dl + (size_t)k * px;
    ci_lightness(j->rgb8, j->ref, j->n, l);
    for (size_t i = 0; i < px; i++)
        dl[i] = l[i] - j->ref_l[i];
    for (size_t i = 0; i < 3 * px; i++)
        srgb[i] = j->rgb8[i] / 255.0f;
    double mean;
    brdffit_error lerr;
    if (brdffit_flip_compare(j->flip, srgb, 0, map, &mean, &lerr) != BRDFFIT_OK)
        return failf(j->err, lerr.status, "FLIP %s: %s", stem_of(f), lerr.message);
    j->r->image_error[k] = mean;
    ci_flip_image(map, j->n, j->rgb8);
    char name[160], caption[256];
    snprintf(name, sizeof name, "%s-flip.png", stem_of(f));
    if (png_write_rgb8(j->dir, name, j->rgb8, j->n, j->n, j->err) != 0)
        return -1;
    snprintf(caption, sizeof caption, "%s: \xea\x9f\xbbLIP %.3g", label_of(f), mean);
    add_file(j->r, name, caption, RF_IMAGE, k);
    return 0;
}

static int write_model(render_job *j, const rf_fit *f, int k, const rf_settings *s)
{
    char caption[256];
    brdffit_error lerr;
    if (brdffit_render_model(f->model, &f->params, &s->render_opt, j->img, 0, &lerr) != BRDFFIT_OK)
        return failf(j->err, lerr.status, "render %s: %s", stem_of(f), lerr.message);
    caption_of(f, caption, sizeof caption);
    if (write_exr(j, j->img, stem_of(f), caption, k) != 0 ||
        write_png(j, j->img, stem_of(f), caption, k) != 0)
        return -1;
    double e;
    j->r->relative_rms[k] = brdffit_image_error(j->raw, j->img, j->n, j->n, 0, &e, NULL, NULL) ==
                                    BRDFFIT_OK ? e : NAN;
    return compare_model(j, f, k);
}

/* The models' renders and files are written by RF_WRITERS threads (writer w
 * takes models w, w + RF_WRITERS, ...), each with images and a file list of
 * its own; their files are then added to j's list in the models' order, as
 * one thread would have written them.  (The files' encoding is sequential:
 * with the renders, whose pixels are already threaded, it was ~70% of a
 * material's renders and files, alone on a machine after a batch's last
 * fits.) */
#define RF_WRITERS 2

typedef struct model_writer {
    render_job j;        /* j's directory and reference; img, rgb8, r and err its own */
    rf_result r;
    brdffit_error err;
    const rf_fit *fits;
    const rf_settings *s;
    int first, nfits;
    int failed;          /* the model that failed, or nfits */
    pthread_t thread;
    int threaded;
} model_writer;

static void *writer_main(void *arg)
{
    model_writer *w = arg;
    for (int k = w->first; k < w->nfits && w->failed == w->nfits; k += RF_WRITERS)
        if (write_model(&w->j, &w->fits[k], k, w->s) != 0)
            w->failed = k;
    return NULL;
}

/* 0, or -1 with j->err of the first model (in order) that failed. */
static int write_models(render_job *j, const rf_fit *fits, int nfits, const rf_settings *s)
{
    size_t px = (size_t)j->n * (size_t)j->n;
    model_writer *w = calloc(RF_WRITERS, sizeof *w);
    int rc = w ? 0 : failf(j->err, BRDFFIT_E_NO_MEMORY, "%s: no memory for the images", j->dir->path);
    for (int i = 0; rc == 0 && i < RF_WRITERS; i++) {
        w[i] = (model_writer){ .j = *j, .fits = fits, .s = s, .first = i, .nfits = nfits,
                               .failed = nfits };
        w[i].r.exposure = j->r->exposure;
        w[i].j.r = &w[i].r;
        w[i].j.err = &w[i].err;
        w[i].j.img = malloc(16 * px);
        w[i].j.rgb8 = malloc(3 * px);
        w[i].j.work = malloc(sizeof(float) * 5 * px);
        if (!w[i].j.img || !w[i].j.rgb8 || !w[i].j.work)
            rc = failf(j->err, BRDFFIT_E_NO_MEMORY, "%s: no memory for the images", j->dir->path);
    }
    for (int i = 1; rc == 0 && i < RF_WRITERS; i++) /* writer 0 in this thread */
        w[i].threaded = pthread_create(&w[i].thread, NULL, writer_main, &w[i]) == 0;
    if (rc == 0)
        writer_main(&w[0]);
    for (int i = 1; rc == 0 && i < RF_WRITERS; i++)
        if (w[i].threaded)
            pthread_join(w[i].thread, NULL);
        else
            writer_main(&w[i]); /* no thread to be had: here, then */
    for (int k = 0; rc == 0 && k < nfits; k++) {
        model_writer *o = &w[k % RF_WRITERS];
        if (o->failed == k) {
            *j->err = o->err;
            rc = -1;
            break;
        }
        j->r->image_error[k] = o->r.image_error[k];
        j->r->relative_rms[k] = o->r.relative_rms[k];
        for (int f = 0; f < o->r.nfiles; f++)
            if (o->r.files[f].fit == k && j->r->nfiles < RF_MAX_FILES)
                j->r->files[j->r->nfiles++] = o->r.files[f];
    }
    for (int i = 0; w && i < RF_WRITERS; i++) {
        free(w[i].j.img);
        free(w[i].j.rgb8);
        free(w[i].j.work);
    }
    free(w);
    return rc;
}

/* The difference images, once every model's L* difference is known: one
 * full scale for them all (ci_diff_scale), and the colour bars. */
static int write_diffs(render_job *j, const rf_fit *fits, int nfits)
{
    size_t px = (size_t)j->n * (size_t)j->n;
    j->r->diff_scale = ci_diff_scale(j->dl, (size_t)nfits * px);
    for (int k = 0; k < nfits; k++) {
        char name[160], caption[256];
        ci_diff_image(j->dl + (size_t)k * px, j->ref, j->n, j->r->diff_scale, j->rgb8);
        snprintf(name, sizeof name, "%s-diff.png", stem_of(&fits[k]));
        if (png_write_rgb8(j->dir, name, j->rgb8, j->n, j->n, j->err) != 0)
            return -1;
        snprintf(caption, sizeof caption, "%s: \xce\x94L*, \xea\x9f\xbbLIP %.3g",
                 label_of(&fits[k]), j->r->image_error[k]);
        add_file(j->r, name, caption, RF_IMAGE, k);
    }
    if (ci_write_bars(j->dir, j->r->diff_scale, j->err) != 0)
        return -1;
    add_file(j->r, "diff-scale.svg", "colours of the difference images", RF_IMAGE, -1);
    add_file(j->r, "flip-scale.svg", "colours of the FLIP maps", RF_IMAGE, -1);
    return 0;
}

/* The reference: its EXR as rendered (masked pixels A = 0.5), then its
 * masked pixels filled where a covered neighbour is, its PNG, the PNG's L*
 * and its FLIP reference. */
static int write_reference(render_job *j, float *raw, float *ref_l, brdffit_flip_ref **flip)
{
    size_t px = (size_t)j->n * (size_t)j->n;
    if (write_exr(j, j->ref, "reference", "Reference (measured)", -1) != 0)
        return -1;
    memcpy(raw, j->ref, sizeof(float) * 4 * px);
    j->r->filled = ci_fill_masked(j->ref, j->n);
    if (write_png(j, j->ref, "reference", "Reference (measured)", -1) != 0)
        return -1;
    ci_lightness(j->rgb8, j->ref, j->n, ref_l);
    float *srgb = malloc(sizeof(float) * 3 * px);
    if (!srgb)
        return failf(j->err, BRDFFIT_E_NO_MEMORY, "%s: no memory for the images", j->dir->path);
    for (size_t i = 0; i < 3 * px; i++)
        srgb[i] = j->rgb8[i] / 255.0f;
    brdffit_error lerr;
    int rc = brdffit_flip_ref_create(srgb, j->n, j->n, 0, 0, flip, &lerr) == BRDFFIT_OK
                 ? 0 : failf(j->err, lerr.status, "FLIP reference: %s", lerr.message);
    free(srgb);
    return rc;
}

static int write_renders(const out_dir *dir, const brdffit_table *table, const rf_fit *fits,
                         int nfits, const rf_settings *s, rf_result *r, brdffit_error *err)
{
    int n = s->render_opt.width, rc = -1;
    size_t px = (size_t)n * (size_t)n;
    render_job j = { dir, n, malloc(16 * px), malloc(16 * px), NULL, malloc(3 * px), r, err,
                     NULL, malloc(sizeof(float) * px * (size_t)(nfits > 0 ? nfits : 1)), NULL,
                     NULL };
    float *ref_l = malloc(sizeof(float) * px), *raw = malloc(16 * px);
    brdffit_flip_ref *flip = NULL;
    brdffit_error lerr;
    if (!j.ref || !j.img || !j.rgb8 || !j.dl || !ref_l || !raw) {
        failf(err, BRDFFIT_E_NO_MEMORY, "%s: no memory for the images", dir->path);
        goto done;
    }
    if (brdffit_render_table(table, &s->render_opt, j.ref, 0, &lerr) != BRDFFIT_OK) {
        failf(err, lerr.status, "render reference: %s", lerr.message);
        goto done;
    }
    r->covered = r->masked = 0;
    for (size_t i = 0; i < px; i++) {
        r->covered += j.ref[4 * i + 3] == 1.0f;
        r->masked += j.ref[4 * i + 3] == BRDFFIT_COVERAGE_MASKED;
    }
    r->exposure = s->exposure > 0 ? s->exposure : tm_auto_exposure(j.ref, n, n, 0);
    if (write_reference(&j, raw, ref_l, &flip) != 0)
        goto done;
    j.raw = raw;
    j.ref_l = ref_l;
    j.flip = flip;
    if (write_models(&j, fits, nfits, s) == 0 && write_diffs(&j, fits, nfits) == 0)
        rc = 0;
done:
    brdffit_flip_ref_free(flip);
    free(ref_l);
    free(raw);
    free(j.ref);
    free(j.img);
    free(j.rgb8);
    free(j.dl);
    return rc;
}

/* ------------------------------------------------------------------ renders.json */

static void json_light_list(FILE *f, const brdffit_render_options *o)
{
    brdffit_light dflt[2];
    const brdffit_light *l = o->lights;
    int n = o->nlights;
    if (n == BRDFFIT_RENDER_DEFAULT_LIGHTS)
        n = brdffit_render_default_lights(dflt), l = dflt;
    fputc('[', f);
    for (int k = 0; k < n; k++) {
        fputs(k ? ",{\"dir\":" : "{\"dir\":", f);
        json_numbers(f, l[k].dir, 3);
        fputs(",\"rgb\":", f);
        json_numbers(f, l[k].rgb, 3);
        fputc('}', f);
    }
    fputc(']', f);
}

static void json_body(FILE *f, const char *material, const rf_fit *fits, int nfits,
                      const rf_settings *s, const rf_result *r)
{
    const brdffit_render_options *o = &s->render_opt;
    fputs("{\"material\":", f);
    json_string(f, material);
    fprintf(f, ",\"size\":%d,\"lights\":", o->width);
    json_light_list(f, o);
    fputs(",\"env\":", f);
    json_string(f, o->env ? (s->env_file ? s->env_file : "") : NULL);
    fprintf(f, ",\"env_samples\":%d,\"interp\":\"%s\",\"scale\":", o->env ? o->env_samples : 0,
            o->interp == BRDFFIT_INTERP_NEAREST ? "nearest" : "trilinear");
    json_string(f, brdffit_scale_name(o->scale));
    fputs(",\"exposure\":", f);
    json_number(f, r->exposure);
    fprintf(f, ",\"exposure_rule\":\"%s\",\"transfer\":\"sRGB (IEC 61966-2-1) of exposure x "
               "radiance, clamped to [0, 1], 8-bit\"",
            s->exposure > 0 ? "given" : "1 / 99th percentile of max(R, G, B) over the sphere");
    fputs(",\"difference\":{\"value\":\"L*(model PNG) - L*(reference PNG), CIE lightness\","
          "\"full_scale\":", f);
    json_number(f, r->diff_scale);
    fputs(",\"scale_rule\":\"95th percentile of |value| over the covered pixels of all models, "
          "rounded up to 1, 1.5, 2, 3, 5 or 7 x 10^k, in [1, 100]\",\"colours\":\"ColorBrewer RdBu: "
          "dark blue -full_scale (model darker), white 0, dark red +full_scale (model brighter); "
          "black off the sphere; grey: masked reference pixel with no covered neighbour\"}", f);
    fprintf(f, ",\"image_error\":\"mean LDR FLIP (NVIDIA) of the model PNG against the "
               "reference PNG over all pixels, 67 pixels per degree\",\"relative_rms\":\"RMS of "
               "model - reference over covered pixels / RMS of the reference (linear)\","
               "\"covered\":%zu,\"masked\":%zu,\"masked_filled\":%zu,\"models\":[",
            r->covered, r->masked, r->filled);
    for (int k = 0; k < nfits; k++) {
        fputs(k ? ",{\"model\":" : "{\"model\":", f);
        json_string(f, brdffit_model_get(fits[k].model)->name);
        fputs(",\"stem\":", f);
        json_string(f, stem_of(&fits[k]));
        fputs(",\"error\":", f);
        json_number(f, fits[k].error);
        fputs(",\"image_error\":", f);
        json_number(f, r->image_error[k]);
        fputs(",\"relative_rms\":", f);
        json_number(f, r->relative_rms[k]);
        fputc('}', f);
    }
    fputs("]}\n", f);
}

static int write_json(const out_dir *dir, const char *material, const rf_fit *fits, int nfits,
                      const rf_settings *s, rf_result *r, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "renders.json", err) != 0)
        return -1;
    json_body(o.f, material, fits, nfits, s, r);
    if (out_commit(&o, err) != 0)
        return -1;
    add_file(r, "renders.json", "render settings and image errors", RF_DATA, -1);
    return 0;
}

/* ------------------------------------------------------------------ plots */

static int write_plots(const out_dir *dir, const char *material, const brdffit_table *table,
                       const rf_fit *fits, int nfits, const rf_settings *s, rf_result *r,
                       brdffit_error *err)
{
    const brdffit_curve_options *o = &s->curve_opt;
    brdffit_error lerr;
    int rc = -1;
    size_t row = 3 * (size_t)o->npoints;
    double *th = malloc(sizeof(double) * (size_t)o->npoints);
    double *meas = malloc(sizeof(double) * row * (size_t)o->ntheta_i);
    double *mod = malloc(sizeof(double) * row * (size_t)o->ntheta_i);
    char name[160], title[512], caption[256];
    if (!th || !meas || !mod) {
        failf(err, BRDFFIT_E_NO_MEMORY, "%s: no memory for the curves", dir->path);
        goto done;
    }
    if (brdffit_curve_theta_o(o, th, &lerr) != BRDFFIT_OK ||
        brdffit_curve_table(table, o, meas, 0, &lerr) != BRDFFIT_OK) {
        failf(err, BRDFFIT_E_INVALID_ARGUMENT, "curves measured: %s", lerr.message);
        goto done;
    }
    snprintf(title, sizeof title, "%s: measured (incidence plane, cube root)", material);
    if (plot_write_svg(dir, "plot-measured.svg", title, o, th, meas, NULL, 0, err) != 0)
        goto done;
    add_file(r, "plot-measured.svg", "Measured (incidence plane, cube root)", RF_PLOT, -1);
    for (int k = 0; k < nfits; k++) {
        if (brdffit_curve_model(fits[k].model, &fits[k].params, o, mod, 0, &lerr) != BRDFFIT_OK) {
            failf(err, lerr.status, "curves %s: %s", stem_of(&fits[k]), lerr.message);
            goto done;
        }
        caption_of(&fits[k], caption, sizeof caption);
        if (isfinite(fits[k].error))
            snprintf(title, sizeof title, "%s: Error %.3g \xe2\x80\x94 %s", label_of(&fits[k]),
                     fits[k].error, material);
        else
            snprintf(title, sizeof title, "%s \xe2\x80\x94 %s", label_of(&fits[k]), material);
        snprintf(name, sizeof name, "plot-%s.svg", stem_of(&fits[k]));
        if (plot_write_svg(dir, name, title, o, th, meas, mod, 0, err) != 0)
            goto done;
        add_file(r, name, caption, RF_PLOT, k);
    }
    rc = 0;
done:
    free(th);
    free(meas);
    free(mod);
    return rc;
}

/* ------------------------------------------------------------------ the material */

int rf_write_material_at(const out_dir *dir, const char *material, const brdffit_table *table,
                         const rf_fit *fits, int nfits, const rf_settings *s, rf_result *out,
                         brdffit_error *err)
{
    rf_result scratch;
    rf_result *r = out ? out : &scratch;
    memset(r, 0, sizeof *r);
    for (int k = 0; k < RF_MAX_FITS; k++)
        r->image_error[k] = r->relative_rms[k] = NAN;
    if (!dir || !material || !table || !s || nfits < 0 || nfits > RF_MAX_FITS ||
        (nfits > 0 && !fits))
        return failf(err, BRDFFIT_E_INVALID_ARGUMENT, "rf_write_material: bad arguments");
    for (int k = 0; k < nfits; k++)
        if (!brdffit_model_get(fits[k].model))
            return failf(err, BRDFFIT_E_UNKNOWN_MODEL, "%s: unknown model", material);
    double t0 = brdffit_seconds();
    if (s->render && (write_renders(dir, table, fits, nfits, s, r, err) != 0 ||
                      write_json(dir, material, fits, nfits, s, r, err) != 0))
        return -1;
    double t1 = brdffit_seconds();
    if (s->plot && write_plots(dir, material, table, fits, nfits, s, r, err) != 0)
        return -1;
    r->seconds_render = t1 - t0;
    r->seconds_plot = brdffit_seconds() - t1;
    return 0;
}

int rf_write_material(const char *dir, const char *material, const brdffit_table *table,
                      const rf_fit *fits, int nfits, const rf_settings *s, rf_result *out,
                      brdffit_error *err)
{
    out_dir d;
    if (!dir)
        return failf(err, BRDFFIT_E_INVALID_ARGUMENT, "rf_write_material: bad arguments");
    if (od_open(&d, dir, 1, err) != 0)
        return -1;
    int rc = rf_write_material_at(&d, material, table, fits, nfits, s, out, err);
    od_close(&d);
    return rc;
}
