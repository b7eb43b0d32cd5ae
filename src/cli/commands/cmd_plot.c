/* SPDX-License-Identifier: MIT */
/* cmd_plot.c -- `brdffit plot TABLE --out DIR [OPTIONS]`: the incidence-plane
 * plots (SVG, cube root) of the measured table and of every fitted model. */
#include "draw.h"

#include <string.h>

const cli_help_block *cli_plot_help(void)
{
    static const cli_help_item items[] = {
        { "--theta-i DEG[,DEG...]",
          "incidence angles in [0, 90), at most 16 (default\n20,40,60,75)" },
        { "--points N", "theta_o samples from -90 to 90, 2..100000 (default 180)" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK("Options of plot", NULL, items);
    return &block;
}

static int set_theta_i(draw_job *j, const char *v)
{
    brdffit_curve_options *c = &j->s.curve_opt;
    int n = draw_numbers(v, c->theta_i_deg, BRDFFIT_CURVE_MAX_THETA_I);
    if (n < 1)
        return cli_usage_error("--theta-i '%s': expected up to %d degrees, comma-separated", v,
                               BRDFFIT_CURVE_MAX_THETA_I);
    for (int k = 0; k < n; k++)
        if (!(c->theta_i_deg[k] >= 0 && c->theta_i_deg[k] < 90))
            return cli_usage_error("--theta-i '%s': %g is not in [0, 90)", v, c->theta_i_deg[k]);
    c->ntheta_i = n;
    return CLI_OK;
}

int cmd_plot(int argc, char **argv)
{
    draw_job j;
    int rc = draw_init(&j, argc);
    j.s.render = 0;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        const char *v;
        int r;
        if (cli_is_help(argv[i])) {
            rc = CLI_HELP;
        } else if ((r = draw_option(argc, argv, &i, "--theta-i", &v)) != 0) {
            rc = r != 1 ? r : set_theta_i(&j, v);
        } else if ((r = draw_option(argc, argv, &i, "--points", &v)) != 0) {
            rc = r != 1 ? r : cli_parse_int(v, 2, 100000, &j.s.curve_opt.npoints) == 0
                                  ? CLI_OK : cli_usage_error("--points '%s': expected 2..100000", v);
        } else {
            r = draw_common_option(&j, argc, argv, &i);
            if (r == 1)
                draw_keep(&j, argv[i]);
            else
                rc = r;
        }
    }
    if (rc == CLI_OK)
        rc = draw_run(&j, "plot");
    draw_free(&j);
    return rc;
}
