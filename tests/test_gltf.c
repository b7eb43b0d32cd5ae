/* SPDX-License-Identifier: MIT */
/* test_gltf.c -- the glTF models (gltf, gltf-ext): values of an independent
 * implementation of glTF 2.0 Appendix B with KHR_materials_ior and
 * KHR_materials_specular (the numpy `reference` of
 * python/tests/test_gltf_model.py, written from the specification's text,
 * which checks many more points), the core model's fixed parameters and the
 * colours' bounds.  Reciprocity and finiteness are the registry-wide tests
 * (test_models.c). */
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <string.h>

typedef struct gltf_case {
    brdffit_model model;
    double base[3], scol[3], p[4]; /* p: metallic, roughness, ior, specular */
    double wi[3], wo[3];           /* not unit: both sides normalise them   */
    double want[3];
} gltf_case;

/* Core material: dielectric at normal incidence; metal; half metal at roughness 1
 * with a grazing (81.9 deg) light.  Extended: ior 3 with a specular colour whose
 * product with f0 = 0.25 exceeds 1 in G and B (clamped: G = B); roughness 0
 * (floored at 1e-3) with ior 1 (f0 = 0) at half specular; ior 2.2 with a light
 * at 89.9 deg. */
static const gltf_case cases[] = {
    { BRDFFIT_GLTF, { 0.8, 0.5, 0.1 }, { 1.0, 1.0, 1.0 }, { 0.0, 0.5, 1.5, 1.0 },
      { 0.0, 0.0, 1.0 }, { 0.0, 0.0, 1.0 },
      { 0.29539157437855779, 0.20371832715762603, 0.081487330863050433 } },
    { BRDFFIT_GLTF, { 0.8, 0.5, 0.1 }, { 1.0, 1.0, 1.0 }, { 1.0, 0.3, 1.5, 1.0 },
      { 0.5, 0.1, 0.86 }, { -0.3, 0.2, 0.93 },
      { 0.29471460980889819, 0.18419727220631912, 0.036840822069547037 } },
    { BRDFFIT_GLTF, { 0.2, 0.9, 0.4 }, { 1.0, 1.0, 1.0 }, { 0.4, 1.0, 1.5, 1.0 },
      { 0.99, 0.0, 0.1411 }, { 0.3, -0.6, 0.74 },
      { 0.055450388335176196, 0.23429850712052386, 0.10654985084527553 } },
    { BRDFFIT_GLTF_EXT, { 0.7, 0.2, 0.4 }, { 0.2, 4.5, 6.0 }, { 0.0, 0.01, 3.0, 1.0 },
      { 0.6, 0.0, 0.8 }, { -0.58, 0.05, 0.81 },
      { 5.1064162050877204e-05, 0.0010160408713609157, 0.0010160408713609157 } },
    { BRDFFIT_GLTF_EXT, { 0.7, 0.2, 0.4 }, { 1.0, 2.0, 3.5 }, { 0.3, 0.0, 1.0, 0.5 },
      { 0.2, 0.3, 0.9 }, { 0.1, -0.4, 0.8 },
      { 0.15597165678459973, 0.044563330509885743, 0.089126661019771347 } },
    { BRDFFIT_GLTF_EXT, { 1.0, 1.0, 1.0 }, { 0.5, 1.0, 2.0 }, { 0.6, 0.5, 2.2, 0.8 },
      { 0.9998477, 0.0, 0.0017453 }, { 0.4, 0.4, 0.82 },
      { 0.14871722549427949, 0.15052593906769379, 0.15414336621452243 } },
};
#define NCASES (int)(sizeof cases / sizeof cases[0])

static brdffit_params params_of(const gltf_case *c)
{
    brdffit_params p;
    memset(&p, 0, sizeof p);
    memcpy(p.d, c->base, sizeof p.d);
    memcpy(p.s, c->scol, sizeof p.s);
    memcpy(p.p, c->p, sizeof c->p);
    return p;
}

/* brdffit_eval equals the reference to 1e-12 relative; a core case equals
 * gltf-ext at the same parameters bit for bit. */
START_TEST(reference_values)
{
    const gltf_case *c = &cases[_i];
    brdffit_params p = params_of(c);
    double rgb[3], ext[3];
    brdffit_error err;
    ck_assert_msg(brdffit_eval(c->model, &p, c->wi, c->wo, rgb, &err) == BRDFFIT_OK, "%s", err.message);
    for (int k = 0; k < 3; k++)
        ck_assert_msg(tu_reldiff(rgb[k], c->want[k]) <= 1e-12, "case %d channel %d: %.17g vs %.17g",
                      _i, k, rgb[k], c->want[k]);
    if (c->model == BRDFFIT_GLTF) {
        ck_assert_int_eq(brdffit_eval(BRDFFIT_GLTF_EXT, &p, c->wi, c->wo, ext, NULL), BRDFFIT_OK);
        for (int k = 0; k < 3; k++)
            ck_assert(ext[k] == rgb[k]);
    }
}
END_TEST

/* The core model takes ior 1.5, specular 1 and a white specular colour
 * only; both take base colours in [0, 1] only: BRDFFIT_E_PARAM_RANGE naming
 * the value. */
START_TEST(bounds)
{
    const gltf_case *c = &cases[0];
    struct { brdffit_model m; int what; double v; const char *name; } bad[] = {
        { BRDFFIT_GLTF, 0, 1.4, "ior" },          { BRDFFIT_GLTF, 1, 0.9, "specular" },
        { BRDFFIT_GLTF, 2, 0.5, "specular_color_g" },
        { BRDFFIT_GLTF, 3, 1.01, "base_color_g" }, { BRDFFIT_GLTF_EXT, 3, -0.1, "base_color_g" },
        { BRDFFIT_GLTF_EXT, 3, NAN, "base_color_g" }, { BRDFFIT_GLTF_EXT, 0, 0.5, "ior" },
        { BRDFFIT_GLTF_EXT, 2, -1, "specular_color_g" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        brdffit_params p = params_of(c);
        double *slot[4] = { &p.p[2], &p.p[3], &p.s[1], &p.d[1] };
        *slot[bad[i].what] = bad[i].v;
        double rgb[3];
        brdffit_error err;
        ck_assert_int_eq(brdffit_eval(bad[i].m, &p, c->wi, c->wo, rgb, &err), BRDFFIT_E_PARAM_RANGE);
        ck_assert_msg(strstr(err.message, bad[i].name), "%zu: %s", i, err.message);
    }
    /* gltf-ext takes what the core model refuses */
    brdffit_params p = params_of(&cases[3]);
    ck_assert_int_eq(brdffit_params_check(BRDFFIT_GLTF_EXT, &p, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_params_check(BRDFFIT_GLTF, &p, NULL), BRDFFIT_E_PARAM_RANGE);
}
END_TEST

Suite *gltf_suite(void)
{
    Suite *s = suite_create("gltf");
    TCase *tc = tcase_create("values");
    tcase_add_loop_test(tc, reference_values, 0, NCASES);
    tcase_add_test(tc, bounds);
    suite_add_tcase(s, tc);
    return s;
}
