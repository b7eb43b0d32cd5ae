/* SPDX-License-Identifier: MIT */
/* demo_material.c -- the embedded synthetic material of `demo` and `batch --demo`:
 * a Cook-Torrance lobe plus Lambertian diffuse at the published Ngan et al.
 * 2005 Cook-Torrance fit of MERL alum-bronze, stored as a MERL table. */
#include "batch.h"
#include "cli.h"

static const brdffit_params demo_truth = {
    .d = { 0.0886, 0.0602, 0.0299 },
    .s = { 0.118, 0.0698, 0.0371 },
    .p = { 0.203, 0.0367 },
};

const char *cli_demo_name(void)
{
    return "synthetic-alum-bronze-ct";
}

const brdffit_params *cli_demo_truth(brdffit_model *model)
{
    *model = BRDFFIT_COOK_TORRANCE;
    return &demo_truth;
}

brdffit_status cli_demo_table(brdffit_scale scale, brdffit_table **out, brdffit_error *err)
{
    brdffit_table *t = NULL;
    brdffit_model model;
    const brdffit_params *p = cli_demo_truth(&model);
    brdffit_status st = brdffit_table_create(&t, err);
    if (st == BRDFFIT_OK)
        st = brdffit_table_fill_model(t, model, p, scale, err);
    if (st != BRDFFIT_OK) {
        brdffit_table_free(t);
        t = NULL;
    }
    *out = t;
    return st;
}
