/* SPDX-License-Identifier: MIT */
/* html_headline.c -- DIR/headline.svg: every model's Error per material, log
 * scale, materials sorted by the Error of one model.  Made to be read at
 * 100%: at most HL_PER_PANEL materials a panel (panels stacked), every
 * material labelled, its name and each point's value on hover (<title>);
 * the y range is that of the bulk of the Errors (Tukey's far-out fences on
 * log10 Error), a point beyond it is a triangle at the edge, not a stretched
 * axis. */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define HL_PER_PANEL 50
#define HL_W 1100.0
#define HL_L 72.0    /* left: tick labels and the y label */
#define HL_R 180.0   /* right: the legend */
#define HL_T 56.0    /* top: the title and the note */
#define HL_PH 250.0  /* a panel's plot height */
#define HL_LB 128.0  /* under a panel: the material names */
#define HL_FENCE 3.0 /* far-out fences: quartile -/+ 3 IQR (decades), IQR at least HL_MIN_IQR */
#define HL_MIN_IQR 0.5

typedef struct order_item {
    int i;
    double e;   /* the sort model's Error */
    int any;    /* the material has an Error of some model */
} order_item;

typedef struct headline {
    const rp_report *rep;
    const order_item *ord;
    int np;          /* materials drawn */
    int npanels, per;
    int lo, hi;      /* log10 of the axis ends */
    int below, above; /* points beyond them */
} headline;

/* The palette has 8 colours: a model past them (its colour repeats an
 * earlier one's) is drawn dashed, its points hollow. */
static int second_round(const rp_report *rep, int k)
{
    return (int)rep->models[k] >= 8;
}

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

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The q-quantile of sorted v[0..n) (linear between order statistics). */
static double quantile(const double *v, int n, double q)
{
    double pos = q * (n - 1);
    int i = (int)floor(pos);
    return i + 1 < n ? v[i] + (pos - i) * (v[i + 1] - v[i]) : v[n - 1];
}

/* The axis: whole decades around the bulk of the Errors. */
static void y_range(headline *h)
{
    const rp_report *rep = h->rep;
    double *v = malloc((size_t)(rep->n * rep->nmodels + 1) * sizeof *v);
    int n = 0;
    for (int i = 0; v && i < rep->n; i++)
        for (int k = 0; k < rep->nmodels; k++) {
            double e = fit_error(&rep->m[i], k);
            if (isfinite(e))
                v[n++] = log10(e);
        }
    h->lo = -3;
    h->hi = 0;
    if (n > 0) {
        qsort(v, (size_t)n, sizeof *v, cmp_double);
        double q1 = quantile(v, n, 0.25), q3 = quantile(v, n, 0.75);
        double iqr = fmax(q3 - q1, HL_MIN_IQR);
        double a = fmax(v[0], q1 - HL_FENCE * iqr), b = fmin(v[n - 1], q3 + HL_FENCE * iqr);
        h->lo = (int)floor(a);
        h->hi = (int)ceil(b);
    }
    if (h->hi <= h->lo)
        h->hi = h->lo + 1;
    free(v);
}

static double panel_top(int p)
{
    return HL_T + p * (HL_PH + HL_LB);
}

static double x_of(const headline *h, int j)
{
    int slot = j % h->per;
    return HL_L + (HL_W - HL_L - HL_R) * (slot + 0.5) / h->per;
}

/* y of log10 value d in panel p, clamped to the plot. */
static double y_of(const headline *h, int p, double d)
{
    double t = (d - h->lo) / (h->hi - h->lo);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return panel_top(p) + HL_PH * (1 - t);
}

static void titled(xml_writer *w, const char *title)
{
    xml_element_text(w, "title", title);
    xml_close(w);
}

static void panel_axes(xml_writer *w, const headline *h, int p)
{
    double pw = HL_W - HL_L - HL_R, top = panel_top(p);
    svg_rect(w, HL_L, top, pw, HL_PH, NULL, "#888888");
    for (int d = h->lo; d <= h->hi; d++) {
        double y = y_of(h, p, d);
        char t[32];
        if (d >= -3 && d <= 3)
            snprintf(t, sizeof t, "%g", pow(10, d));
        else
            snprintf(t, sizeof t, "1e%d", d);
        svg_line(w, HL_L, y, HL_L + pw, y, "#dddddd", 1, NULL);
        svg_text(w, HL_L - 6, y + 4, "end", 12, t);
        for (int m = 2; m <= 9 && d < h->hi; m++) {
            double ym = y_of(h, p, d + log10((double)m));
            svg_line(w, HL_L, ym, HL_L + 4, ym, "#888888", 1, NULL);
        }
    }
    svg_text_rotated(w, 18, top + HL_PH / 2, -90, "middle", 13, "Error (ngan-l2, 1/sr)");
    /* every material: its name under the panel, its column named on hover */
    double col = pw / h->per;
    for (int j = p * h->per; j < h->np && j < (p + 1) * h->per; j++) {
        const char *name = h->rep->m[h->ord[j].i].name;
        double x = x_of(h, j);
        xml_open(w, "rect"); /* invisible, its column named on hover */
        xml_attr_num(w, "x", x - col / 2);
        xml_attr_num(w, "y", top);
        xml_attr_num(w, "width", col);
        xml_attr_num(w, "height", HL_PH);
        xml_attr(w, "fill", "#ffffff");
        xml_attr(w, "fill-opacity", "0");
        titled(w, name);
        svg_line(w, x, top + HL_PH, x, top + HL_PH + 4, "#888888", 1, NULL);
        xml_open(w, "text");
        xml_attr_num(w, "x", x + 4);
        xml_attr_num(w, "y", top + HL_PH + 12);
        xml_attr(w, "text-anchor", "end");
        xml_attr_num(w, "font-size", h->per > 30 ? 11 : 12);
        xml_attrf(w, "transform", "rotate(-55 %.6g %.6g)", x + 4, top + HL_PH + 12);
        xml_text(w, name);
        xml_close(w);
    }
}

