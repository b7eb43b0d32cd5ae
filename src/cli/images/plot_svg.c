/* SPDX-License-Identifier: MIT */
/* plot_svg.c -- the incidence-plane plot of a material (SVG): measured curves
 * solid, a model's dashed, one colour per theta_i, cube root of the channel
 * mean on the y axis with ticks labelled in 1/sr. */
#include "render_files.h"
#include "svg.h"
#include "image_io.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Plot geometry (px). */
#define PW 640.0
#define PH 440.0
#define ML 78.0   /* left margin: tick labels and the y label */
#define MR 150.0  /* right margin: the legend */
#define MT 46.0   /* top: the title */
#define MB 56.0   /* bottom: tick labels and the x label */
#define DASH "7,4"

typedef struct axes {
    double ymax; /* top of the y axis, in cube-root units */
} axes;

static double px_x(double theta_o)
{
    return ML + (theta_o + 90.0) / 180.0 * (PW - ML - MR);
}

static double px_y(const axes *ax, double y)
{
    return PH - MB - y / ax->ymax * (PH - MT - MB);
}

/* The plotted value of a point: cube root of the channel mean, or -1 when
 * some channel is masked (negative). */
double plot_value(const double rgb[3])
{
    if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0)
        return -1;
    return cbrt((rgb[0] + rgb[1] + rgb[2]) / 3.0);
}

static double curve_max(const double *rgb, size_t stride, int ncurves, int npoints)
{
    double m = 0;
    for (int a = 0; a < ncurves; a++)
        for (int k = 0; k < npoints; k++) {
            double v = plot_value(rgb + (size_t)a * stride + 3 * (size_t)k);
            if (isfinite(v))
                m = fmax(m, v);
        }
    return m;
}

/* Polyline segments of one curve, broken at masked points. */
static void draw_curve(xml_writer *w, const axes *ax, const double *theta_o, const double *rgb,
                       int npoints, const char *colour, const char *dash)
{
    double x[2048], y[2048];
    int n = 0;
    for (int k = 0; k <= npoints; k++) {
        double v = k < npoints ? plot_value(rgb + 3 * (size_t)k) : -1;
        if (v >= 0 && isfinite(v)) {
            if (n == 2048) { /* a full buffer: draw it, continue from its last point */
                svg_polyline(w, x, y, n, colour, 1.6, dash);
                x[0] = x[n - 1], y[0] = y[n - 1], n = 1;
            }
            x[n] = px_x(theta_o[k]);
            y[n] = px_y(ax, v);
            n++;
            continue;
        }
        if (n == 1)
            svg_circle(w, x[0], y[0], 1.2, colour, NULL);
        svg_polyline(w, x, y, n, colour, 1.6, dash);
        n = 0;
    }
}

/* Tick values in 1/sr: 0 and 1-2-5 values whose cube roots fall in the
 * axis, at least 8% of the axis apart; powers of ten are placed first, then
 * 5s, then 2s, so the labels read as decades where room is short. */
static int y_ticks(const axes *ax, double *t, int max)
{
    static const double mult[3] = { 1, 5, 2 };
    double top = ax->ymax * ax->ymax * ax->ymax, gap = 0.08 * ax->ymax;
    int n = 0;
    t[n++] = 0;
    for (int m = 0; m < 3; m++)
        for (int e = 6; e >= -6; e--) {
            double v = mult[m] * pow(10.0, e), y = cbrt(v);
            int ok = v <= top && n < max;
            for (int i = 0; i < n && ok; i++)
                ok = fabs(cbrt(t[i]) - y) >= gap;
            if (ok)
                t[n++] = v;
        }
    return n;
}

