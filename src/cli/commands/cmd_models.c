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
    printf("\nThe paper's models and GGX: f_c = d_c/pi + s_c K_c(wi, wo; p) per channel\n"
           "c = R, G, B; d_c, s_c >= 0.  Unit um: micrometres; no unit: dimensionless.\n"
           "A per-channel lobe is evaluated at the wavelengths 0.645, 0.526, 0.444 um.\n"
           "gltf, gltf-ext: the glTF 2.0 BRDF (Appendix B; gltf-ext with KHR_materials_ior\n"
           "and KHR_materials_specular): d = base_color in [0, 1], s = specular_color\n"
           "(gltf: 1, 1, 1), alpha = roughness^2; linear sRGB (docs/conventions.md).\n");
    return CLI_OK;
}
