/* SPDX-License-Identifier: MIT */
/* html_report.c -- the report of a batch as static files with relative links:
 * per material DIR/<material>/params.tsv, params.json and index.html (the
 * parameter table, renders, plots); DIR/index.html (settings, per-model
 * summary, the headline figure, the Error matrix), DIR/fits.tsv and
 * DIR/headline.svg.  HTML and SVG go through the escaping writer of svg.h. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"
#include "svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ small text helpers */

/* x with fmt, or "-" when it is not finite. */
static const char *num(char *buf, size_t len, const char *fmt, double x)
{
    if (isfinite(x))
        snprintf(buf, len, fmt, x);
    else
        snprintf(buf, len, "-");
    return buf;
}

/* A path segment of a relative URL: every byte but [A-Za-z0-9._~-] percent-encoded. */
static const char *url_segment(char *buf, size_t len, const char *s)
{
    static const char hex[] = "0123456789ABCDEF";
    size_t n = 0;
    for (const unsigned char *p = (const unsigned char *)s; *p && n + 4 < len; p++) {
        unsigned c = *p;
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
            c == '.' || c == '_' || c == '~' || c == '-') {
            buf[n++] = (char)c;
        } else {
            buf[n++] = '%';
            buf[n++] = hex[c >> 4];
            buf[n++] = hex[c & 15];
        }
    }
    buf[n] = '\0';
    return buf;
}

static const char *param_label(brdffit_model model, int k)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    return k < mi->nparams ? mi->params[k].name : "";
}

static int open_in(out_file *o, const char *dir, const char *name, brdffit_error *err)
{
    char path[BJ_PATH_MAX];
    if (out_join(path, sizeof path, dir, name) != 0) {
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "cannot write %.1800s/%s: name too long", dir,
                 name);
        return -1;
    }
    return out_open(o, path, err);
}

/* Finish a page written with the XML writer: commit it, or report the failure. */
static int finish(out_file *o, xml_writer *w, brdffit_error *err)
{
    if (xml_finish(w) != 0 && !ferror(o->f)) {
        out_abandon(o);
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "cannot write %.1800s: the page could not be "
                 "laid out (a non-finite number or unbalanced element)", o->path);
        return -1;
    }
    return out_commit(o, err);
}

/* ------------------------------------------------------------------ params.tsv, params.json */

/* The rows of a material in the TSV of fits (fit_record.h): its failure, or its fits. */
static void tsv_material(FILE *f, const rp_report *rep, const rp_material *m)
{
    if (m->failure) {
        fr_write_tsv_row(f, m->failure, NULL);
        return;
    }
    for (int k = 0; k < rep->nmodels; k++)
        if (m->fit[k])
            fr_write_tsv_row(f, m->fit[k], m->published[k]);
}

static int write_params_tsv(const rp_report *rep, const rp_material *m, const char *dir,
                            brdffit_error *err)
{
    out_file o;
    if (open_in(&o, dir, "params.tsv", err) != 0)
        return -1;
    fprintf(o.f, "# %s: metric %s, cutoff %g deg, scale %s, starts %d, brdffit %s; "
                 "ratio = error / published_error; p0..p2 per model: brdffit models; "
                 "the columns: docs/fit-record.md\n",
            m->name, brdffit_metric_name(), rep->settings.cutoff_deg, rep->settings.scale,
            rep->settings.starts, rep->settings.version);
    fr_write_tsv_header(o.f);
    tsv_material(o.f, rep, m);
    return out_commit(&o, err);
}

/* params.json: the material, its failure record (or null), its fit records
 * and the records of its published parameters (fit_record.h). */
