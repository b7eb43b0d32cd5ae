/* SPDX-License-Identifier: MIT */
/* test_models.c -- the closed-form lobes (every model of the registry whose
 * lobe is the same for the three channels; He has its own suite): reference
 * values, reciprocity, finiteness at the edges of the hemisphere and of the
 * parameter ranges; the kernel's exp that the power lobes (and He's series)
 * take; the registry itself and the ABI values it pins. */
#define _DEFAULT_SOURCE
#include "testutil.h"
#include "registry.h"
#include "bf_lobe_pass.h"

#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


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
        ck_assert_int_eq(brdffit_model_from_name(fl[0], &m, NULL), BRDFFIT_OK);
        brdffit_params p;
        tu_params_from_row(fl, &p);
        double wi[3], wo[3], rgb[3];
        for (int k = 0; k < 3; k++) {
            wi[k] = atof(fl[11 + k]);
            wo[k] = atof(fl[14 + k]);
        }
        ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
        /* 1e-12, except that x^n turns one rounding step of x (which the
         * reference and we may round differently) into n * 2.2e-16: for the
         * chrome Lafortune row at the mirror direction (n = 6630) that is
         * 1.5e-12.  So the bound is max(1e-12, 2 n eps), n the largest lobe
         * parameter above 1 (the exponent of an exponent lobe). */
        double n_exp = 0.0;
        for (int k = 0; k < brdffit_model_get(m)->nparams; k++)
            n_exp = fmax(n_exp, p.p[k] > 1 ? p.p[k] : 0.0);
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

/* The closed-form models of the registry, in id order: those with a lobe
 * (lobes = 1: the form d/pi + s K, bf_model_has_lobe) or all (the glTF
 * models too). */
static int closed_form_of(brdffit_model *out, int lobes)
{
    int n = 0;
    for (int m = 0; m < brdffit_model_count(); m++)
        if (!brdffit_model_get((brdffit_model)m)->chromatic &&
            (!lobes || bf_model_has_lobe((brdffit_model)m)))
            out[n++] = (brdffit_model)m;
    return n;
}

static int closed_form(brdffit_model *out)
{
    return closed_form_of(out, 0);
}

static brdffit_model closed_form_model(int i)
{
    brdffit_model ms[BRDFFIT_MODEL_COUNT];
    ck_assert_int_lt(i, closed_form(ms));
    return ms[i];
}

static brdffit_model closed_lobe_model(int i)
{
    brdffit_model ms[BRDFFIT_MODEL_COUNT];
    ck_assert_int_lt(i, closed_form_of(ms, 1));
    return ms[i];
}

/* Parameters of a model: its alum-bronze row of ngan2005-fits.tsv when
 * ../shared has it, else (a model the paper did not fit, or no ../shared)
 * the registry's start values with alum-bronze-like d and s. */
static void published(brdffit_model m, brdffit_params *p)
{
    if (tu_published("alum-bronze", m, p))
        return;
    static const brdffit_params ds = { { 0.0851, 0.0586, 0.0294 }, { 0.0484, 0.0274, 0.0135 },
                                       { 0 }, { 0 } };
    *p = ds;
    tu_start_params(m, p->p);
    if (brdffit_model_get(m)->colour_form != BRDFFIT_COLOUR_DS) { /* a bronze-like metal */
        for (int c = 0; c < 3; c++) {
            p->d[c] = 10 * ds.d[c];
            p->s[c] = 1.0;
        }
        p->p[0] = 0.7;
    }
}

START_TEST(reciprocity)
{
    unsigned st = 12345u + (unsigned)_i;
    brdffit_model m = closed_form_model(_i);
    brdffit_params p;
    published(m, &p);
    /* a model the registry calls not reciprocal (OpenPBR's albedo scaling at
     * the view direction) is not: some pair differs by more than 1e-3 */
    const int nonrec = bf_model_def_get(m)->nonreciprocal;
    double most = 0.0;
    for (int t = 0; t < 20000; t++) {
        double wi[3], wo[3], a[3], b[3];
        tu_rand_dir(&st, 1e-3, wi);
        tu_rand_dir(&st, 1e-3, wo);
        ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, a, NULL), BRDFFIT_OK);
        ck_assert_int_eq(brdffit_eval(m, &p, wo, wi, b, NULL), BRDFFIT_OK);
        for (int c = 0; c < 3; c++) {
            most = fmax(most, tu_reldiff(a[c], b[c]));
            ck_assert_msg(nonrec || tu_reldiff(a[c], b[c]) <= 1e-12,
                          "model %d: f(wi,wo)=%.17g f(wo,wi)=%.17g", (int)m, a[c], b[c]);
        }
    }
    if (nonrec)
        ck_assert_msg(most > 1e-3, "model %d: reciprocal to %g", (int)m, most);
}
END_TEST

