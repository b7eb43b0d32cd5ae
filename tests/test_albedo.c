/* SPDX-License-Identifier: MIT */
/* test_albedo.c -- the directional albedo (brdffit_albedo_model, _table)
 * against closed forms, white-furnace limits, a 1-D integral at the normal,
 * and brute-force sums written here (a dense midpoint grid over wi: nothing
 * of the library's quadrature), with its refusals and its values at every
 * model's bounds. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "batch.h"
#include "html_report.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const double GRID[18] = { 0, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 75, 80, 85 };

static brdffit_params params_of(brdffit_model m, double d, double s, const double *p)
{
    brdffit_params pa;
    memset(&pa, 0, sizeof pa);
    for (int c = 0; c < 3; c++) {
        pa.d[c] = d;
        pa.s[c] = s;
    }
    for (int k = 0; k < brdffit_model_get(m)->nparams; k++)
        pa.p[k] = p[k];
    return pa;
}

static double albedo1(brdffit_model m, const brdffit_params *pa, double theta_o, int c)
{
    double rgb[3];
    brdffit_error err;
    ck_assert_msg(brdffit_albedo_model(m, pa, 1, &theta_o, rgb, &err) == BRDFFIT_OK, "%s",
                  err.message);
    return rgb[c];
}

/* Every paper model with s = 0 is the Lambertian d/pi: a = d at every theta_o. */
START_TEST(lambertian_gives_d)
{
    const double d[3] = { 0.8, 0.35, 0.05 };
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        if (mi->colour_form != BRDFFIT_COLOUR_DS)
            continue;
        double p[BRDFFIT_MAX_LOBE_PARAMS];
        tu_start_params((brdffit_model)m, p);
        brdffit_params pa = params_of((brdffit_model)m, 0, 0, p);
        memcpy(pa.d, d, sizeof d);
        double rgb[54];
        ck_assert_int_eq(brdffit_albedo_model((brdffit_model)m, &pa, 18, GRID, rgb, NULL), BRDFFIT_OK);
        for (int k = 0; k < 54; k++)
            ck_assert_msg(fabs(rgb[k] - d[k % 3]) < 1e-12, "%s theta_o %g: %g, d %g", mi->name,
                          GRID[k / 3], rgb[k], d[k % 3]);
    }
}
END_TEST

/* Blinn-Phong at the normal: delta = theta_i / 2, and with c = cos(theta_i / 2)
 * a = (n+2)/(2 pi) 2 pi int cos^n(ti/2) cos ti sin ti dti
 *   = 4 (n+2) [2 (1 - 2^-(n+4)/2) / (n+4) - (1 - 2^-(n+2)/2) / (n+2)]. */
START_TEST(blinn_phong_closed_form_at_normal)
{
    const double ns[] = { 0.1, 1, 10, 100, 1e4, 1e6 };
    for (size_t i = 0; i < sizeof ns / sizeof ns[0]; i++) {
        double n = ns[i];
        double want = 4 * (n + 2) *
                      (2 * (1 - pow(2, -(n + 4) / 2)) / (n + 4) - (1 - pow(2, -(n + 2) / 2)) / (n + 2));
        brdffit_params pa = params_of(BRDFFIT_BLINN_PHONG, 0, 1, &n);
        double got = albedo1(BRDFFIT_BLINN_PHONG, &pa, 0, 0);
        ck_assert_msg(fabs(got - want) < 1e-4 * fmax(1, want), "n %g: %.9g, closed form %.9g", n,
                      got, want);
    }
}
END_TEST

/* Lafortune's mirror lobe (Cxy = -Cz): (n+2)/(2 pi) (wi . r)^n about the
 * mirror direction r, whose cosine-weighted integral over the cap wi . r > 0
 * is exactly cos theta_o (the white-furnace limit: 1 at the normal).  The
 * horizon cuts the cap; for n >= 1e4 what it cuts is below e^-150 at
 * theta_o <= 80, so a = cos theta_o there; at the normal for every n. */
