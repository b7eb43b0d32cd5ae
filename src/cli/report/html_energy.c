/* SPDX-License-Identifier: MIT */
/* html_energy.c -- the energy section of a material's page: each fit's
 * directional albedo against the measured table's (fit_record_albedo.c), the
 * fits flagged for reflecting more than they receive (albedo above 1) or for
 * departing from the table by more than 10%, and a small plot of the two
 * curves (luminance) per fit.  docs/batch-report.md explains the flags. */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PLOT_W 220.0
#define PLOT_H 150.0
#define LEFT 38.0
#define RIGHT 8.0
#define TOP 18.0
#define BOTTOM 26.0

/* The upper end of a plot's y axis: the larger curve, and 1 when it is near. */
static double y_top(const fit_record *r)
{
    double top = 0;
    for (int k = 0; k < FR_ALBEDO_N; k++) {
        top = fmax(top, fr_luminance(r->albedo[k]));
        if (r->has_albedo_measured)
            top = fmax(top, fr_luminance(r->albedo_measured[k]));
    }
    if (top > 0.8 && top < 1.05)
        top = 1.05;
    return top > 0 ? top * 1.08 : 1;
}

static void curve(xml_writer *w, const double a[FR_ALBEDO_N][3], double top, const char *colour,
                  double width, const char *dash)
{
    double x[FR_ALBEDO_N], y[FR_ALBEDO_N];
    for (int k = 0; k < FR_ALBEDO_N; k++) {
        x[k] = LEFT + (PLOT_W - LEFT - RIGHT) * (FR_ALBEDO_STEP_DEG * k) / 90.0;
        y[k] = PLOT_H - BOTTOM - (PLOT_H - TOP - BOTTOM) * fr_luminance(a[k]) / top;
    }
    svg_polyline(w, x, y, FR_ALBEDO_N, colour, width, dash);
}

/* The plot of one fit: axes, the measured curve (black), the model's. */
static void plot(xml_writer *w, const fit_record *r, int k)
{
    double top = y_top(r), x0 = LEFT, x1 = PLOT_W - RIGHT, y0 = PLOT_H - BOTTOM, y1 = TOP;
    char label[64];
    xml_open(w, "svg");
    xml_attr(w, "xmlns", "http://www.w3.org/2000/svg");
    xml_attr_num(w, "width", PLOT_W);
    xml_attr_num(w, "height", PLOT_H);
    xml_attrf(w, "viewBox", "0 0 %g %g", PLOT_W, PLOT_H);
    xml_attr(w, "role", "img");
    xml_attrf(w, "aria-label", "directional albedo of %s and of the table against theta_o",
              r->model);
    svg_rect(w, 0, 0, PLOT_W, PLOT_H, "#ffffff", NULL);
    svg_line(w, x0, y0, x1, y0, "#888888", 1, NULL);
    svg_line(w, x0, y0, x0, y1, "#888888", 1, NULL);
    for (int t = 0; t <= 90; t += 30) {
        double x = x0 + (x1 - x0) * t / 90.0;
        snprintf(label, sizeof label, "%d", t);
        svg_text(w, x, y0 + 12, "middle", 9, label);
    }
    svg_text(w, (x0 + x1) / 2, PLOT_H - 3, "middle", 9, "theta_o (deg)");
    snprintf(label, sizeof label, "%.2g", top);
    svg_text(w, x0 - 3, y1 + 4, "end", 9, label);
    svg_text(w, x0 - 3, y0, "end", 9, "0");
    if (top > 1) {
        double y = y0 - (y0 - y1) / top;
        svg_line(w, x0, y, x1, y, "#cc0000", 0.8, "4,3");
        svg_text(w, x0 - 3, y + 3, "end", 9, "1");
    }
    if (r->has_albedo_measured)
        curve(w, r->albedo_measured, top, "#000000", 2, NULL);
    curve(w, r->albedo, top, svg_color(k), 1.5, "5,2");
    svg_text(w, x0 + 4, TOP - 6, "start", 10, r->model);
    xml_close(w);
}

static void flags_text(const fit_record *r, char *buf, size_t len)
{
    char a[32], b[32];
    snprintf(buf, len, "max %s at %g deg",
             rp_num(a, sizeof a, "%.3f", r->albedo_max), r->albedo_max_theta_o);
    if (isfinite(r->albedo_departure)) {
        size_t n = strlen(buf);
        snprintf(buf + n, len - n, "; departs %s%% at %g deg",
                 rp_num(b, sizeof b, "%.1f", 100 * r->albedo_departure), r->albedo_departure_theta_o);
    }
    if (fr_albedo_exceeds(r))
        strncat(buf, " \xe2\x9a\xa0 exceeds 1", len - strlen(buf) - 1);
    if (fr_albedo_departs(r))
        strncat(buf, " \xe2\x9a\xa0 departs > 10%", len - strlen(buf) - 1);
}

void rp_energy_section(xml_writer *w, const rp_report *rep, const rp_material *m)
{
    int any = 0;
    for (int k = 0; k < rep->nmodels; k++)
        any += m->fit[k] && m->fit[k]->has_albedo;
    if (!any)
        return;
    xml_element_text(w, "h2", "Energy: directional albedo");
    xml_open(w, "p");
    xml_attr(w, "class", "note");
    xml_text(w, "a(theta_o) = the integral of f cos theta_i over the hemisphere, luminance "
                "(0.2126 R + 0.7152 G + 0.0722 B); black: the measured table, dashed: the fit. "
                "\xe2\x9a\xa0 exceeds 1: the fit reflects more than it receives at some theta_o "
                "(some channel above 1.0001); \xe2\x9a\xa0 departs: its luminance albedo differs "
                "from the table's by more than 10% at some theta_o up to the cutoff.");
    xml_close(w);
    for (int k = 0; k < rep->nmodels; k++) {
        const fit_record *r = m->fit[k];
        if (!r || !r->has_albedo)
            continue;
        char text[256];
        flags_text(r, text, sizeof text);
        xml_open(w, "figure");
        xml_attr(w, "class", fr_albedo_exceeds(r) || fr_albedo_departs(r) ? "energy flagged" : "energy");
        plot(w, r, k);
        xml_element_text(w, "figcaption", text);
        xml_close(w);
    }
}