/* A unit direction whose cosine is z (its azimuth phi deg): grazing closer
 * than degrees can say. */
static void dir_z(double z, double phi, double w[3])
{
    const double s = sqrt(1.0 - z * z), a = phi * M_PI / 180.0;
    w[0] = s * cos(a);
    w[1] = s * sin(a);
    w[2] = z;
}

/* finite_everywhere's directions: (theta deg, phi deg) at 0 .. FE_ND - 1,
 * then the cosines fe_zs at the azimuths fe_phis (FE_NZ of them). */
static const double fe_dirs[][2] = { { 0, 0 },     { 1e-9, 0 },  { 30, 0 },      { 30, 180 },
                                     { 60, 90 },   { 80, 45 },   { 89.9, 0 },    { 89.9, 180 },
                                     { 89.9, 90 }, { 89.999, 10 }, { 45, 270 } };
static const double fe_zs[] = { 1e-12, 1e-100, 1e-300, 4.9e-324 }, fe_phis[] = { 0, 90, 180, 217 };
enum {
    FE_ND = (int)(sizeof fe_dirs / sizeof fe_dirs[0]),
    FE_NPHI = (int)(sizeof fe_phis / sizeof fe_phis[0]),
    FE_NZ = (int)(sizeof fe_zs / sizeof fe_zs[0]) * FE_NPHI
};

static void fe_dir(int k, double w[3])
{
    if (k < FE_ND)
        tu_dir_at(fe_dirs[k][0], fe_dirs[k][1], w);
    else
        dir_z(fe_zs[(k - FE_ND) / FE_NPHI], fe_phis[(k - FE_ND) % FE_NPHI], w);
}

/* Finite, non-negative values for every lobe at the corners of the parameter
 * box and the awkward directions: wi = wo, normal incidence, grazing 89.9 deg,
 * and cosines of 1e-12 down to the smallest double (back-scatter among
 * them: bf_geom_derive's BF_COS_FLOOR). */
START_TEST(finite_everywhere)
{
    brdffit_model m = closed_form_model(_i);
    const brdffit_model_info *mi = brdffit_model_get(m);
    ck_assert_ptr_nonnull(mi);
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
            double lo = mi->params[k].lower, hi = mi->params[k].upper;
            p.p[k] = cnr < corners ? (bit ? hi : lo)
                   : cnr < 2 * corners ? (bit ? hi - 1e-9 * (hi - lo) : lo + 1e-9 * (hi - lo))
                                       : lo + (hi - lo) * tu_urand(&st);
        }
        for (int k = 0; k + 1 < mi->nparams; k++) /* a direction pair needs a direction */
            if (mi->params[k].map == BRDFFIT_MAP_DIRECTION && p.p[k] == 0 && p.p[k + 1] == 0)
                p.p[k + 1] = 1;
        for (int a = 0; a < FE_ND + FE_NZ; a++)
            for (int b = 0; b < FE_ND + FE_NZ; b++) {
                double wi[3], wo[3], rgb[3];
                fe_dir(a, wi);
                fe_dir(b, wo);
                ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
                for (int c = 0; c < 3; c++)
                    ck_assert_msg(isfinite(rgb[c]) && rgb[c] >= 0,
                                  "%s p=(%g,%g,%g) wi=(%g,%g,%g) wo=(%g,%g,%g): f=%g", mi->name,
                                  p.p[0], p.p[1], p.p[2], wi[0], wi[1], wi[2], wo[0], wo[1],
                                  wo[2], rgb[c]);
            }
    }
}
END_TEST