START_TEST(lafortune_mirror_white_furnace)
{
    const double ns[] = { 0.1, 1, 30, 1e4, 1e6 };
    for (size_t i = 0; i < sizeof ns / sizeof ns[0]; i++) {
        double p[3] = { -0.57735026918962576, 0.57735026918962576, ns[i] };
        brdffit_params pa = params_of(BRDFFIT_LAFORTUNE, 0, 1, p);
        double got = albedo1(BRDFFIT_LAFORTUNE, &pa, 0, 1);
        ck_assert_msg(fabs(got - 1) < 1e-4, "n %g at the normal: %.9g", ns[i], got);
        for (int k = 1; ns[i] >= 1e4 && k < 17; k++) {
            got = albedo1(BRDFFIT_LAFORTUNE, &pa, GRID[k], 1);
            double want = cos(GRID[k] * M_PI / 180);
            ck_assert_msg(fabs(got - want) < 1e-4, "n %g theta_o %g: %.9g, cos %.9g", ns[i],
                          GRID[k], got, want);
        }
    }
}
END_TEST

/* A glTF metal of base colour 1 (F = 1): single scattering loses energy, so
 * a <= 1 at every roughness, and a -> 1 as the roughness -> 0 (alpha = 1e-4
 * at roughness 0.01, alpha = 1e-6 at the floor). */
START_TEST(gltf_metal_white_furnace)
{
    const double r[] = { 0, 0.01, 0.1, 0.3, 0.6, 1 };
    for (size_t i = 0; i < sizeof r / sizeof r[0]; i++) {
        double p[4] = { 1, r[i], 1.5, 1 };
        brdffit_params pa = params_of(BRDFFIT_GLTF, 1, 1, p);
        double rgb[54];
        ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GLTF, &pa, 18, GRID, rgb, NULL), BRDFFIT_OK);
        for (int k = 0; k < 18; k++) {
            ck_assert_msg(rgb[3 * k] <= 1 + 1e-4, "roughness %g theta_o %g: %.9g > 1", r[i],
                          GRID[k], rgb[3 * k]);
            if (r[i] <= 0.01)
                ck_assert_msg(fabs(rgb[3 * k] - 1) < 1e-4, "roughness %g theta_o %g: %.9g", r[i],
                              GRID[k], rgb[3 * k]);
        }
    }
}
END_TEST

/* A glTF metal of base colour 1 at roughness 1: alpha = 1, D = 1/pi and
 * Vis = 1 / (2 (cos ti + cos to)), so a = int_0^1 mu / (mu + mo) dmu =
 * 1 - mo ln((1 + mo) / mo), mo = cos theta_o: a closed form at every theta_o. */
START_TEST(gltf_rough_metal_closed_form)
{
    double p[4] = { 1, 1, 1.5, 1 };
    brdffit_params pa = params_of(BRDFFIT_GLTF, 1, 1, p);
    double rgb[54];
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GLTF, &pa, 18, GRID, rgb, NULL), BRDFFIT_OK);
    for (int k = 0; k < 18; k++) {
        double mo = cos(GRID[k] * M_PI / 180), want = 1 - mo * log((1 + mo) / mo);
        ck_assert_msg(fabs(rgb[3 * k] - want) < 1e-4, "theta_o %g: %.9f, closed form %.9f",
                      GRID[k], rgb[3 * k], want);
    }
}
END_TEST

/* Ward-Duer at the normal: with t = tan^2 delta (delta = theta_i / 2 < pi/4),
 * a = (1 / alpha^2) int_0^1 e^(-t / alpha^2) / (1 + t)^2 dt, taken here by
 * composite Simpson's rule; it tends to 1 as alpha -> 0 (Ward-Duer's
 * normalisation). */
static double ward_duer_normal(double alpha)
{
    const int n = 400000;
    double c = 1 / (alpha * alpha), h = 1.0 / n, sum = 0;
    for (int i = 0; i <= n; i++) {
        double t = i * h, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        sum += w * exp(-c * t) / ((1 + t) * (1 + t));
    }
    return c * sum * h / 3;
}

START_TEST(ward_duer_one_dimensional_at_normal)
{
    const double alphas[] = { 0.01, 0.05, 0.2, 0.5, 1 };
    for (size_t i = 0; i < sizeof alphas / sizeof alphas[0]; i++) {
        brdffit_params pa = params_of(BRDFFIT_WARD_DUER, 0, 1, &alphas[i]);
        double got = albedo1(BRDFFIT_WARD_DUER, &pa, 0, 2), want = ward_duer_normal(alphas[i]);
        ck_assert_msg(fabs(got - want) < 1e-4, "alpha %g: %.9g, 1-D %.9g", alphas[i], got, want);
        ck_assert(got <= 1 + 1e-9);
    }
}
END_TEST

