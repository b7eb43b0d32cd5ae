/* SPDX-License-Identifier: MIT */
/* test_models.c -- the six closed-form lobes: reference values, reciprocity,
 * finiteness at the edges of the hemisphere and of the parameter ranges. */
#define _DEFAULT_SOURCE
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const brdffit_model closed_form[] = {
    BRDFFIT_WARD, BRDFFIT_WARD_DUER, BRDFFIT_BLINN_PHONG,
    BRDFFIT_LAFORTUNE, BRDFFIT_COOK_TORRANCE, BRDFFIT_ASHIKHMIN_SHIRLEY,
};
#define NCLOSED (int)(sizeof closed_form / sizeof closed_form[0])

START_TEST(reference_values)
{
    char path[1024], line[4096];
    FILE *f = fopen(tu_shared("data/model-reference.tsv", path, sizeof path), "r");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    char *fl[32];
    int rows = 0, header = 0;
    double worst = 0;
    while (tu_tsv_next(f, line, sizeof line, fl, 32) > 0) {
        if (!header) { /* the column header line */
            ck_assert_str_eq(fl[0], "model");
            header = 1;
            continue;
        }
        brdffit_model m;
        ck_assert_int_eq(brdffit_model_from_name(fl[0], &m), BRDFFIT_OK);
        brdffit_params p;
        tu_params_from_row(fl, &p);
        double wi[3], wo[3], rgb[3];
        for (int k = 0; k < 3; k++) {
            wi[k] = atof(fl[11 + k]);
            wo[k] = atof(fl[14 + k]);
        }
        ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, rgb), BRDFFIT_OK);
        /* 1e-12, except that x^n turns one rounding step of x (which the
         * reference and we may round differently) into n * 2.2e-16: for the
         * chrome Lafortune row at the mirror direction (n = 6630) that is
         * 1.5e-12.  So the bound is max(1e-12, 2 n eps) for exponent lobes. */
        double n_exp = m == BRDFFIT_BLINN_PHONG ? p.p[0]
                     : m == BRDFFIT_LAFORTUNE ? p.p[2]
                     : m == BRDFFIT_ASHIKHMIN_SHIRLEY ? p.p[1] : 0.0;
        double tol = fmax(1e-12, 2.0 * n_exp * 2.220446049250313e-16);
        for (int c = 0; c < 3; c++) {
            double ref = atof(fl[17 + c]), rd = tu_reldiff(rgb[c], ref);
            if (rd > worst)
                worst = rd;
            ck_assert_msg(rd <= tol, "%s %s row %d channel %d: %.17g vs reference %.17g (rel %g)",
                          fl[0], fl[1], rows, c, rgb[c], ref, rd);
        }
        rows++;
    }
    fclose(f);
    ck_assert_int_eq(rows, 384);
}
END_TEST

static void published(brdffit_model m, brdffit_params *p)
{
    /* alum-bronze rows of ngan2005-fits.tsv */
    static const double tab[6][9] = {
        { 0.0851, 0.0586, 0.0294, 0.0484, 0.0274, 0.0135, 0.0357, 0, 0 },
        { 0.0856, 0.0585, 0.0291, 0.032, 0.0189, 0.00986, 0.0374, 0, 0 },
        { 0.0864, 0.0597, 0.0302, 0.015, 0.00818, 0.00381, 1290.0, 0, 0 },
        { 0.0923, 0.0625, 0.0311, 0.322, 0.193, 0.105, -0.579, 0.574, 630.0 },
        { 0.0886, 0.0602, 0.0299, 0.118, 0.0698, 0.0371, 0.203, 0.0367, 0 },
        { 0.0877, 0.0598, 0.0297, 0.108, 0.0637, 0.0337, 0.249, 1350.0, 0 },
    };
    memset(p, 0, sizeof *p);
    for (int c = 0; c < 3; c++) {
        p->d[c] = tab[m][c];
        p->s[c] = tab[m][3 + c];
    }
    for (int k = 0; k < 3; k++)
        p->p[k] = tab[m][6 + k];
}

START_TEST(reciprocity)
{
    unsigned st = 12345u + (unsigned)_i;
    brdffit_model m = closed_form[_i];
    brdffit_params p;
    published(m, &p);
    for (int t = 0; t < 20000; t++) {
        double wi[3], wo[3], a[3], b[3];
        tu_rand_dir(&st, 1e-3, wi);
        tu_rand_dir(&st, 1e-3, wo);
        ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, a), BRDFFIT_OK);
        ck_assert_int_eq(brdffit_eval(m, &p, wo, wi, b), BRDFFIT_OK);
        for (int c = 0; c < 3; c++)
            ck_assert_msg(tu_reldiff(a[c], b[c]) <= 1e-12, "model %d: f(wi,wo)=%.17g f(wo,wi)=%.17g",
                          (int)m, a[c], b[c]);
    }
}
END_TEST