START_TEST(exponent_million)
{
    /* every lobe with an exponent up to 1e6, there (the others at their start):
     * the peak is finite and huge, off-peak values underflow to 0 cleanly */
    brdffit_params p;
    memset(&p, 0, sizeof p);
    p.s[0] = p.s[1] = p.s[2] = 1;
    double wi[3], wo[3], rgb[3];
    tu_dir_at(30, 0, wi);
    tu_dir_at(30, 180, wo);
    int tested = 0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        int big = -1;
        for (int k = 0; k < mi->nparams; k++)
            if (mi->params[k].upper >= 1e6)
                big = k;
        if (big < 0 || mi->chromatic)
            continue;
        tested++;
        tu_start_params((brdffit_model)m, p.p);
        p.p[big] = 1e6;
        ck_assert_int_eq(brdffit_eval((brdffit_model)m, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
        ck_assert_msg(isfinite(rgb[0]) && rgb[0] > 1e4, "peak of %s at %s=1e6: %g", mi->name,
                      mi->params[big].name, rgb[0]);
        double off[3];
        tu_dir_at(40, 180, off); /* half-vector 5 deg off the peak */
        ck_assert_int_eq(brdffit_eval((brdffit_model)m, &p, wi, off, rgb, NULL), BRDFFIT_OK);
        ck_assert_msg(isfinite(rgb[0]) && rgb[0] >= 0 && rgb[0] < 1e-100, "%s off-peak %g",
                      mi->name, rgb[0]);
    }
    ck_assert_int_ge(tested, 3); /* Blinn-Phong, Lafortune, Ashikhmin-Shirley */
    /* a direction pair scaled to |C| = 50 (Lafortune), exponent 5000: the
     * normalisation comes before the power, so the peak does not underflow */
    int pairs = 0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        for (int k = 0; k + 1 < mi->nparams; k++) {
            if (mi->params[k].map != BRDFFIT_MAP_DIRECTION)
                continue;
            tu_start_params((brdffit_model)m, p.p);
            double f = 50.0 / fmax(fabs(p.p[k]), fabs(p.p[k + 1]));
            p.p[k] *= f, p.p[k + 1] *= f;
            for (int e = 0; e < mi->nparams; e++)
                if (mi->params[e].upper >= 1e6)
                    p.p[e] = 5000;
            ck_assert_int_eq(brdffit_eval((brdffit_model)m, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
            ck_assert_msg(rgb[0] > 1.0, "%s peak with |C| = 50, n = 5000: %g", mi->name, rgb[0]);
            pairs++;
            k++;
        }
    }
    ck_assert_int_ge(pairs, 1);
}
END_TEST

/* The kernel's exponential (kernels/bf_exp.h, compiled here for the host)
 * against expl: bf_exp_poly within 5e-16 relative over [-708, 709] (2.3 ulp;
 * glibc's exp is within 1) and clamped outside; bf_exp_wide_poly the same
 * where e^x is normal and within one subnormal step of exp below, 0 where
 * exp underflows to 0; both finite at any argument.  The host's bf_exp and
 * bf_exp_wide (glibc's exp) take the same clamps. */
START_TEST(exp_function)
{
    double worst = 0.0, worst_wide = 0.0;
    long checked = 0;
    for (double x = -708.0; x <= 709.0; x += 7.13e-4) {
        long double e = expl((long double)x);
        worst = fmax(worst, (double)fabsl(bf_exp_poly(x) / e - 1.0L));
        worst_wide = fmax(worst_wide, (double)fabsl(bf_exp_wide_poly(x) / e - 1.0L));
        checked++;
    }
    ck_assert_msg(worst <= 5e-16, "bf_exp_poly: %g relative", worst);
    ck_assert_msg(worst_wide <= 5e-16, "bf_exp_wide_poly: %g relative", worst_wide);
    for (double x = -760.0; x < -708.0; x += 1.3e-4) {
        double e = exp(x), w = bf_exp_wide_poly(x);
        if (e >= DBL_MIN)
            ck_assert_msg(fabs(w / e - 1.0) <= 5e-16, "bf_exp_wide_poly(%.17g) = %g, exp %g", x, w, e);
        else
            ck_assert_msg(fabs(w - e) <= 4.9406564584124654e-324, "bf_exp_wide_poly(%.17g) = %g, exp %g",
                          x, w, e);
        checked++;
    }
    ck_assert(bf_exp_wide_poly(-746.0) == 0.0 && bf_exp_wide_poly(-1e300) == 0.0);
    ck_assert(bf_exp_poly(-1e300) == bf_exp_poly(-708.0) && bf_exp_poly(1e300) == bf_exp_poly(709.0));
    ck_assert(isfinite(bf_exp_poly(1e300)) && isfinite(bf_exp_wide_poly(1e300)));
    ck_assert(bf_exp(-1e300) == exp(-708.0) && bf_exp(1e300) == exp(709.0));
    ck_assert(bf_exp_wide(-745.3) == 0.0 && bf_exp_wide(-745.0) == exp(-745.0) && bf_exp_wide(1.5) == exp(1.5));
    ck_assert_int_gt(checked, 2000000);
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
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb, NULL), BRDFFIT_E_PARAM_RANGE);
    p.p[0] = 0.0; /* alpha = 0 is no Ward lobe */
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb, NULL), BRDFFIT_E_PARAM_RANGE);
    p.p[0] = 0.1;
    p.d[1] = -0.1;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb, NULL), BRDFFIT_E_PARAM_RANGE);
    p.d[1] = INFINITY;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb, NULL), BRDFFIT_E_PARAM_RANGE);
    p.d[1] = 0.1;
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_eval((brdffit_model)brdffit_model_count(), &p, wi, wo, rgb, NULL), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, NULL, wi, wo, rgb, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, NULL, wo, rgb, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    double zero[3] = { 0, 0, 0 }, nan3[3] = { NAN, 0, 1 };
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, zero, wo, rgb, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &p, nan3, wo, rgb, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0);
    /* a direction pair (Lafortune's Cxy, Cz) with both 0 is no lobe */
    int pairs = 0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        for (int k = 0; k + 1 < mi->nparams; k++)
            if (mi->params[k].map == BRDFFIT_MAP_DIRECTION) {
                published((brdffit_model)m, &p);
                ck_assert_int_eq(brdffit_eval((brdffit_model)m, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
                p.p[k] = p.p[k + 1] = 0;
                ck_assert_int_eq(brdffit_params_check((brdffit_model)m, &p, &err),
                                 BRDFFIT_E_PARAM_RANGE);
                ck_assert_ptr_nonnull(strstr(err.message, mi->params[k + 1].name));
                ck_assert_int_eq(brdffit_eval((brdffit_model)m, &p, wi, wo, rgb, NULL),
                                 BRDFFIT_E_PARAM_RANGE);
                pairs++;
                k++;
            }
    }
    ck_assert_int_ge(pairs, 1);
}
END_TEST