/* A point of model slot k, material j (Error e): a circle, or beyond the
 * axis a triangle at its edge; its value on hover. */
static void point(xml_writer *w, headline *h, int j, int k, double e)
{
    const rp_report *rep = h->rep;
    const char *col = svg_color((int)rep->models[k]);
    int p = j / h->per;
    double x = x_of(h, j), d = log10(e), y = y_of(h, p, d);
    int out = d < h->lo || d > h->hi, up = d > h->hi;
    char t[BJ_NAME_MAX + 160], v[32];
    snprintf(t, sizeof t, "%s \xe2\x80\x94 %s: %s%s", rep->m[h->ord[j].i].name,
             brdffit_model_get(rep->models[k])->title, rp_compact(v, sizeof v, 4, e),
             !out ? "" : up ? " (above the axis)" : " (below the axis)");
    if (out) {
        h->above += up;
        h->below += !up;
        xml_open(w, "path");
        xml_attrf(w, "d", "M%.2f %.2fl-4.5 %dh9z", x, y, up ? 8 : -8);
        xml_attr(w, "fill", col);
        titled(w, t);
        return;
    }
    xml_open(w, "circle");
    xml_attr_num(w, "cx", x);
    xml_attr_num(w, "cy", y);
    xml_attr_num(w, "r", 3);
    xml_attr(w, "fill", second_round(rep, k) ? "#ffffff" : col);
    xml_attr(w, "stroke", col);
    titled(w, t);
}

/* Model slot k across the materials: its line (broken by a gap, a panel's
 * end or a point beyond the axis), then its points. */
static void series(xml_writer *w, headline *h, int k)
{
    const rp_report *rep = h->rep;
    double x[HL_PER_PANEL], y[HL_PER_PANEL];
    const char *col = svg_color((int)rep->models[k]);
    int run = 0;
    for (int j = 0; j <= h->np; j++) {
        double e = j < h->np ? fit_error(&rep->m[h->ord[j].i], k) : NAN;
        double d = isfinite(e) ? log10(e) : NAN;
        int in = isfinite(d) && d >= h->lo && d <= h->hi;
        if (run > 0 && (!in || j % h->per == 0)) {
            svg_polyline(w, x, y, run, col, 1.2, second_round(rep, k) ? "6,3" : NULL);
            run = 0;
        }
        if (in) {
            x[run] = x_of(h, j);
            y[run] = y_of(h, j / h->per, d);
            run++;
        }
    }
    for (int j = 0; j < h->np; j++) {
        double e = fit_error(&rep->m[h->ord[j].i], k);
        if (isfinite(e))
            point(w, h, j, k, e);
    }
}

static void legend(xml_writer *w, const rp_report *rep)
{
    for (int k = 0; k < rep->nmodels; k++) {
        double ly = HL_T + 10 + 20 * k, lx = HL_W - HL_R + 16;
        const char *col = svg_color((int)rep->models[k]);
        int two = second_round(rep, k);
        svg_line(w, lx, ly, lx + 22, ly, col, 2, two ? "6,3" : NULL);
        svg_circle(w, lx + 11, ly, 3, two ? "#ffffff" : col, col);
        svg_text(w, lx + 28, ly + 4, "start", 13, brdffit_model_get(rep->models[k])->title);
    }
}

static void draw(xml_writer *w, headline *h, int sort_k)
{
    const rp_report *rep = h->rep;
    char title[256];
    snprintf(title, sizeof title, "Error of every model per material, materials sorted by %s's Error",
             sort_k >= 0 ? brdffit_model_get(rep->models[sort_k])->title : "(none)");
    xml_element_text(w, "title", title);
    svg_text(w, (HL_W - HL_R) / 2, 22, "middle", 16, title);
    for (int p = 0; p < h->npanels; p++)
        panel_axes(w, h, p);
    for (int k = 0; k < rep->nmodels; k++)
        series(w, h, k);
    legend(w, rep);
    char note[256] = "log scale; hover a point for its material, model and Error";
    if (h->below || h->above)
        snprintf(note + strlen(note), sizeof note - strlen(note),
                 "; \xe2\x96\xb2 / \xe2\x96\xbc: %d above / %d below the axis, "
                 "which shows the bulk of the Errors", h->above, h->below);
    svg_text(w, (HL_W - HL_R) / 2, 42, "middle", 12, note);
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
    headline h;
    memset(&h, 0, sizeof h);
    h.rep = rep;
    h.ord = ord;
    for (int i = 0; i < rep->n; i++) {
        ord[i].i = i;
        ord[i].e = sort_k >= 0 ? fit_error(&rep->m[i], sort_k) : NAN;
        ord[i].any = 0;
        for (int k = 0; k < rep->nmodels; k++)
            ord[i].any |= isfinite(fit_error(&rep->m[i], k));
        h.np += ord[i].any;
    }
    qsort(ord, (size_t)rep->n, sizeof *ord, by_error);
    h.npanels = h.np > 0 ? (h.np + HL_PER_PANEL - 1) / HL_PER_PANEL : 1;
    h.per = h.np > 0 ? (h.np + h.npanels - 1) / h.npanels : 1;
    y_range(&h);
    xml_writer w;
    svg_begin(&w, o.f, HL_W, panel_top(h.npanels) + 8);
    draw(&w, &h, sort_k);
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
