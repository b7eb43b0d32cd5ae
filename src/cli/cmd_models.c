/* SPDX-License-Identifier: MIT */
/* cmd_models.c -- `brdffit models`: the models, their lobe parameters and bounds. */
#include "cli.h"

int cmd_models(int argc, char **argv)
{
    if (argc > 0) {
        if (cli_is_help(argv[0]))
            return CLI_HELP;
        return cli_usage_error("models takes no arguments (got '%s')", argv[0]);
    }
    printf("%-18s %-18s %s\n", "model", "title", "lobe parameters: name [lower, upper] (start)");
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        printf("%-18s %-18s", mi->name, mi->title);
        for (int k = 0; k < mi->nparams; k++)
            printf("%s %s [%g, %g] (%g)", k ? "," : "", mi->param_names[k], mi->lower[k],
                   mi->upper[k], mi->start[k]);
        printf("%s\n", mi->chromatic ? "; per-channel lobe" : "");
    }
    printf("\nEvery model: f_c = d_c/pi + s_c K_c(wi, wo; p) per channel c = R, G, B;\n"
           "d_c, s_c >= 0.  He: tau and sigma0 in micrometres, n a refractive index,\n"
           "wavelengths 0.645, 0.526, 0.444 um.\n");
    return CLI_OK;
}
