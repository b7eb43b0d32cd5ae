/* SPDX-License-Identifier: MIT */
/* cmd_models.c -- `brdffit models`: the models of the registry, their lobe parameters
 * (bounds, units, typical values, what they are) and default starts. */
#include "cli.h"

int cmd_models(int argc, char **argv)
{
    if (argc > 0) {
        if (cli_is_help(argv[0]))
            return CLI_HELP;
        return cli_usage_error("models takes no arguments (got '%s')", argv[0]);
    }
    printf("%-18s %-18s %s\n", "model", "title",
           "lobe parameters: name [lower, upper] unit (start); default starts");
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        printf("%-18s %-18s", mi->name, mi->title);
        for (int k = 0; k < mi->nparams; k++) {
            const brdffit_param_info *pi = &mi->params[k];
            printf("%s %s [%g, %g]%s%s (%g)", k ? "," : "", pi->name, pi->lower, pi->upper,
                   *pi->unit ? " " : "", pi->unit, pi->start);
        }
        printf("; %d starts%s\n", mi->default_starts, mi->chromatic ? "; per-channel lobe" : "");
        for (int k = 0; k < mi->nparams; k++)
            printf("%-37s %s: %s\n", "", mi->params[k].name, mi->params[k].description);
    }
    printf("\nEvery model: f_c = d_c/pi + s_c K_c(wi, wo; p) per channel c = R, G, B;\n"
           "d_c, s_c >= 0.  Unit um: micrometres; no unit: dimensionless.  A per-channel\n"
           "lobe is evaluated at the wavelengths 0.645, 0.526, 0.444 um.\n");
    return CLI_OK;
}