static void draw_axes(xml_writer *w, const axes *ax)
{
    double x0 = ML, x1 = PW - MR, y0 = PH - MB, y1 = MT;
    char buf[64];
    svg_rect(w, x0, y1, x1 - x0, y0 - y1, NULL, "#000000");
    for (int d = -90; d <= 90; d += 30) {
        double x = px_x(d);
        svg_line(w, x, y0, x, y0 + 5, "#000000", 1, NULL);
        if (d != -90 && d != 90)
            svg_line(w, x, y1, x, y0, "#dddddd", 0.8, NULL);
        snprintf(buf, sizeof buf, "%d", d);
        svg_text(w, x, y0 + 19, "middle", 12, buf);
    }
    double t[32];
    int n = y_ticks(ax, t, 32);
    for (int i = 0; i < n; i++) {
        double y = px_y(ax, cbrt(t[i]));
        svg_line(w, x0 - 5, y, x0, y, "#000000", 1, NULL);
        if (t[i] > 0)
            svg_line(w, x0, y, x1, y, "#eeeeee", 0.8, NULL);
        snprintf(buf, sizeof buf, "%g", t[i]);
        svg_text(w, x0 - 8, y + 4, "end", 12, buf);
    }
    svg_text(w, (x0 + x1) / 2, PH - 14, "middle", 13,
             "\xce\xb8o (degrees), incidence plane; > 0 on the mirror side");
    svg_text_rotated(w, 18, (y0 + y1) / 2, -90, "middle", 13,
                     "f (1/sr), cube-root axis; mean of R, G, B");
}

static void draw_legend(xml_writer *w, const brdffit_curve_options *o, int with_model)
{
    double x = PW - MR + 14, y = MT + 12;
    char buf[64];
    for (int a = 0; a < o->ntheta_i; a++, y += 20) {
        svg_line(w, x, y - 4, x + 26, y - 4, svg_color(a), 2.5, NULL);
        snprintf(buf, sizeof buf, "\xce\xb8i = %g\xc2\xb0", o->theta_i_deg[a]);
        svg_text(w, x + 32, y, "start", 12, buf);
    }
    y += 10;
    svg_line(w, x, y - 4, x + 26, y - 4, "#000000", 1.6, NULL);
    svg_text(w, x + 32, y, "start", 12, "measured");
    if (with_model) {
        y += 20;
        svg_line(w, x, y - 4, x + 26, y - 4, "#000000", 1.6, DASH);
        svg_text(w, x + 32, y, "start", 12, "model");
    }
}

int plot_write_svg(const out_dir *dir, const char *name, const char *title, const brdffit_curve_options *o,
                   const double *theta_o, const double *measured, const double *model,
                   size_t stride, brdffit_error *err)
{
    int np = o->npoints, nc = o->ntheta_i;
    if (stride == 0)
        stride = 3 * (size_t)np;
    double mmax = curve_max(measured, stride, nc, np);
    double fmax_ = model ? curve_max(model, stride, nc, np) : 0;
    /* a model that shoots up at grazing angles is clipped rather than
     * squashing the measured curves: the axis ends at 1.5x the measured top */
    double top = mmax > 0 ? fmax(mmax, fmin(fmax_, 1.5 * mmax)) : fmax_;
    axes ax = { top > 0 ? 1.08 * top : 1.0 };
    out_file of;
    if (out_open(&of, dir, name, err) != 0)
        return -1;
    FILE *f = of.f;
    xml_writer w;
    svg_begin(&w, f, PW, PH);
    xml_element_text(&w, "title", title);
    svg_text(&w, (ML + PW - MR) / 2, 26, "middle", 15, title);
    draw_axes(&w, &ax);
    xml_open(&w, "defs");
    xml_open(&w, "clipPath");
    xml_attr(&w, "id", "plot-area");
    svg_rect(&w, ML, MT, PW - MR - ML, PH - MT - MB, "#000000", NULL);
    xml_close(&w);
    xml_close(&w);
    xml_open(&w, "g");
    xml_attr(&w, "clip-path", "url(#plot-area)");
    for (int a = 0; a < nc; a++) {
        draw_curve(&w, &ax, theta_o, measured + (size_t)a * stride, np, svg_color(a), NULL);
        if (model)
            draw_curve(&w, &ax, theta_o, model + (size_t)a * stride, np, svg_color(a), DASH);
    }
    xml_close(&w);
    draw_legend(&w, o, model != NULL);
    if (svg_end(&w) != 0 && !ferror(f)) {
        out_abandon(&of);
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "%.1800s: cannot write the SVG plot", of.path);
        return -1;
    }
    return out_commit(&of, err);
}