START_TEST(below_horizon_and_batch)
{
    brdffit_params p;
    published(BRDFFIT_COOK_TORRANCE, &p);
    double wi[6] = { 0, 0, 1, 0.3, 0.1, -0.5 }, wo[6] = { 0.6, 0, 0.8, 0, 0, 2 }, rgb[6];
    ck_assert_int_eq(brdffit_eval_batch(BRDFFIT_COOK_TORRANCE, &p, 2, wi, wo, rgb, NULL), BRDFFIT_OK);
    ck_assert(rgb[3] == 0 && rgb[4] == 0 && rgb[5] == 0);
    double one[3];
    ck_assert_int_eq(brdffit_eval(BRDFFIT_COOK_TORRANCE, &p, wi, wo, one, NULL), BRDFFIT_OK);
    for (int c = 0; c < 3; c++)
        ck_assert(one[c] == rgb[c] && one[c] > 0);
    /* unnormalised input directions give the same value */
    double wi2[3] = { 0, 0, 7 }, wo2[3] = { 3, 0, 4 };
    ck_assert_int_eq(brdffit_eval(BRDFFIT_COOK_TORRANCE, &p, wi2, wo2, one, NULL), BRDFFIT_OK);
    for (int c = 0; c < 3; c++)
        ck_assert(tu_reldiff(one[c], rgb[c]) < 1e-14);
}
END_TEST