/* ---- brute force: the midpoint rule on a uniform grid in (cos theta_i, phi_i) */

#define BF_N 1000

/* The brute-force albedo at theta_o of a model (table NULL) or a table; masked
 * lookups count 0 per channel. */
static void brute_force(brdffit_model m, const brdffit_params *pa, const brdffit_table *table,
                        double theta_o, double out[3])
{
    size_t n = (size_t)BF_N * BF_N;
    double *wi = malloc(3 * n * sizeof *wi), *wo = malloc(3 * n * sizeof *wo);
    double *f = malloc(3 * n * sizeof *f);
    ck_assert(wi && wo && f);
    double t = theta_o * M_PI / 180;
    for (int a = 0; a < BF_N; a++)
        for (int b = 0; b < BF_N; b++) {
            size_t q = (size_t)a * BF_N + b;
            double mu = (a + 0.5) / BF_N, phi = 2 * M_PI * (b + 0.5) / BF_N, st = sqrt(1 - mu * mu);
            double v[3] = { st * cos(phi), st * sin(phi), mu }, o[3] = { sin(t), 0, cos(t) };
            memcpy(wi + 3 * q, v, sizeof v);
            memcpy(wo + 3 * q, o, sizeof o);
        }
    brdffit_error err;
    brdffit_status st = table ? brdffit_table_lookup_batch(table, n, wi, wo, BRDFFIT_SCALE_STANDARD,
                                                           BRDFFIT_INTERP_TRILINEAR, f, &err)
                              : brdffit_eval_batch(m, pa, n, wi, wo, f, &err);
    ck_assert_msg(st == BRDFFIT_OK, "%s", err.message);
    double acc[3] = { 0, 0, 0 };
    for (size_t q = 0; q < n; q++)
        for (int c = 0; c < 3; c++)
            acc[c] += fmax(f[3 * q + c], 0) * wi[3 * q + 2];
    for (int c = 0; c < 3; c++)
        out[c] = acc[c] * (2 * M_PI / ((double)BF_N * BF_N));
    free(wi);
    free(wo);
    free(f);
}

/* Parameters whose lobes the brute-force grid resolves. */
static const struct {
    brdffit_model model;
    double p[4];
} SAMPLED[] = {
    { BRDFFIT_WARD, { 0.3 } },
    { BRDFFIT_WARD_DUER, { 0.25 } },
    { BRDFFIT_BLINN_PHONG, { 20 } },
    { BRDFFIT_LAFORTUNE, { -0.6, 0.55, 15 } },
    { BRDFFIT_LAFORTUNE, { 0.5, 0.7, 8 } },
    { BRDFFIT_COOK_TORRANCE, { 0.3, 0.35 } },
    { BRDFFIT_ASHIKHMIN_SHIRLEY, { 0.4, 25 } },
    { BRDFFIT_HE, { 4, 0.4, 1.6 } },
    { BRDFFIT_GGX, { 0.5, 0.3 } },
    { BRDFFIT_GLTF, { 0.4, 0.6, 1.5, 1 } },
    { BRDFFIT_GLTF_EXT, { 0.2, 0.55, 2.5, 0.7 } },
};

START_TEST(models_against_brute_force)
{
    const double angles[3] = { 10, 45, 75 };
    int i = _i;
    brdffit_model m = SAMPLED[i].model;
    brdffit_params pa = params_of(m, 0.3, 0.8, SAMPLED[i].p);
    if (brdffit_model_get(m)->colour_form == BRDFFIT_COLOUR_GLTF) {
        pa.d[1] = 0.6;
        if (m == BRDFFIT_GLTF)
            pa.s[0] = pa.s[1] = pa.s[2] = 1;
    }
    ck_assert_int_eq(brdffit_params_check(m, &pa, NULL), BRDFFIT_OK);
    double got[9], bf[3];
    ck_assert_int_eq(brdffit_albedo_model(m, &pa, 3, angles, got, NULL), BRDFFIT_OK);
    for (int k = 0; k < 3; k++) {
        brute_force(m, &pa, NULL, angles[k], bf);
        for (int c = 0; c < 3; c++)
            ck_assert_msg(fabs(got[3 * k + c] - bf[c]) < 2e-4 * fmax(1, bf[c]),
                          "%s theta_o %g channel %d: %.7f, brute force %.7f",
                          brdffit_model_get(m)->name, angles[k], c, got[3 * k + c], bf[c]);
    }
}
END_TEST