/* Finite, non-negative values for every lobe at the corners of the parameter
 * box and the awkward directions: wi = wo, normal incidence, grazing 89.9 deg. */
START_TEST(finite_everywhere)
{
    brdffit_model m = closed_form[_i];
    const brdffit_model_info *mi = brdffit_model_get(m);
    ck_assert_ptr_nonnull(mi);
    double dirs[][2] = { { 0, 0 }, { 1e-9, 0 }, { 30, 0 }, { 30, 180 }, { 60, 90 }, { 80, 45 },
                         { 89.9, 0 }, { 89.9, 180 }, { 89.9, 90 }, { 89.999, 10 }, { 45, 270 } };
    int nd = (int)(sizeof dirs / sizeof dirs[0]);
    int corners = 1 << mi->nparams;
    unsigned st = 99;
    for (int cnr = 0; cnr < corners * 3; cnr++) {
        brdffit_params p;
        memset(&p, 0, sizeof p);
        for (int c = 0; c < 3; c++) {
            p.d[c] = 0.5;
            p.s[c] = 1.0;
        }
        for (int k = 0; k < mi->nparams; k++) {
            int bit = (cnr % corners) >> k & 1;
            /* corners, then points just inside them, then random interior points */
            double lo = mi->lower[k], hi = mi->upper[k];
            p.p[k] = cnr < corners ? (bit ? hi : lo)
                   : cnr < 2 * corners ? (bit ? hi - 1e-9 * (hi - lo) : lo + 1e-9 * (hi - lo))
                                       : lo + (hi - lo) * tu_urand(&st);
        }
        if (m == BRDFFIT_LAFORTUNE && p.p[0] == 0 && p.p[1] == 0)
            p.p[1] = 1;
        for (int a = 0; a < nd; a++)
            for (int b = 0; b < nd; b++) {
                double wi[3], wo[3], rgb[3];
                tu_dir_at(dirs[a][0], dirs[a][1], wi);
                tu_dir_at(dirs[b][0], dirs[b][1], wo);
                ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, rgb), BRDFFIT_OK);
                for (int c = 0; c < 3; c++)
                    ck_assert_msg(isfinite(rgb[c]) && rgb[c] >= 0,
                                  "%s p=(%g,%g,%g) wi=(%g deg,%g) wo=(%g deg,%g): f=%g", mi->name,
                                  p.p[0], p.p[1], p.p[2], dirs[a][0], dirs[a][1], dirs[b][0],
                                  dirs[b][1], rgb[c]);
            }
    }
}
END_TEST

START_TEST(exponent_million)
{
    /* n = 1e6: the peak is finite and huge, off-peak values underflow to 0 cleanly */
    brdffit_params p;
    memset(&p, 0, sizeof p);
    p.s[0] = p.s[1] = p.s[2] = 1;
    double wi[3], wo[3], rgb[3];
    tu_dir_at(30, 0, wi);
    tu_dir_at(30, 180, wo);
    brdffit_model ms[] = { BRDFFIT_BLINN_PHONG, BRDFFIT_LAFORTUNE, BRDFFIT_ASHIKHMIN_SHIRLEY };
    for (int i = 0; i < 3; i++) {
        p.p[0] = ms[i] == BRDFFIT_LAFORTUNE ? -1.0 : (ms[i] == BRDFFIT_ASHIKHMIN_SHIRLEY ? 0.5 : 1e6);
        p.p[1] = ms[i] == BRDFFIT_LAFORTUNE ? 1.0 : 1e6;
        p.p[2] = 1e6;
        ck_assert_int_eq(brdffit_eval(ms[i], &p, wi, wo, rgb), BRDFFIT_OK);
        ck_assert_msg(isfinite(rgb[0]) && rgb[0] > 1e4, "peak of model %d at n=1e6: %g", (int)ms[i], rgb[0]);
        double off[3];
        tu_dir_at(40, 180, off); /* half-vector 5 deg off the peak */
        ck_assert_int_eq(brdffit_eval(ms[i], &p, wi, off, rgb), BRDFFIT_OK);
        ck_assert_msg(isfinite(rgb[0]) && rgb[0] >= 0 && rgb[0] < 1e-100, "off-peak %g", rgb[0]);
    }
    /* Lafortune with large C: normalisation before the power, no underflow to 0 */
    p.p[0] = -50, p.p[1] = 50, p.p[2] = 5000;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_LAFORTUNE, &p, wi, wo, rgb), BRDFFIT_OK);
    ck_assert_msg(rgb[0] > 1.0, "Lafortune peak with |C| = 50, n = 5000: %g", rgb[0]);
}
END_TEST

