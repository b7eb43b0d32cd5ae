/* SPDX-License-Identifier: MIT */
/* mktable.c -- write a MERL table made by a Cook-Torrance lobe (F0 0.4,
 * m 0.15, plus a Lambertian term) for README's example to fit back
 * (tests/packaging.sh; needs no ../shared).  Usage: mktable OUT.binary */
#include <brdffit.h>

#include <stdio.h>

int main(int argc, char **argv)
{
    brdffit_params p = { { 0.08, 0.06, 0.03 }, { 0.12, 0.07, 0.04 }, { 0.4, 0.15, 0 }, { 0 } };
    brdffit_error err;
    brdffit_table *t = NULL;
    if (argc != 2)
        return 2;
    if (brdffit_table_create(&t, &err) != BRDFFIT_OK ||
        brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p, BRDFFIT_SCALE_STANDARD, &err) !=
            BRDFFIT_OK ||
        brdffit_table_write(t, argv[1], &err) != BRDFFIT_OK) {
        fprintf(stderr, "mktable: %s\n", err.message);
        brdffit_table_free(t);
        return 1;
    }
    brdffit_table_free(t);
    return 0;
}
