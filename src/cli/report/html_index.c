/* SPDX-License-Identifier: MIT */
/* html_index.c -- the report's own files: DIR/index.html (settings, per-model
 * summary, the headline figure, the Error matrix), DIR/headline.svg and
 * DIR/fits.tsv. */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ settings and Error cells */

static void settings_table(xml_writer *w, const rp_report *rep)
{
    char b[256];
    xml_open(w, "table");
    const char *rows[][2] = {
        { "metric", rep->settings.metric[0] ? rep->settings.metric : brdffit_metric_name() },
        { "cutoff", (snprintf(b, sizeof b, "%g deg (theta_i, theta_o)", rep->settings.cutoff_deg), b) },
    };
    for (int i = 0; i < 2; i++) {
        xml_open(w, "tr");
        rp_cell(w, "th", "name", rows[i][0]);
        rp_cell(w, "td", "name", rows[i][1]);
        xml_close(w);
    }
    char starts[320], dflt[256];
    if (rep->settings.starts > 0)
        snprintf(starts, sizeof starts, "%d per model", rep->settings.starts);
    else
        snprintf(starts, sizeof starts, "each model's default (%s)",
                 cli_default_starts(dflt, sizeof dflt));
    const char *more[][2] = {
        { "scale", rep->settings.scale },
        { "starts", starts },
        { "brdffit version", rep->settings.version },
        { "backend", rep->backend },
        { "report written", rep->started },
        { "published fits", rep->have_published ? rep->published_path : "(none given)" },
    };
    for (size_t i = 0; i < sizeof more / sizeof more[0]; i++) {
        xml_open(w, "tr");
        rp_cell(w, "th", "name", more[i][0]);
        rp_cell(w, "td", "name", more[i][1]);
        xml_close(w);
    }
    xml_close(w);
}

/* An Error cell: the fitted Error, and under it the published one and the ratio. */
static void error_cell(xml_writer *w, const fit_record *fit, const fit_record *pub, int best,
                       int have_pub)
{
    char b[64], r[64];
    xml_open(w, "td");
    if (best)
        xml_attr(w, "class", "best");
    if (!fit)
        xml_text(w, "-");
    else if (!fr_ok(fit))
        xml_textf(w, "failed: %s", fr_status_text(fit));
    else
        xml_textf(w, "%s%s", rp_num(b, sizeof b, "%.4g", fit->error), best ? " \xe2\x98\x85" : "");
    if (have_pub && pub) {
        xml_open(w, "span");
        xml_attr(w, "class", "pub");
        if (fr_ok(pub))
            xml_textf(w, "published %s, ratio %s", rp_num(b, sizeof b, "%.4g", pub->error),
                      rp_num(r, sizeof r, "%.3g", fr_ratio(fit, pub)));
        else
            xml_textf(w, "published: %s", pub->message);
        xml_close(w);
    }
    xml_close(w);
}

/* ------------------------------------------------------------------ the headline figure */

typedef struct order_item {
    int i;
    double e;   /* the sort model's Error */
    int any;    /* the material has an Error of some model */
} order_item;

static int by_error(const void *a, const void *b)
{
    const order_item *x = a, *y = b;
    if (x->any != y->any)
        return y->any - x->any; /* materials without any Error last (not drawn) */
    int fx = isfinite(x->e), fy = isfinite(y->e);
    if (fx != fy)
        return fy - fx; /* materials without an Error last */
    if (fx && x->e != y->e)
        return x->e < y->e ? -1 : 1;
    return x->i - y->i;
}

static double fit_error(const rp_material *m, int k)
{
    const fit_record *f = m->fit[k];
    return f && fr_ok(f) && f->error > 0 && isfinite(f->error) ? f->error : NAN;
}

#define HF_W 960.0
#define HF_H 540.0
#define HF_L 72.0
#define HF_R 190.0
#define HF_T 44.0
#define HF_B 130.0

static void headline_axes(xml_writer *w, int lo, int hi, const rp_report *rep, const order_item *ord,
                          int np)
{
    double pw = HF_W - HF_L - HF_R, ph = HF_H - HF_T - HF_B;
    svg_rect(w, HF_L, HF_T, pw, ph, NULL, "#888888");
    for (int d = lo; d <= hi; d++) {
        double y = HF_T + ph * (1 - (double)(d - lo) / (hi - lo));
        char t[32];
        if (d >= -3 && d <= 3)
            snprintf(t, sizeof t, "%g", pow(10, d));
        else
            snprintf(t, sizeof t, "1e%d", d);
        svg_line(w, HF_L, y, HF_L + pw, y, "#dddddd", 1, NULL);
        svg_text(w, HF_L - 6, y + 4, "end", 11, t);
        for (int m = 2; m <= 9 && d < hi; m++) {
            double ym = y - ph / (hi - lo) * log10((double)m);
            svg_line(w, HF_L, ym, HF_L + 4, ym, "#888888", 1, NULL);
        }
    }
    svg_text_rotated(w, 18, HF_T + ph / 2, -90, "middle", 12, "Error (ngan-l2, 1/sr), log scale");
    for (int i = 0; i < np && np <= 150; i++) {
        double x = HF_L + pw * (i + 0.5) / np;
        svg_text_rotated(w, x + 3, HF_T + ph + 8, 60, "start", np > 60 ? 7 : 10,
                         rep->m[ord[i].i].name);
    }
}

