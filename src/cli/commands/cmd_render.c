/* SPDX-License-Identifier: MIT */
/* cmd_render.c -- `brdffit render TABLE --out DIR [OPTIONS]`: the measured
 * reference and every fitted model rendered (EXR, PNG), the difference
 * images and the image errors (printed, renders.json). */
#include "draw.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const cli_help_block *cli_draw_help(void)
{
    static const cli_help_item items[] = {
        { "--out DIR", "where the files go (made when missing)" },
        { "--fits FILE", "the fits to draw: `brdffit fit --json` output (JSON\n"
                         "Lines) or an ngan2005-fits.tsv-style TSV; default:\n"
                         "fit the models now; a TSV's parameters are scored\n"
                         "on TABLE (their Error); one stating '# scale: S'\n"
                         "needs --scale S" },
        { "--allow-scale-mismatch", "draw a --fits TSV of another scale anyway" },
        { "--interp trilinear|nearest", "table lookup (default trilinear)" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK(
        "Options of render and plot",
        "and the options of fit: --model, --scale, --cutoff,\n--starts, --backend, --device",
        items);
    return &block;
}

const cli_help_block *cli_render_help(void)
{
    static const cli_help_item items[] = {
        { "--size N", "N x N pixels, 1..4096 (default 256)" },
        { "--light X,Y,Z[:R,G,B]", "a directional light toward X,Y,Z (camera frame: x right,\n"
                                   "y up, z toward the viewer), irradiance R,G,B (default\n"
                                   "1,1,1); repeatable, at most 16; default: a key light\n"
                                   "-1,1,1.5 and a rim light 1,0.25,-0.6:0.5,0.5,0.5" },
        { "--env FILE.exr", "a latitude-longitude environment (RGB radiance, half\n"
                            "or float); without --light it is the only light" },
        { "--env-samples N", "quadrature directions per pixel, 1..65536 (default 256)" },
        { "--exposure E", "PNG exposure (default: 1 / the 99th percentile of the\n"
                          "reference's max(R, G, B))" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK("Options of render", NULL, items);
    return &block;
}

/* --light X,Y,Z[:R,G,B] */
static int add_light(draw_job *j, const char *v)
{
    brdffit_render_options *o = &j->s.render_opt;
    if (o->nlights == BRDFFIT_RENDER_DEFAULT_LIGHTS)
        o->nlights = 0;
    if (o->nlights >= BRDFFIT_RENDER_MAX_LIGHTS)
        return cli_usage_error("--light: at most %d lights", BRDFFIT_RENDER_MAX_LIGHTS);
    if (draw_light(v, &o->lights[o->nlights]) != CLI_OK)
        return CLI_USAGE;
    o->nlights++;
    return CLI_OK;
}

/* One option of render (or plot): CLI_OK, CLI_USAGE, or 1 when argv[*i] is not ours. */
static int render_option(draw_job *j, int argc, char **argv, int *i)
{
    const char *v;
    brdffit_render_options *o = &j->s.render_opt;
    int r;
    if ((r = draw_option(argc, argv, i, "--size", &v)) != 0)
        return r != 1 ? r : cli_parse_int(v, 1, 4096, &o->width) == 0
                                ? CLI_OK : cli_usage_error("--size '%s': expected 1..4096", v);
    if ((r = draw_option(argc, argv, i, "--light", &v)) != 0)
        return r != 1 ? r : add_light(j, v);
    if ((r = draw_option(argc, argv, i, "--env-samples", &v)) != 0)
        return r != 1 ? r : cli_parse_int(v, 1, 65536, &o->env_samples) == 0
                                ? CLI_OK : cli_usage_error("--env-samples '%s': expected 1..65536", v);
    if ((r = draw_option(argc, argv, i, "--env", &v)) != 0) {
        if (r == 1)
            j->env = v;
        return r != 1 ? r : CLI_OK;
    }
    if ((r = draw_option(argc, argv, i, "--exposure", &v)) != 0)
        return r != 1 ? r : cli_parse_double(v, &j->s.exposure) == 0 && j->s.exposure > 0
                                ? CLI_OK : cli_usage_error("--exposure '%s': expected a number > 0", v);
    return draw_common_option(j, argc, argv, i);
}

int cmd_render(int argc, char **argv)
{
    draw_job j;
    int rc = draw_init(&j, argc);
    j.s.plot = 0;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        if (cli_is_help(argv[i])) {
            rc = CLI_HELP;
            break;
        }
        int r = render_option(&j, argc, argv, &i);
        if (r == 1)
            draw_keep(&j, argv[i]);
        else
            rc = r;
    }
    if (rc == CLI_OK && j.env && j.s.render_opt.nlights == BRDFFIT_RENDER_DEFAULT_LIGHTS)
        j.s.render_opt.nlights = 0; /* the environment alone */
    if (rc == CLI_OK)
        rc = draw_run(&j, "render");
    draw_free(&j);
    return rc;
}