/* A measured table's albedo against the brute-force sum of its lookups, and
 * the model's it was filled from (the table holds the model at the bins'
 * directions: the same to the interpolation's error). */
START_TEST(table_against_brute_force)
{
    brdffit_params pa = params_of(BRDFFIT_GGX, 0.2, 0.6, (double[]){ 0.8, 0.25 });
    pa.d[2] = 0.05;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_GGX, &pa, BRDFFIT_SCALE_STANDARD, NULL),
                     BRDFFIT_OK);
    const double angles[3] = { 0, 40, 70 };
    double got[9], masked[3], model[9], bf[3];
    ck_assert_int_eq(brdffit_albedo_table(t, BRDFFIT_SCALE_STANDARD, BRDFFIT_INTERP_TRILINEAR, 3,
                                          angles, got, masked, NULL),
                     BRDFFIT_OK);
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 3, angles, model, NULL), BRDFFIT_OK);
    for (int k = 0; k < 3; k++) {
        brute_force(BRDFFIT_GGX, NULL, t, angles[k], bf);
        ck_assert(masked[k] >= 0 && masked[k] < 0.01);
        for (int c = 0; c < 3; c++) {
            ck_assert_msg(fabs(got[3 * k + c] - bf[c]) < 2e-4 * fmax(1, bf[c]),
                          "theta_o %g channel %d: %.7f, brute force %.7f", angles[k], c,
                          got[3 * k + c], bf[c]);
            ck_assert_msg(fabs(got[3 * k + c] - model[3 * k + c]) < 0.02,
                          "theta_o %g channel %d: table %.5f, model %.5f", angles[k], c,
                          got[3 * k + c], model[3 * k + c]);
        }
    }
    brdffit_table_free(t);
}
END_TEST

/* A Lambertian table gives d; masking every bin of a theta_d band in one
 * channel lowers that channel only, and says how much of the hemisphere met it. */
START_TEST(table_lambertian_and_masked)
{
    const double d[3] = { 0.7, 0.4, 0.1 };
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    double f[3], *v = brdffit_table_values(t);
    brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL);
    for (int c = 0; c < 3; c++)
        for (size_t b = 0; b < BRDFFIT_MERL_BINS; b++)
            v[c * (size_t)BRDFFIT_MERL_BINS + b] = d[c] / M_PI / f[c];
    double rgb[54], masked[18];
    ck_assert_int_eq(brdffit_albedo_table(t, BRDFFIT_SCALE_STANDARD, BRDFFIT_INTERP_TRILINEAR, 18,
                                          GRID, rgb, masked, NULL),
                     BRDFFIT_OK);
    for (int k = 0; k < 54; k++)
        ck_assert_msg(fabs(rgb[k] - d[k % 3]) < 1e-6, "theta_o %g: %.9f", GRID[k / 3], rgb[k]);
    for (int k = 0; k < 18; k++)
        ck_assert(masked[k] == 0);
    for (int i = 0; i < 90; i++)
        for (int j = 30; j < 40; j++)
            for (int k = 0; k < 180; k++)
                v[brdffit_bin_index(i, j, k)] = -1; /* red, theta_d bins 30..39 */
    ck_assert_int_eq(brdffit_albedo_table(t, BRDFFIT_SCALE_STANDARD, BRDFFIT_INTERP_TRILINEAR, 18,
                                          GRID, rgb, masked, NULL),
                     BRDFFIT_OK);
    ck_assert(masked[0] > 0.01 && masked[0] < 0.99);
    ck_assert(rgb[0] < d[0] * (1 - masked[0]) + 1e-6 && rgb[0] > d[0] * (1 - masked[0]) - 0.05);
    ck_assert(fabs(rgb[1] - d[1]) < 1e-6 && fabs(rgb[2] - d[2]) < 1e-6);
    brdffit_table_free(t);
}
END_TEST