static void headline_series(xml_writer *w, const rp_report *rep, const order_item *ord, int np,
                            int k, int lo, int hi)
{
    double pw = HF_W - HF_L - HF_R, ph = HF_H - HF_T - HF_B;
    double *x = malloc((size_t)rep->n * sizeof *x), *y = malloc((size_t)rep->n * sizeof *y);
    if (!x || !y) {
        free(x);
        free(y);
        return;
    }
    const char *col = svg_color((int)rep->models[k]); /* a model's colour in every figure */
    int run = 0;
    for (int i = 0; i <= np; i++) {
        double e = i < np ? fit_error(&rep->m[ord[i].i], k) : NAN;
        if (isfinite(e)) {
            x[run] = HF_L + pw * (i + 0.5) / np;
            y[run] = HF_T + ph * (1 - (log10(e) - lo) / (hi - lo));
            svg_circle(w, x[run], y[run], 2.5, col, NULL);
            run++;
        } else {
            svg_polyline(w, x, y, run, col, 1.2, NULL); /* a gap ends the line */
            run = 0;
        }
    }
    free(x);
    free(y);
}

int rp_write_headline(const rp_report *rep, const out_dir *dir, int sort_k, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "headline.svg", err) != 0)
        return -1;
    order_item *ord = malloc((size_t)(rep->n > 0 ? rep->n : 1) * sizeof *ord);
    if (!ord) {
        out_abandon(&o);
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "out of memory");
        return -1;
    }
    double emin = INFINITY, emax = -INFINITY;
    int np = 0;
    for (int i = 0; i < rep->n; i++) {
        ord[i].i = i;
        ord[i].e = sort_k >= 0 ? fit_error(&rep->m[i], sort_k) : NAN;
        ord[i].any = 0;
        for (int k = 0; k < rep->nmodels; k++) {
            double e = fit_error(&rep->m[i], k);
            if (isfinite(e)) {
                emin = fmin(emin, e);
                emax = fmax(emax, e);
                ord[i].any = 1;
            }
        }
        np += ord[i].any;
    }
    qsort(ord, (size_t)rep->n, sizeof *ord, by_error);
    int lo = isfinite(emin) ? (int)floor(log10(emin)) : -3;
    int hi = isfinite(emax) ? (int)ceil(log10(emax)) : 0;
    if (hi <= lo)
        hi = lo + 1;
    xml_writer w;
    svg_begin(&w, o.f, HF_W, HF_H);
    char title[256];
    snprintf(title, sizeof title, "Error of every model per material, materials sorted by %s's Error",
             sort_k >= 0 ? brdffit_model_get(rep->models[sort_k])->title : "(none)");
    svg_text(&w, HF_W / 2, 24, "middle", 15, title);
    headline_axes(&w, lo, hi, rep, ord, np);
    for (int k = 0; k < rep->nmodels; k++) {
        headline_series(&w, rep, ord, np, k, lo, hi);
        double ly = HF_T + 10 + 20 * k, lx = HF_W - HF_R + 16;
        svg_line(&w, lx, ly, lx + 22, ly, svg_color((int)rep->models[k]), 2, NULL);
        svg_circle(&w, lx + 11, ly, 2.5, svg_color((int)rep->models[k]), NULL);
        svg_text(&w, lx + 28, ly + 4, "start", 12, brdffit_model_get(rep->models[k])->title);
    }
    free(ord);
    if (svg_end(&w) != 0 && !ferror(o.f)) {
        out_abandon(&o);
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "cannot write %.1800s: a non-finite coordinate",
                 o.path);
        return -1;
    }
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ fits.tsv */

int rp_write_fits_tsv(const rp_report *rep, const out_dir *dir, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "fits.tsv", err) != 0)
        return -1;
    fprintf(o.f, "# every fit of the report: metric %s, cutoff %g deg, scale %s, starts %d, "
                 "brdffit %s; ratio = error / published_error; the columns: docs/fit-record.md\n",
            rep->settings.metric, rep->settings.cutoff_deg, rep->settings.scale,
            rep->settings.starts, rep->settings.version);
    fr_write_tsv_header(o.f);
    for (int i = 0; i < rep->n; i++)
        rp_tsv_material(o.f, rep, &rep->m[i]);
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ DIR/index.html */