static int write_params_json(const rp_report *rep, const rp_material *m, const char *dir,
                             brdffit_error *err)
{
    out_file o;
    if (open_in(&o, dir, "params.json", err) != 0)
        return -1;
    FILE *f = o.f;
    fputs("{\"material\":", f);
    json_string(f, m->name);
    fputs(",\"failure\":", f);
    if (m->failure)
        fr_write_json(f, m->failure);
    else
        fputs("null", f);
    for (int pass = 0; pass < 2; pass++) {
        fputs(pass ? ",\"published\":[" : ",\"fits\":[", f);
        int first = 1;
        for (int k = 0; k < rep->nmodels; k++) {
            const fit_record *r = pass ? m->published[k] : m->fit[k];
            if (!r)
                continue;
            if (!first)
                putc(',', f);
            first = 0;
            fr_write_json(f, r);
        }
        putc(']', f);
    }
    fputs("}\n", f);
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ HTML pieces */

static const char *const page_css =
    "body{font-family:sans-serif;margin:1.5em;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0}"
    "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right;font-variant-numeric:tabular-nums}"
    "th{background:#eee}td.name,th.name{text-align:left}"
    "td.best{background:#d8f0d0;font-weight:bold}"
    "td.failed{color:#a00;text-align:left}"
    "span.pub{display:block;color:#555;font-size:85%}"
    "figure{display:inline-block;margin:4px;text-align:center}"
    "figure img{display:block}figcaption{font-size:90%}"
    "p.note{color:#555;font-size:90%}";

static void html_begin(xml_writer *w, FILE *f, const char *title)
{
    xml_init(w, f, XML_MODE_HTML);
    xml_raw(w, "<!DOCTYPE html>\n");
    xml_open(w, "html");
    xml_attr(w, "lang", "en");
    xml_open(w, "head");
    xml_open(w, "meta");
    xml_attr(w, "charset", "utf-8");
    xml_close(w);
    xml_element_text(w, "title", title);
    xml_element_text(w, "style", page_css);
    xml_close(w);
    xml_open(w, "body");
}

static void html_end(xml_writer *w)
{
    xml_close(w); /* body */
    xml_close(w); /* html */
}

static void link(xml_writer *w, const char *href, const char *text)
{
    xml_open(w, "a");
    xml_attr(w, "href", href);
    xml_text(w, text);
    xml_close(w);
}

static void cell(xml_writer *w, const char *tag, const char *cls, const char *text)
{
    xml_open(w, tag);
    if (cls)
        xml_attr(w, "class", cls);
    xml_text(w, text);
    xml_close(w);
}

static void settings_table(xml_writer *w, const rp_report *rep)
{
    char b[256];
    xml_open(w, "table");
    const char *rows[][2] = {
        { "metric", brdffit_metric_name() },
        { "cutoff", (snprintf(b, sizeof b, "%g deg (theta_i, theta_o)", rep->settings.cutoff_deg), b) },
    };
    for (int i = 0; i < 2; i++) {
        xml_open(w, "tr");
        cell(w, "th", "name", rows[i][0]);
        cell(w, "td", "name", rows[i][1]);
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
        cell(w, "th", "name", more[i][0]);
        cell(w, "td", "name", more[i][1]);
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
        xml_textf(w, "%s%s", num(b, sizeof b, "%.4g", fit->error), best ? " \xe2\x98\x85" : "");
    if (have_pub && pub) {
        xml_open(w, "span");
        xml_attr(w, "class", "pub");
        if (fr_ok(pub))
            xml_textf(w, "published %s, ratio %s", num(b, sizeof b, "%.4g", pub->error),
                      num(r, sizeof r, "%.3g", fr_ratio(fit, pub)));
        else
            xml_textf(w, "published: %s", pub->message);
        xml_close(w);
    }
    xml_close(w);
}

/* ------------------------------------------------------------------ a material's page */

/* The parameter table of a material. */
static void params_table(xml_writer *w, const rp_report *rep, const rp_material *m, int best)
{
    static const char *const head[] = { "d_r", "d_g", "d_b", "s_r", "s_g", "s_b", "p0", "p1", "p2" };
    char b[64];
    xml_open(w, "table");
    xml_open(w, "tr");
    cell(w, "th", "name", "model");
    for (int i = 0; i < 9; i++)
        cell(w, "th", NULL, head[i]);
    cell(w, "th", NULL, "Error");
    if (rep->have_published) {
        cell(w, "th", NULL, "published Error");
        cell(w, "th", NULL, "ratio");
    }
    cell(w, "th", NULL, "iterations");
    cell(w, "th", NULL, "seconds");
    cell(w, "th", "name", "on a bound");
    xml_close(w);
    for (int k = 0; k < rep->nmodels; k++) {
        const fit_record *f = m->fit[k], *p = m->published[k];
        if (!f)
            continue;
        xml_open(w, "tr");
        cell(w, "td", "name", f->model);
        if (!fr_ok(f)) {
            xml_open(w, "td");
            xml_attr(w, "class", "failed");
            xml_attr(w, "colspan", "10");
            xml_textf(w, "failed: %s: %s", fr_status_text(f), f->message);
            xml_close(w);
        } else {
            for (int c = 0; c < 3; c++)
                cell(w, "td", NULL, num(b, sizeof b, "%.4g", f->params.d[c]));
            for (int c = 0; c < 3; c++)
                cell(w, "td", NULL, num(b, sizeof b, "%.4g", f->params.s[c]));
            for (int q = 0; q < 3; q++) {
                char t[96];
                if (q < f->nparams)
                    snprintf(t, sizeof t, "%s %.4g", param_label(rep->models[k], q), f->params.p[q]);
                else
                    snprintf(t, sizeof t, "-");
                cell(w, "td", NULL, t);
            }
            snprintf(b, sizeof b, "%.5g%s", f->error, k == best ? " \xe2\x98\x85" : "");
            cell(w, "td", k == best ? "best" : NULL, b);
        }
        if (rep->have_published) {
            cell(w, "td", NULL, p && fr_ok(p) ? num(b, sizeof b, "%.5g", p->error) : p ? "invalid" : "-");
            cell(w, "td", NULL, num(b, sizeof b, "%.3g", fr_ratio(f, p)));
        }
        snprintf(b, sizeof b, "%d", f->iterations);
        cell(w, "td", NULL, f->has_counts ? b : "-");
        cell(w, "td", NULL, num(b, sizeof b, "%.2f", f->seconds));
        char bound[128] = "";
        if (f->has_counts)
            fr_at_bound_text(rep->models[k], f->at_bound, ", ", bound, sizeof bound);
        cell(w, "td", "name", bound[0] ? bound : "-");
        xml_close(w);
    }
    xml_close(w);
}

/* The figures of one kind ("image", "plot") from the assets list. */
static void figures(xml_writer *w, const rp_material *m, const char *kind, const char *title)
{
    if (!m->assets)
        return;
    int any = 0;
    const char *p = m->assets->assets;
    while (*p) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        char line[1024], href[1024];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line - 1 ? n : sizeof line - 1), p);
        p += n + (end ? 1 : 0);
        char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
        if (!t2)
            continue;
        *t1 = *t2 = '\0';
        if (strcmp(line, kind) != 0)
            continue;
        if (!any++)
            xml_element_text(w, "h2", title);
        url_segment(href, sizeof href, t1 + 1);
        if (strcmp(kind, "data") == 0) {
            xml_open(w, "p");
            link(w, href, t1 + 1);
            xml_textf(w, " %s", t2 + 1);
            xml_close(w);
            continue;
        }
        xml_open(w, "figure");
        xml_open(w, "img");
        xml_attr(w, "src", href);
        xml_attr(w, "alt", t2 + 1);
        xml_close(w);
        xml_element_text(w, "figcaption", t2 + 1);
        xml_close(w);
    }
}