/* Every model at every corner of its bounds (d, s 0 and 1) gives finite values. */
START_TEST(finite_at_bounds)
{
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        for (int corner = 0; corner < (1 << mi->nparams); corner++) {
            double p[4];
            for (int k = 0; k < mi->nparams; k++)
                p[k] = (corner >> k) & 1 ? mi->params[k].upper : mi->params[k].lower;
            brdffit_params pa = params_of((brdffit_model)m, 1, 1, p);
            if (brdffit_params_check((brdffit_model)m, &pa, NULL) != BRDFFIT_OK)
                continue; /* Lafortune's (0, 0) has no direction */
            double rgb[54];
            brdffit_error err;
            ck_assert_msg(brdffit_albedo_model((brdffit_model)m, &pa, 18, GRID, rgb, &err) == BRDFFIT_OK,
                          "%s corner %d: %s", mi->name, corner, err.message);
            for (int k = 0; k < 54; k++)
                ck_assert_msg(isfinite(rgb[k]) && rgb[k] >= 0, "%s corner %d theta_o %g: %g",
                              mi->name, corner, GRID[k / 3], rgb[k]);
        }
    }
}
END_TEST

START_TEST(refuses_bad_input)
{
    brdffit_params pa = params_of(BRDFFIT_GGX, 0.1, 0.1, (double[]){ 0.5, 0.2 });
    double rgb[6], th[2] = { 0, 45 }, bad[3] = { 90, -1, NAN };
    brdffit_error err;
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, NULL, 2, th, rgb, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_albedo_model((brdffit_model)99, &pa, 2, th, rgb, &err),
                     BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 2, NULL, rgb, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 2, th, NULL, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    for (int i = 0; i < 3; i++) {
        ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 1, &bad[i], rgb, &err),
                         BRDFFIT_E_INVALID_ARGUMENT);
        ck_assert_ptr_nonnull(strstr(err.message, "theta_o_deg[0]"));
    }
    pa.p[1] = 2;
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 2, th, rgb, &err), BRDFFIT_E_PARAM_RANGE);
    pa.p[1] = 0.2;
    pa.s[0] = 1e308;
    pa.d[0] = 1.7e308;
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 2, th, rgb, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_int_eq(brdffit_albedo_model(BRDFFIT_GGX, &pa, 0, NULL, NULL, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_albedo_table(NULL, BRDFFIT_SCALE_STANDARD, BRDFFIT_INTERP_TRILINEAR,
                                          2, th, rgb, NULL, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_albedo_table(t, (brdffit_scale)7, BRDFFIT_INTERP_TRILINEAR, 2, th,
                                          rgb, NULL, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_albedo_table(t, BRDFFIT_SCALE_STANDARD, BRDFFIT_INTERP_TRILINEAR, 1,
                                          &bad[0], rgb, NULL, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_table_free(t);
}
END_TEST


/* ---- the program: the fit records' energy fields, the report's section */

static double max_of(const double a[FR_ALBEDO_N][3], double *where)
{
    double best = -1;
    for (int k = 0; k < FR_ALBEDO_N; k++)
        for (int c = 0; c < 3; c++)
            if (a[k][c] > best) {
                best = a[k][c];
                *where = 5.0 * k;
            }
    return best;
}

/* `fit --json` records carry the model's albedo (as the library gives it at
 * the record's parameters), its maximum and where, the table's albedo and the
 * departure as docs/fit-record.md defines it. */
START_TEST(records_carry_albedo)
{
    char args[2048];
    snprintf(args, sizeof args, "fit '%s' --model blinn-phong,ward-duer --starts 1 --json",
             tu_table_fixture());
    tu_run_out r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 0, args);
    static fit_record rec;
    int n = 0;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_read(tu_table_fixture(), &t, NULL), BRDFFIT_OK);
    double measured[54];
    ck_assert_int_eq(brdffit_albedo_table(t, BRDFFIT_SCALE_STANDARD, BRDFFIT_INTERP_TRILINEAR, 18,
                                          GRID, measured, NULL, NULL),
                     BRDFFIT_OK);
    brdffit_table_free(t);
    for (char *save = NULL, *line = strtok_r(r.out, "\n", &save); line;
         line = strtok_r(NULL, "\n", &save), n++) {
        ck_assert_msg(strstr(line, "\"albedo\":[") && strstr(line, "\"albedo_max_theta_o\":"),
                      "%s", line);
        ck_assert_int_eq(fr_read_json(line, &rec, FR_NEED_FIT), 0);
        ck_assert(rec.has_albedo && rec.has_albedo_measured);
        brdffit_model m;
        ck_assert_int_eq(brdffit_model_from_name(rec.model, &m, NULL), BRDFFIT_OK);
        double a[54], where = -1;
        ck_assert_int_eq(brdffit_albedo_model(m, &rec.params, 18, GRID, a, NULL), BRDFFIT_OK);
        for (int k = 0; k < 54; k++) {
            ck_assert(fabs(rec.albedo[k / 3][k % 3] - a[k]) <= 1e-5 * a[k] + 1e-12);
            ck_assert(fabs(rec.albedo_measured[k / 3][k % 3] - measured[k]) <= 1e-5 * measured[k] + 1e-12);
        }
        ck_assert(fabs(rec.albedo_max - max_of(rec.albedo, &where)) < 1e-12);
        ck_assert(rec.albedo_max_theta_o == where);
        double worst = -1, at = -1;
        for (int k = 0; k < 17; k++) { /* theta_o <= the cutoff, 80 */
            double ym = 0.2126 * a[3 * k] + 0.7152 * a[3 * k + 1] + 0.0722 * a[3 * k + 2];
            double yt = 0.2126 * measured[3 * k] + 0.7152 * measured[3 * k + 1] +
                        0.0722 * measured[3 * k + 2];
            double d = fabs(ym - yt) / fmax(yt, 0.01);
            if (d > worst) {
                worst = d;
                at = 5.0 * k;
            }
        }
        ck_assert_msg(fabs(rec.albedo_departure - worst) < 1e-4, "%s: %g, here %g", rec.model,
                      rec.albedo_departure, worst);
        ck_assert(rec.albedo_departure_theta_o == at);
        ck_assert(rec.seconds_albedo >= 0 && rec.seconds_albedo < 1);
        /* the table is a Ward-Duer lobe: its own model's fit stays close */
        if (m == BRDFFIT_WARD_DUER)
            ck_assert_msg(!fr_albedo_departs(&rec), "departure %g", rec.albedo_departure);
    }
    ck_assert_int_eq(n, 2);
    tu_run_free(&r);
}
END_TEST

static void curve_fill(double a[FR_ALBEDO_N][3], double v)
{
    for (int k = 0; k < FR_ALBEDO_N; k++)
        a[k][0] = a[k][1] = a[k][2] = v;
}

/* The flags: a fit above 1 exceeds, one 20% off the table departs, one 5%
 * off neither; each has its plot; a record that failed has none. */
START_TEST(energy_section_flags)
{
    static fit_record rec[4];
    const char *names[4] = { "ward", "ggx", "blinn-phong", "he" };
    const double model_value[3] = { 0.5, 0.36, 0.315 };
    for (int i = 0; i < 4; i++) {
        fr_init(&rec[i], FR_FIT);
        snprintf(rec[i].model, sizeof rec[i].model, "%s", names[i]);
        rec[i].settings.cutoff_deg = 80;
        rec[i].has_params = i < 3;
        rec[i].status = i < 3 ? BRDFFIT_OK : BRDFFIT_E_FIT_FAILED;
        if (i == 3)
            continue;
        rec[i].has_albedo = rec[i].has_albedo_measured = 1;
        curve_fill(rec[i].albedo, model_value[i]);
        curve_fill(rec[i].albedo_measured, 0.3);
        rec[i].albedo_max = model_value[i];
        rec[i].albedo_max_theta_o = 0;
        rec[i].albedo_departure = (model_value[i] - 0.3) / 0.3;
        rec[i].albedo_departure_theta_o = 0;
    }
    rec[0].albedo[17][0] = 1.2; /* red above 1 at 85 deg */
    rec[0].albedo_max = 1.2;
    rec[0].albedo_max_theta_o = 85;
    ck_assert(fr_albedo_exceeds(&rec[0]) && !fr_albedo_exceeds(&rec[1]));
    ck_assert(fr_albedo_departs(&rec[1]) && !fr_albedo_departs(&rec[2]));
    rp_report rep;
    bj_settings set;
    memset(&set, 0, sizeof set);
    const brdffit_model models[4] = { BRDFFIT_WARD, BRDFFIT_GGX, BRDFFIT_BLINN_PHONG, BRDFFIT_HE };
    ck_assert_int_eq(rp_init(&rep, models, 4, &set), 0);
    rp_material m;
    memset(&m, 0, sizeof m);
    for (int i = 0; i < 4; i++)
        m.fit[i] = &rec[i];
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    ck_assert_ptr_nonnull(f);
    xml_writer w;
    xml_init(&w, f, XML_MODE_HTML);
    xml_open(&w, "body");
    rp_energy_section(&w, &rep, &m);
    xml_close(&w);
    ck_assert_int_eq(xml_finish(&w), 0);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_msg(strstr(text, "Energy: directional albedo"), "%.300s", text);
    int svgs = 0;
    for (const char *p = text; (p = strstr(p, "<svg")); p++)
        svgs++;
    ck_assert_int_eq(svgs, 3);
    static const char *const captions[3] = {
        "max 1.200 at 85 deg; departs 66.7% at 0 deg \xe2\x9a\xa0 exceeds 1 \xe2\x9a\xa0 departs &gt; 10%</figcaption>",
        "max 0.360 at 0 deg; departs 20.0% at 0 deg \xe2\x9a\xa0 departs &gt; 10%</figcaption>",
        "max 0.315 at 0 deg; departs 5.0% at 0 deg</figcaption>",
    };
    for (int i = 0; i < 3; i++)
        ck_assert_msg(strstr(text, captions[i]), "no caption %s", captions[i]);
    free(text);
    rp_free(&rep);
}
END_TEST

/* A record's albedo is judged as the program writes it. */
START_TEST(record_check_judges_albedo)
{
    static fit_record r;
    char line[] = "{\"kind\":\"fit\",\"material\":\"m\",\"model\":\"ward\",\"status_code\":0,"
                  "\"albedo\":[1,2,3]}";
    ck_assert_int_eq(fr_read_json(line, &r, FR_NEED_FIT), -1); /* 3 numbers, not 54 */
    fr_init(&r, FR_FIT);
    snprintf(r.material, sizeof r.material, "m");
    snprintf(r.id.path, sizeof r.id.path, "/data/m.binary");
    r.id.size = 34992012;
    snprintf(r.id.hash, sizeof r.id.hash, "0123456789abcdef");
    snprintf(r.settings.version, sizeof r.settings.version, "%s", brdffit_version());
    snprintf(r.settings.scale, sizeof r.settings.scale, "standard");
    r.settings.cutoff_deg = 80;
    snprintf(r.model, sizeof r.model, "ward");
    r.status = BRDFFIT_E_FIT_FAILED;
    snprintf(r.message, sizeof r.message, "failed");
    char why[256];
    ck_assert_ptr_null(fr_check(&r, why, sizeof why));
    r.has_albedo = 1; /* a failed fit with an albedo */
    const char *bad = fr_check(&r, why, sizeof why);
    ck_assert_msg(bad && strstr(bad, "albedo"), "%s", bad ? bad : "(accepted)");
}
END_TEST

Suite *albedo_suite(void)
{
    Suite *s = suite_create("albedo");
    TCase *tc = tcase_create("albedo");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, lambertian_gives_d);
    tcase_add_test(tc, blinn_phong_closed_form_at_normal);
    tcase_add_test(tc, lafortune_mirror_white_furnace);
    tcase_add_test(tc, gltf_metal_white_furnace);
    tcase_add_test(tc, gltf_rough_metal_closed_form);
    tcase_add_test(tc, ward_duer_one_dimensional_at_normal);
    tcase_add_loop_test(tc, models_against_brute_force, 0,
                        (int)(sizeof SAMPLED / sizeof SAMPLED[0]));
    tcase_add_test(tc, table_against_brute_force);
    tcase_add_test(tc, table_lambertian_and_masked);
    tcase_add_test(tc, finite_at_bounds);
    tcase_add_test(tc, refuses_bad_input);
    suite_add_tcase(s, tc);
    TCase *tp = tcase_create("program");
    tcase_set_timeout(tp, 300);
    tcase_add_unchecked_fixture(tp, tu_table_fixture_make, tu_table_fixture_remove);
    tcase_add_test(tp, records_carry_albedo);
    tcase_add_test(tp, energy_section_flags);
    tcase_add_test(tp, record_check_judges_albedo);
    suite_add_tcase(s, tp);
    return s;
}