START_TEST(bad_parameters)
{
    brdffit_params p;
    published(BRDFFIT_WARD, &p);
    double wi[3] = { 0, 0, 1 }, wo[3] = { 0.5, 0, 0.8 }, rgb[3] = { 7, 7, 7 };
    brdffit_error err;
    p.p[0] = NAN;
    ck_assert_int_eq(brdffit_params_check(BRDFFIT_WARD, &p, &err), BRDFFIT_E_PARAM_RANGE);
    ck_assert_ptr_nonnull(strstr(err.message, "alpha"));
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb), BRDFFIT_E_PARAM_RANGE);
    p.p[0] = 0.0; /* alpha = 0 is no Ward lobe */
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb), BRDFFIT_E_PARAM_RANGE);
    p.p[0] = 0.1;
    p.d[1] = -0.1;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb), BRDFFIT_E_PARAM_RANGE);
    p.d[1] = INFINITY;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb), BRDFFIT_E_PARAM_RANGE);
    p.d[1] = 0.1;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_MODEL_COUNT, &p, wi, wo, rgb), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, NULL, wi, wo, rgb), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, NULL, wo, rgb), BRDFFIT_E_INVALID_ARGUMENT);
    double zero[3] = { 0, 0, 0 }, nan3[3] = { NAN, 0, 1 };
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, zero, wo, rgb), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, nan3, wo, rgb), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0);
    /* Lafortune with both C zero is no lobe */
    published(BRDFFIT_LAFORTUNE, &p);
    p.p[0] = p.p[1] = 0;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_LAFORTUNE, &p, wi, wo, rgb), BRDFFIT_E_PARAM_RANGE);
}
END_TEST

START_TEST(below_horizon_and_batch)
{
    brdffit_params p;
    published(BRDFFIT_COOK_TORRANCE, &p);
    double wi[6] = { 0, 0, 1, 0.3, 0.1, -0.5 }, wo[6] = { 0.6, 0, 0.8, 0, 0, 2 }, rgb[6];
    ck_assert_int_eq(brdffit_eval_batch(BRDFFIT_COOK_TORRANCE, &p, 2, wi, wo, rgb), BRDFFIT_OK);
    ck_assert(rgb[3] == 0 && rgb[4] == 0 && rgb[5] == 0);
    double one[3];
    ck_assert_int_eq(brdffit_eval(BRDFFIT_COOK_TORRANCE, &p, wi, wo, one), BRDFFIT_OK);
    for (int c = 0; c < 3; c++)
        ck_assert(one[c] == rgb[c] && one[c] > 0);
    /* unnormalised input directions give the same value */
    double wi2[3] = { 0, 0, 7 }, wo2[3] = { 3, 0, 4 };
    ck_assert_int_eq(brdffit_eval(BRDFFIT_COOK_TORRANCE, &p, wi2, wo2, one), BRDFFIT_OK);
    for (int c = 0; c < 3; c++)
        ck_assert(tu_reldiff(one[c], rgb[c]) < 1e-14);
}
END_TEST

START_TEST(model_table)
{
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        ck_assert_ptr_nonnull(mi);
        ck_assert_int_eq(mi->id, m);
        brdffit_model back;
        ck_assert_int_eq(brdffit_model_from_name(mi->name, &back), BRDFFIT_OK);
        ck_assert_int_eq(back, m);
        ck_assert(mi->nparams >= 1 && mi->nparams <= 3);
        for (int k = 0; k < mi->nparams; k++) {
            ck_assert_ptr_nonnull(mi->param_names[k]);
            ck_assert(mi->lower[k] < mi->upper[k]);
            ck_assert(mi->start[k] >= mi->lower[k] && mi->start[k] <= mi->upper[k]);
        }
    }
    brdffit_model m;
    ck_assert_int_eq(brdffit_model_from_name("cook_torrance", &m), BRDFFIT_OK);
    ck_assert_int_eq(m, BRDFFIT_COOK_TORRANCE);
    ck_assert_int_eq(brdffit_model_from_name("phong", &m), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_model_from_name("ward-duerX", &m), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_ptr_null(brdffit_model_get(BRDFFIT_MODEL_COUNT));
    for (int s = 0; s < BRDFFIT_STATUS_COUNT; s++)
        ck_assert(strlen(brdffit_strerror((brdffit_status)s)) > 0);
    ck_assert_str_eq(brdffit_strerror((brdffit_status)999), "unknown status");
}
END_TEST

Suite *models_suite(void)
{
    Suite *s = suite_create("models");
    TCase *tr = tcase_create("reference");
    tcase_set_timeout(tr, 60);
    tcase_set_tags(tr, TU_NEEDS_SHARED);
    tcase_add_test(tr, reference_values);
    suite_add_tcase(s, tr);
    TCase *tc = tcase_create("closed-form");
    tcase_set_timeout(tc, 60);
    tcase_add_loop_test(tc, reciprocity, 0, NCLOSED);
    tcase_add_loop_test(tc, finite_everywhere, 0, NCLOSED);
    tcase_add_test(tc, exponent_million);
    tcase_add_test(tc, bad_parameters);
    tcase_add_test(tc, below_horizon_and_batch);
    tcase_add_test(tc, model_table);
    suite_add_tcase(s, tc);
    return s;
}