static int write_material_page(const rp_report *rep, const rp_material *m, int best,
                               const char *dir, brdffit_error *err)
{
    out_file o;
    if (open_in(&o, dir, "index.html", err) != 0)
        return -1;
    xml_writer w;
    html_begin(&w, o.f, m->name);
    xml_element_text(&w, "h1", m->name);
    xml_open(&w, "p");
    link(&w, "../index.html", "all materials");
    xml_text(&w, " \xc2\xb7 ");
    link(&w, "params.tsv", "params.tsv");
    xml_text(&w, " \xc2\xb7 ");
    link(&w, "params.json", "params.json");
    xml_close(&w);
    xml_open(&w, "p");
    xml_attr(&w, "class", "note");
    if (m->id.size >= 0)
        xml_textf(&w, "table %s (%lld bytes, hash %s); metric %s, cutoff %g deg, scale %s",
                  m->id.path, m->id.size, m->id.hash, brdffit_metric_name(),
                  rep->settings.cutoff_deg, rep->settings.scale);
    else
        xml_textf(&w, "table %s", m->id.path);
    xml_close(&w);
    if (m->failure) {
        xml_open(&w, "p");
        xml_attr(&w, "class", "failed");
        xml_textf(&w, "Not fitted: %s", m->failure->message);
        xml_close(&w);
    } else {
        params_table(&w, rep, m, best);
        xml_open(&w, "p");
        xml_attr(&w, "class", "note");
        xml_text(&w, "d = Lambertian albedo (diffuse = d/pi), s = specular coefficient rho_s, "
                     "p0..p2 the lobe parameters in the paper's units; Error = ngan-l2 (1/sr); "
                     "\xe2\x98\x85 the lowest Error");
        if (rep->have_published)
            xml_text(&w, "; published Error = the Error of the published parameters on this "
                         "table, ratio = Error / published Error (below 1: this fit is closer)");
        xml_close(&w);
        figures(&w, m, "image", "Renders (reference and each model, same exposure)");
        figures(&w, m, "diff", "Differences from the reference");
        figures(&w, m, "plot", "Incidence-plane plots (cube root)");
        figures(&w, m, "data", "Data: linear images (OpenEXR, alpha = coverage), render settings");
    }
    html_end(&w);
    return finish(&o, &w, err);
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

static int write_headline(const rp_report *rep, const char *dir, int sort_k, brdffit_error *err)
{
    out_file o;
    if (open_in(&o, dir, "headline.svg", err) != 0)
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

static int write_fits_tsv(const rp_report *rep, const char *dir, brdffit_error *err)
{
    out_file o;
    if (open_in(&o, dir, "fits.tsv", err) != 0)
        return -1;
    fprintf(o.f, "# every fit of the report: metric %s, cutoff %g deg, scale %s, starts %d, "
                 "brdffit %s; ratio = error / published_error; the columns: docs/fit-record.md\n",
            brdffit_metric_name(), rep->settings.cutoff_deg, rep->settings.scale,
            rep->settings.starts, rep->settings.version);
    fr_write_tsv_header(o.f);
    for (int i = 0; i < rep->n; i++)
        tsv_material(o.f, rep, &rep->m[i]);
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ DIR/index.html */

static void summary_table(xml_writer *w, const rp_report *rep)
{
    char b[64];
    xml_open(w, "table");
    xml_open(w, "tr");
    cell(w, "th", "name", "model");
    cell(w, "th", NULL, "median Error");
    cell(w, "th", NULL, "best on");
    cell(w, "th", NULL, "fitted");
    xml_close(w);
    for (int k = 0; k < rep->nmodels; k++) {
        int nbest = 0, nfit = 0;
        double med = rp_median(rep, k, &nbest, &nfit);
        xml_open(w, "tr");
        cell(w, "td", "name", brdffit_model_get(rep->models[k])->title);
        cell(w, "td", NULL, num(b, sizeof b, "%.4g", med));
        snprintf(b, sizeof b, "%d", nbest);
        cell(w, "td", NULL, b);
        snprintf(b, sizeof b, "%d of %d", nfit, rep->n);
        cell(w, "td", NULL, b);
        xml_close(w);
    }
    xml_close(w);
}

static void error_matrix(xml_writer *w, const rp_report *rep)
{
    char href[BJ_NAME_MAX * 3 + 16];
    xml_open(w, "table");
    xml_open(w, "tr");
    cell(w, "th", "name", "material");
    for (int k = 0; k < rep->nmodels; k++)
        cell(w, "th", NULL, brdffit_model_get(rep->models[k])->name);
    xml_close(w);
    for (int i = 0; i < rep->n; i++) {
        const rp_material *m = &rep->m[i];
        int best = rp_best(rep, i);
        xml_open(w, "tr");
        xml_open(w, "td");
        xml_attr(w, "class", "name");
        url_segment(href, sizeof href - 12, m->name);
        strcat(href, "/index.html");
        link(w, href, m->name);
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

static int write_index(const rp_report *rep, const char *dir, int sort_k, brdffit_error *err)
{
    out_file o;
    if (open_in(&o, dir, "index.html", err) != 0)
        return -1;
    xml_writer w;
    int failed = 0;
    for (int i = 0; i < rep->n; i++)
        failed += rep->m[i].failure != NULL;
    char title[256];
    snprintf(title, sizeof title, "brdffit report: %d material%s, %d model%s", rep->n,
             rep->n == 1 ? "" : "s", rep->nmodels, rep->nmodels == 1 ? "" : "s");
    html_begin(&w, o.f, title);
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
    link(&w, "fits.tsv", "fits.tsv");
    xml_close(&w);
    html_end(&w);
    return finish(&o, &w, err);
}

/* ------------------------------------------------------------------ all of it */

/* Copy the asset files of a material kept in another directory (a shard). */
static int copy_assets(const rp_material *m, const char *mdir, brdffit_error *err)
{
    if (!m->assets || !m->asset_dir[0] || strcmp(m->asset_dir, mdir) == 0)
        return 0;
    const char *p = m->assets->assets;
    while (*p) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        char line[1024], from[BJ_PATH_MAX], to[BJ_PATH_MAX];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line - 1 ? n : sizeof line - 1), p);
        p += n + (end ? 1 : 0);
        char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
        if (!t2)
            continue;
        *t2 = '\0';
        if (strchr(t1 + 1, '/') || out_join(from, sizeof from, m->asset_dir, t1 + 1) != 0 ||
            out_join(to, sizeof to, mdir, t1 + 1) != 0 || out_copy(from, to, err) != 0)
            return -1;
    }
    return 0;
}

int rp_write(const rp_report *rep, const char *dir, brdffit_error *err)
{
    for (int i = 0; i < rep->n; i++) {
        const rp_material *m = &rep->m[i];
        char mdir[BJ_PATH_MAX];
        if (out_join(mdir, sizeof mdir, dir, m->name) != 0 || out_mkdir(mdir, err) != 0 ||
            copy_assets(m, mdir, err) != 0 || write_params_tsv(rep, m, mdir, err) != 0 ||
            write_params_json(rep, m, mdir, err) != 0 ||
            write_material_page(rep, m, rp_best(rep, i), mdir, err) != 0)
            return -1;
        cli_fault_point("page");
    }
    int sort_k = rp_sort_model(rep);
    if (write_fits_tsv(rep, dir, err) != 0 || write_headline(rep, dir, sort_k, err) != 0 ||
        write_index(rep, dir, sort_k, err) != 0)
        return -1;
    return 0;
}