static void summary_table(xml_writer *w, const rp_report *rep)
{
    char b[64];
    xml_open(w, "table");
    xml_open(w, "tr");
    rp_cell(w, "th", "name", "model");
    rp_cell(w, "th", NULL, "median Error");
    rp_cell(w, "th", NULL, "best on");
    rp_cell(w, "th", NULL, "fitted");
    xml_close(w);
    for (int k = 0; k < rep->nmodels; k++) {
        int nbest = 0, nfit = 0;
        double med = rp_median(rep, k, &nbest, &nfit);
        xml_open(w, "tr");
        rp_cell(w, "td", "name", brdffit_model_get(rep->models[k])->title);
        rp_cell(w, "td", NULL, rp_num(b, sizeof b, "%.4g", med));
        snprintf(b, sizeof b, "%d", nbest);
        rp_cell(w, "td", NULL, b);
        snprintf(b, sizeof b, "%d of %d", nfit, rep->n);
        rp_cell(w, "td", NULL, b);
        xml_close(w);
    }
    xml_close(w);
}

static void error_matrix(xml_writer *w, const rp_report *rep)
{
    char href[BJ_NAME_MAX * 3 + 16];
    xml_open(w, "table");
    xml_open(w, "tr");
    rp_cell(w, "th", "name", "material");
    for (int k = 0; k < rep->nmodels; k++)
        rp_cell(w, "th", NULL, brdffit_model_get(rep->models[k])->name);
    xml_close(w);
    for (int i = 0; i < rep->n; i++) {
        const rp_material *m = &rep->m[i];
        int best = rp_best(rep, i);
        xml_open(w, "tr");
        xml_open(w, "td");
        xml_attr(w, "class", "name");
        rp_url_segment(href, sizeof href - 12, m->name);
        strcat(href, "/index.html");
        rp_link(w, href, m->name);
        xml_close(w);
        if (m->failure) {
            xml_open(w, "td");
            xml_attr(w, "class", "failed");
            xml_attrf(w, "colspan", "%d", rep->nmodels);
            xml_textf(w, "not fitted: %s", m->failure->message);
            xml_close(w);
        } else {
            for (int k = 0; k < rep->nmodels; k++)
                error_cell(w, m->fit[k], m->published[k], k == best, rep->have_published);
        }
        xml_close(w);
    }
    xml_close(w);
}

int rp_write_index(const rp_report *rep, const out_dir *dir, int sort_k, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "index.html", err) != 0)
        return -1;
    xml_writer w;
    int failed = 0;
    for (int i = 0; i < rep->n; i++)
        failed += rep->m[i].failure != NULL;
    char title[256];
    snprintf(title, sizeof title, "brdffit report: %d material%s, %d model%s", rep->n,
             rep->n == 1 ? "" : "s", rep->nmodels, rep->nmodels == 1 ? "" : "s");
    rp_html_begin(&w, o.f, title);
    xml_element_text(&w, "h1", title);
    if (failed) {
        xml_open(&w, "p");
        xml_attr(&w, "class", "failed");
        xml_textf(&w, "%d material%s could not be fitted: see the rows marked \"not fitted\".",
                  failed, failed == 1 ? "" : "s");
        xml_close(&w);
    }
    xml_element_text(&w, "h2", "Settings");
    settings_table(&w, rep);
    xml_element_text(&w, "h2", "Models");
    summary_table(&w, rep);
    xml_element_text(&w, "h2", "Error of every material");
    xml_open(&w, "figure");
    xml_open(&w, "img");
    xml_attr(&w, "src", "headline.svg");
    xml_attr(&w, "alt", "Error of every model per material, log scale");
    xml_close(&w);
    xml_open(&w, "figcaption");
    xml_textf(&w, "Each model's Error per material (log scale); materials sorted by %s's Error "
                  "(the lowest median).",
              sort_k >= 0 ? brdffit_model_get(rep->models[sort_k])->title : "(none)");
    xml_close(&w);
    xml_close(&w);
    xml_element_text(&w, "h2", "Error matrix");
    error_matrix(&w, rep);
    xml_open(&w, "p");
    xml_attr(&w, "class", "note");
    xml_text(&w, "Error = ngan-l2 (1/sr); \xe2\x98\x85 the lowest Error of the material");
    if (rep->have_published)
        xml_text(&w, "; published = the Error of the published parameters on the same table, "
                     "ratio = Error / published Error");
    xml_text(&w, ". Every fit, one line: ");
    rp_link(&w, "fits.tsv", "fits.tsv");
    xml_close(&w);
    rp_html_end(&w);
    return rp_finish(&o, &w, err);
}
