/* SPDX-License-Identifier: MIT */
/* mitsuba_options.c -- the options of `brdffit export --format mitsuba` that
 * set the scene: the size, samples per pixel, lights and environment map,
 * as `brdffit render` takes them (export.h). */
#define _XOPEN_SOURCE 700
#include "draw.h"
#include "export.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* --light X,Y,Z[:R,G,B] */
static int add_light(mitsuba_scene *sc, const char *v)
{
    if (!sc->lights_given)
        sc->nlights = 0;
    sc->lights_given = 1;
    if (sc->nlights >= BRDFFIT_RENDER_MAX_LIGHTS)
        return cli_usage_error("--light: at most %d lights", BRDFFIT_RENDER_MAX_LIGHTS);
    if (draw_light(v, &sc->lights[sc->nlights]) != CLI_OK)
        return CLI_USAGE;
    sc->nlights++;
    return CLI_OK;
}

/* --env FILE: its absolute path, so the scene renders from any directory. */
static int set_env(mitsuba_scene *sc, const char *v)
{
    char buf[PATH_MAX];
    if (!realpath(v, buf))
        return cli_usage_error("--env '%s': no such file", v);
    if (strlen(buf) >= sizeof sc->env)
        return cli_usage_error("--env '%s': path too long", v);
    strcpy(sc->env, buf);
    return CLI_OK;
}

static int is_square(int n)
{
    int k = 0;
    while ((k + 1) * (k + 1) <= n)
        k++;
    return k * k == n;
}

int mitsuba_option(mitsuba_scene *sc, int argc, char **argv, int *i)
{
    const char *v;
    int r;
    if ((r = draw_option(argc, argv, i, "--size", &v)) != 0)
        return r != 1 ? r : cli_parse_int(v, 1, 4096, &sc->width) == 0
                                ? CLI_OK : cli_usage_error("--size '%s': expected 1..4096", v);
    if ((r = draw_option(argc, argv, i, "--spp", &v)) != 0)
        return r != 1 ? r : cli_parse_int(v, 1, 1 << 20, &sc->spp) == 0 && is_square(sc->spp)
                                ? CLI_OK
                                : cli_usage_error("--spp '%s': expected a square 1..1048576 "
                                                  "(Mitsuba's stratified sampler: 16, 64, 256...)", v);
    if ((r = draw_option(argc, argv, i, "--light", &v)) != 0)
        return r != 1 ? r : add_light(sc, v);
    if ((r = draw_option(argc, argv, i, "--env", &v)) != 0)
        return r != 1 ? r : set_env(sc, v);
    return 1;
}

void mitsuba_options_done(mitsuba_scene *sc)
{
    if (sc->env[0] && !sc->lights_given)
        sc->nlights = 0; /* the environment alone, as render */
}