START_TEST(model_table)
{
    ck_assert_int_eq(brdffit_model_count(), BRDFFIT_MODEL_COUNT);
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        ck_assert_ptr_nonnull(mi);
        ck_assert_int_eq(mi->id, m);
        brdffit_model back;
        ck_assert_int_eq(brdffit_model_from_name(mi->name, &back, NULL), BRDFFIT_OK);
        ck_assert_int_eq(back, m);
        ck_assert(strlen(mi->title) > 0);
        ck_assert(mi->nparams >= 1 && mi->nparams <= BRDFFIT_MAX_LOBE_PARAMS);
        ck_assert(mi->default_starts >= 1 && mi->default_starts <= 1000);
        ck_assert(mi->chromatic == 0 || mi->chromatic == 1);
        for (int k = 0; k < mi->nparams; k++) {
            const brdffit_param_info *pi = brdffit_model_param((brdffit_model)m, k);
            ck_assert_ptr_eq(pi, &mi->params[k]);
            ck_assert(pi->name && *pi->name && pi->unit && pi->description && *pi->description);
            /* lower == upper: a parameter the model holds fixed (the core
             * glTF material's ior and specular) */
            ck_assert(pi->lower < pi->upper ||
                      (pi->lower == pi->upper && mi->colour_form == BRDFFIT_COLOUR_GLTF));
            ck_assert(pi->start >= pi->lower && pi->start <= pi->upper);
            ck_assert(pi->map == BRDFFIT_MAP_LOG || pi->map == BRDFFIT_MAP_LINEAR ||
                      pi->map == BRDFFIT_MAP_DIRECTION);
            if (pi->map == BRDFFIT_MAP_LOG)
                ck_assert(pi->lower > 0);
            if (pi->map == BRDFFIT_MAP_DIRECTION) { /* a pair */
                ck_assert_int_lt(k + 1, mi->nparams);
                ck_assert_int_eq(mi->params[k + 1].map, BRDFFIT_MAP_DIRECTION);
                k++;
            }
        }
        ck_assert_ptr_null(brdffit_model_param((brdffit_model)m, mi->nparams));
        ck_assert_ptr_null(brdffit_model_param((brdffit_model)m, -1));
        /* the default parameters are valid (with colours 0, or for a glTF
         * model the core material's white specular colour) */
        ck_assert(mi->colour_form == BRDFFIT_COLOUR_DS || mi->colour_form == BRDFFIT_COLOUR_GLTF ||
                  mi->colour_form == BRDFFIT_COLOUR_OPENPBR);
        ck_assert(mi->colour_names[0] && mi->colour_names[1]);
        ck_assert_str_eq(mi->colour_names[0], mi->colour_form == BRDFFIT_COLOUR_DS ? "d" : "base_color");
        ck_assert_str_eq(mi->colour_names[1],
                         mi->colour_form == BRDFFIT_COLOUR_DS ? "s" : "specular_color");
        brdffit_params p;
        memset(&p, 0, sizeof p);
        tu_start_params((brdffit_model)m, p.p);
        for (int c = 0; c < 3 && mi->colour_form != BRDFFIT_COLOUR_DS; c++)
            p.s[c] = 1.0;
        ck_assert_int_eq(brdffit_params_check((brdffit_model)m, &p, NULL), BRDFFIT_OK);
    }
    brdffit_model m;
    ck_assert_int_eq(brdffit_model_from_name("cook_torrance", &m, NULL), BRDFFIT_OK);
    ck_assert_int_eq(m, BRDFFIT_COOK_TORRANCE);
    /* any case */
    ck_assert_int_eq(brdffit_model_from_name("Cook-Torrance", &m, NULL), BRDFFIT_OK);
    ck_assert_int_eq(m, BRDFFIT_COOK_TORRANCE);
    ck_assert_int_eq(brdffit_model_from_name("GGX", &m, NULL), BRDFFIT_OK);
    ck_assert_int_eq(m, BRDFFIT_GGX);
    ck_assert_int_eq(brdffit_model_from_name("ASHIKHMIN_shirley", &m, NULL), BRDFFIT_OK);
    ck_assert_int_eq(m, BRDFFIT_ASHIKHMIN_SHIRLEY);
    for (int k = 0; k < brdffit_model_count(); k++) /* the registry's names are lower case */
        for (const char *c = brdffit_model_get((brdffit_model)k)->name; *c; c++)
            ck_assert_msg(*c == '-' || (*c >= 'a' && *c <= 'z'), "%s", brdffit_model_get((brdffit_model)k)->name);
    ck_assert_int_eq(brdffit_model_from_name("phong", &m, NULL), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_model_from_name("ward-duerX", &m, NULL), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_model_from_name("Ward-Duer-", &m, NULL), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_model_from_name(NULL, &m, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_null(brdffit_model_get((brdffit_model)brdffit_model_count()));
    ck_assert_ptr_null(brdffit_model_get((brdffit_model)-1));
    ck_assert_ptr_null(brdffit_model_param((brdffit_model)brdffit_model_count(), 0));
    for (int s = 0; s < BRDFFIT_STATUS_COUNT; s++)
        ck_assert(strlen(brdffit_strerror((brdffit_status)s)) > 0);
    ck_assert_str_eq(brdffit_strerror((brdffit_status)999), "unknown status");
}
END_TEST

/* BF_MODEL_LOBES (kernels/bf_models.h) binds each registry entry, by id, to
 * the lobe of its name: every id once, in order, "ward_duer" for "ward-duer". */
START_TEST(lobe_list_is_the_registry)
{
    static const struct { int id; const char *name; } lobes[] = {
#define LOBE_ROW(id, name, fd) { id, #name },
        BF_MODEL_LOBES(LOBE_ROW)
#undef LOBE_ROW
    };
    int n = (int)(sizeof lobes / sizeof lobes[0]);
    ck_assert_int_eq(n, BF_LOBE_MODELS);
    /* the models with a lobe are ids 0 .. n-1; the rest (the glTF models) have none */
    for (int m = 0; m < brdffit_model_count(); m++) {
        ck_assert_int_eq(bf_model_has_lobe((brdffit_model)m), m < n);
        int form = brdffit_model_get((brdffit_model)m)->colour_form;
        ck_assert_int_eq(form == BRDFFIT_COLOUR_DS, m < n);
    }
    ck_assert(!bf_model_has_lobe((brdffit_model)brdffit_model_count()));
    ck_assert(!bf_model_has_lobe((brdffit_model)-1));
    for (int i = 0; i < n; i++) {
        ck_assert_int_eq(lobes[i].id, i);
        char want[64];
        snprintf(want, sizeof want, "%s", brdffit_model_get((brdffit_model)i)->name);
        for (char *c = want; *c; c++)
            if (*c == '-')
                *c = '_';
        ck_assert_str_eq(lobes[i].name, want);
    }
    /* an id out of range has no lobe */
    bf_geom g = { 0, 0, 1, 0, 0, 1, 0, 0 };
    bf_geom_derive(&g);
    double p[3] = { 0.1, 0.1, 0.1 }, lam[3] = { 0.6, 0.5, 0.4 }, K[3] = { 1, 1, 1 };
    bf_lobe(n, &g, p, lam, K);
    ck_assert(K[0] == 0 && K[1] == 0 && K[2] == 0);
}
END_TEST

/* The ABI: model ids and names never change (new models are appended), nor do
 * the values of the other public enums. */
START_TEST(abi_values)
{
    static const struct { int id; const char *name; } pinned[] = {
        { BRDFFIT_WARD, "ward" }, { BRDFFIT_WARD_DUER, "ward-duer" },
        { BRDFFIT_BLINN_PHONG, "blinn-phong" }, { BRDFFIT_LAFORTUNE, "lafortune" },
        { BRDFFIT_COOK_TORRANCE, "cook-torrance" }, { BRDFFIT_ASHIKHMIN_SHIRLEY, "ashikhmin-shirley" },
        { BRDFFIT_HE, "he" }, { BRDFFIT_GGX, "ggx" },
    };
    for (int i = 0; i < (int)(sizeof pinned / sizeof pinned[0]); i++) {
        ck_assert_int_eq(pinned[i].id, i);
        ck_assert_str_eq(brdffit_model_get((brdffit_model)i)->name, pinned[i].name);
    }
    ck_assert_int_eq(BRDFFIT_MAP_LOG, 0);
    ck_assert_int_eq(BRDFFIT_MAP_LINEAR, 1);
    ck_assert_int_eq(BRDFFIT_MAP_DIRECTION, 2);
    /* status values are pinned: callers and FFI mirrors compare numbers */
    ck_assert_int_eq(BRDFFIT_E_INVALID_ARGUMENT, 1);
    ck_assert_int_eq(BRDFFIT_E_FILE_OPEN, 3);
    ck_assert_int_eq(BRDFFIT_E_FILE_NONFINITE, 10);
    ck_assert_int_eq(BRDFFIT_E_FIT_FAILED, 18);
    ck_assert_int_eq(BRDFFIT_E_VALUE_RANGE, 21);
    ck_assert_int_eq(BRDFFIT_E_OPTIONS_SIZE, 22);
    ck_assert_int_eq(BRDFFIT_STATUS_COUNT, 23);
}
END_TEST

/* The lobe's K at p[0] and its forward-difference neighbours, each evaluated
 * (BF_FD_POINTWISE, the plain forward differences): the oracle of the
 * partials a data pass takes instead (BF_FD_GRAD, BF_FD_SCHLICK). */
static void fd_pointwise(int model, const bf_geom *g, const double (*p)[3], int np,
                         const double *lam, double *K0, double (*Kj)[3])
{
    switch (model) {
#define PW_CASE(id, name, fd) \
    case id: { BF_FD_POINTWISE(name) } return;
        BF_MODEL_LOBES(PW_CASE)
#undef PW_CASE
    default: ck_abort_msg("model %d has no lobe", model);
    }
}

/* A data pass's derivative of a closed-form lobe in each parameter,
 * (K(p_j) - K(p_0)) / h from bf_lobe_fd with p_j = p_0 + h e_j, h = 1e-8 of
 * |p_j| (its partials, BF_FD_GRAD / BF_FD_SCHLICK), against the central
 * difference (K(p_0 + H e_j) - K(p_0 - H e_j)) / 2H of the lobe evaluated
 * at those points (fd_pointwise), H = 1e-6 of |p_j| or less where K
 * changes by more than 1e-3 of itself over it: within 1e-5 of
 * |G| + |K| / |p_j| at random points and directions (the central
 * difference's own error is ~H^2 / 6 times the third partial, ~1e-7 of
 * it; not where K is subnormal), and finite at the corners of the parameter
 * box too.  K0 is the lobe's value, bit for bit. */
START_TEST(partials_match_differences)
{
    brdffit_model m = closed_lobe_model(_i);
    const brdffit_model_info *mi = brdffit_model_get(m);
    ck_assert_int_ne(bf_lobe_fd_kind((int)m), BF_FD_KIND_OWN);
    const double lam[3] = { 0.645, 0.526, 0.444 };
    const int np = mi->nparams, corners = 1 << np;
    unsigned st = 4242u + (unsigned)_i;
    long compared = 0;
    for (int pt = 0; pt < corners + 40; pt++) {
        double p0[3] = { 0, 0, 0 };
        for (int k = 0; k < np; k++) {
            double lo = mi->params[k].lower, hi = mi->params[k].upper;
            if (pt < corners)
                p0[k] = (pt >> k & 1) ? hi : lo;
            else if (mi->params[k].map == BRDFFIT_MAP_LOG) /* log-uniform, as the fit sees it */
                p0[k] = lo * pow(hi / lo, tu_urand(&st));
            else
                p0[k] = lo + (hi - lo) * tu_urand(&st);
        }
        if (mi->params[0].map == BRDFFIT_MAP_DIRECTION) {
            if (p0[0] == 0 && p0[1] == 0)
                p0[1] = 1;
            if (fabs(fabs(p0[0]) - fabs(p0[1])) < 1e-3 * fmax(fabs(p0[0]), fabs(p0[1])))
                p0[1] *= 1.01; /* off Lafortune's kink at |Cxy| = |Cz| */
        }
        double pa[4][3], step[3];
        for (int j = 0; j <= np; j++) {
            memcpy(pa[j], p0, sizeof p0);
            if (j > 0) {
                step[j - 1] = 1e-8 * fmax(fabs(p0[j - 1]), 1e-3);
                pa[j][j - 1] += step[j - 1];
            }
        }
        for (int t = 0; t < 400; t++) {
            double wi[3], wo[3], K0[3], Ka[3][3], Kb0[3], Kb[3][3], Kc[3][3];
            double ga[3], H[3], pb[4][3], pc[4][3];
            tu_rand_dir(&st, t < 200 ? 1e-3 : 0.2, wi);
            tu_rand_dir(&st, t < 200 ? 1e-3 : 0.2, wo);
            bf_geom g = { wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], 0, 0 };
            bf_geom_derive(&g);
            bf_lobe_fd((int)m, &g, (const double(*)[3])pa, np, lam, K0, Ka, NULL);
            /* the oracle's step: 1e-6 of |p_j|, or less where K changes by more
             * than 1e-3 of itself over it (a far tail) */
            for (int j = 0; j <= np; j++) {
                memcpy(pb[j], p0, sizeof p0);
                memcpy(pc[j], p0, sizeof p0);
                if (j == 0)
                    continue;
                ga[j - 1] = (Ka[j - 1][0] - K0[0]) / step[j - 1];
                H[j - 1] = 100.0 * step[j - 1];
                if (fabs(ga[j - 1]) * H[j - 1] > 1e-3 * K0[0])
                    H[j - 1] = 1e-3 * K0[0] / fabs(ga[j - 1]);
                pb[j][j - 1] += H[j - 1];
                pc[j][j - 1] -= H[j - 1];
            }
            fd_pointwise((int)m, &g, (const double(*)[3])pb, np, lam, Kb0, Kb);
            ck_assert(memcmp(K0, Kb0, sizeof K0) == 0);
            fd_pointwise((int)m, &g, (const double(*)[3])pc, np, lam, Kb0, Kc);
            for (int j = 0; j < np; j++) {
                ck_assert_msg(isfinite(ga[j]), "%s p=(%g,%g,%g): partial %d is %g", mi->name,
                              p0[0], p0[1], p0[2], j, ga[j]);
                if (pt < corners || !(K0[0] > 1e-280)) /* subnormal K: no digits to compare */
                    continue;
                double gb = (Kb[j][0] - Kc[j][0]) / ((pb[1 + j][j] - p0[j]) - (pc[1 + j][j] - p0[j]));
                double scale = fabs(gb) + fabs(K0[0]) / fmax(fabs(p0[j]), 1e-3);
                ck_assert_msg(fabs(ga[j] - gb) <= 1e-5 * scale,
                              "%s p=(%.9g,%.9g,%.9g) wi=(%g,%g,%g) wo=(%g,%g,%g) K=%g: partial %d "
                              "%.9g, difference %.9g",
                              mi->name, p0[0], p0[1], p0[2], wi[0], wi[1], wi[2], wo[0], wo[1],
                              wo[2], K0[0], j, ga[j], gb);
                compared++;
            }
        }
    }
    ck_assert_msg(compared > 40L * 400 * np / 4, "%s: only %ld partials compared where K > 0",
                  mi->name, compared);
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
    brdffit_model ms[BRDFFIT_MODEL_COUNT];
    int nclosed = closed_form(ms), nlobes = closed_form_of(ms, 1);
    tcase_add_loop_test(tc, reciprocity, 0, nclosed);
    tcase_add_loop_test(tc, finite_everywhere, 0, nclosed);
    tcase_add_loop_test(tc, partials_match_differences, 0, nlobes);
    tcase_add_test(tc, exponent_million);
    tcase_add_test(tc, exp_function);
    tcase_add_test(tc, bad_parameters);
    tcase_add_test(tc, below_horizon_and_batch);
    tcase_add_test(tc, model_table);
    tcase_add_test(tc, abi_values);
    tcase_add_test(tc, lobe_list_is_the_registry);
    suite_add_tcase(s, tc);
    return s;
}
