/* SPDX-License-Identifier: MIT */
/* fit_record_albedo.c -- the fit record's energy fields: the fitted model's
 * directional albedo on the grid theta_o = 0, 5, ..., 85 deg
 * (brdffit_albedo_model), its maximum and where, the measured table's
 * albedo on the same grid (brdffit_albedo_table) and how far the model's
 * departs from it; their JSON and TSV.  docs/fit-record.md defines them. */
#define _POSIX_C_SOURCE 200809L
#include "fit_record.h"
#include "fit_record_parts.h"
#include "batch.h"
#include "cli.h"

#include <math.h>
#include <string.h>

void fr_albedo_angles(double theta_o_deg[FR_ALBEDO_N])
{
    for (int k = 0; k < FR_ALBEDO_N; k++)
        theta_o_deg[k] = FR_ALBEDO_STEP_DEG * k;
}

double fr_luminance(const double rgb[3])
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

int fr_albedo_measure(const brdffit_table *table, brdffit_scale scale,
                      double out[FR_ALBEDO_N][3])
{
    double th[FR_ALBEDO_N];
    fr_albedo_angles(th);
    return brdffit_albedo_table(table, scale, BRDFFIT_INTERP_TRILINEAR, FR_ALBEDO_N, th, &out[0][0],
                                NULL, NULL) == BRDFFIT_OK
               ? 0
               : -1;
}

/* The departure of the model's albedo from the measured one (luminance),
 * over the theta_o the fit saw: up to its cutoff (80 deg when not known). */
static void departure(fit_record *r)
{
    r->albedo_departure = r->albedo_departure_theta_o = NAN;
    if (!r->has_albedo || !r->has_albedo_measured)
        return;
    double worst = -1, cutoff = r->settings.cutoff_deg > 0 ? r->settings.cutoff_deg : 80;
    for (int k = 0; k < FR_ALBEDO_N && FR_ALBEDO_STEP_DEG * k <= cutoff; k++) {
        double m = fr_luminance(r->albedo[k]), t = fr_luminance(r->albedo_measured[k]);
        double d = fabs(m - t) / fmax(t, FR_ALBEDO_FLOOR);
        if (d > worst) {
            worst = d;
            r->albedo_departure_theta_o = FR_ALBEDO_STEP_DEG * k;
        }
    }
    r->albedo_departure = worst;
}

/* albedo_max and where, from the curve. */
static void maximum(fit_record *r)
{
    r->albedo_max = r->albedo_max_theta_o = NAN;
    if (!r->has_albedo)
        return;
    double best = -1;
    for (int k = 0; k < FR_ALBEDO_N; k++)
        for (int c = 0; c < 3; c++)
            if (r->albedo[k][c] > best) {
                best = r->albedo[k][c];
                r->albedo_max_theta_o = FR_ALBEDO_STEP_DEG * k;
            }
    r->albedo_max = best;
}

void fr_set_albedo(fit_record *r, brdffit_model model, const double measured[FR_ALBEDO_N][3])
{
    double th[FR_ALBEDO_N], t0 = brdffit_seconds();
    fr_albedo_angles(th);
    r->has_albedo = r->has_params &&
                    brdffit_albedo_model(model, &r->params, FR_ALBEDO_N, th, &r->albedo[0][0],
                                         NULL) == BRDFFIT_OK;
    r->seconds_albedo = r->has_albedo ? brdffit_seconds() - t0 : NAN;
    r->has_albedo_measured = measured != NULL;
    if (measured)
        memcpy(r->albedo_measured, measured, sizeof r->albedo_measured);
    maximum(r);
    departure(r);
}

int fr_albedo_exceeds(const fit_record *r)
{
    return r->has_albedo && r->albedo_max > FR_ALBEDO_MAX_OK;
}

int fr_albedo_departs(const fit_record *r)
{
    return r->has_albedo && r->has_albedo_measured && r->albedo_departure > FR_ALBEDO_DEPARTS;
}

/* ------------------------------------------------------------------ JSON, TSV */

/* A curve: 54 numbers, R, G, B at each theta_o, to 6 digits (the
 * quadrature's accuracy is 1e-4). */
static void json_curve(FILE *f, const char *key, int have, const double a[FR_ALBEDO_N][3])
{
    fprintf(f, ",\"%s\":", key);
    if (!have) {
        fputs("null", f);
        return;
    }
    for (int i = 0; i < 3 * FR_ALBEDO_N; i++)
        fprintf(f, "%c%.6g", i ? ',' : '[', a[i / 3][i % 3]);
    putc(']', f);
}

void fr_albedo_write_json(FILE *f, const fit_record *r)
{
    json_curve(f, "albedo", r->has_albedo, r->albedo);
    fputs(",\"albedo_max\":", f);
    json_number(f, r->albedo_max);
    fputs(",\"albedo_max_theta_o\":", f);
    json_number(f, r->albedo_max_theta_o);
    json_curve(f, "albedo_measured", r->has_albedo_measured, r->albedo_measured);
    fputs(",\"albedo_departure\":", f);
    json_number(f, r->albedo_departure);
    fputs(",\"albedo_departure_theta_o\":", f);
    json_number(f, r->albedo_departure_theta_o);
    fputs(",\"seconds_albedo\":", f);
    json_number(f, r->seconds_albedo);
}

/* A curve: 1 read, 0 null or absent, -1 anything else. */
static int read_curve(const jr_object *o, const char *key, double a[FR_ALBEDO_N][3])
{
    const jr_member *m = jr_get(o, key);
    if (!m || m->type == JR_NULL)
        return 0;
    if (m->type != JR_ARRAY || m->narr != 3 * FR_ALBEDO_N || m->str)
        return -1;
    for (int i = 0; i < 3 * FR_ALBEDO_N; i++) {
        if (!isfinite(m->arr[i]))
            return -1;
        a[i / 3][i % 3] = m->arr[i];
    }
    return 1;
}

int fr_albedo_read_json(const jr_object *o, fit_record *r)
{
    int ha = read_curve(o, "albedo", r->albedo);
    int hm = ha < 0 ? -1 : read_curve(o, "albedo_measured", r->albedo_measured);
    if (ha < 0 || hm < 0)
        return -1;
    const jr_member *s = jr_get(o, "seconds_albedo");
    if (s && s->type != JR_NUMBER && s->type != JR_NULL)
        return -1;
    r->seconds_albedo = s && s->type == JR_NUMBER ? s->num : NAN;
    r->has_albedo = ha;
    r->has_albedo_measured = hm;
    /* the maximum and the departure follow from the curves */
    maximum(r);
    departure(r);
    return 0;
}

void fr_albedo_tsv_header(FILE *f)
{
    fputs("\talbedo_max\talbedo_max_theta_o\talbedo_departure\talbedo_departure_theta_o", f);
}

void fr_albedo_tsv_row(FILE *f, const fit_record *r)
{
    const double v[4] = { r->albedo_max, r->albedo_max_theta_o, r->albedo_departure,
                          r->albedo_departure_theta_o };
    for (int k = 0; k < 4; k++) {
        putc('\t', f);
        if (isfinite(v[k]))
            fprintf(f, k % 2 ? "%g" : "%.6g", v[k]);
        else
            putc('-', f);
    }
}
