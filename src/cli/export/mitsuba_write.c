/* SPDX-License-Identifier: MIT */
/* mitsuba_write.c -- a fit as a Mitsuba 3 scene of brdffit's render sphere:
 * the orthographic camera looking down -z onto the unit sphere filling
 * the N x N image, the directional lights (and the environment map) of
 * `brdffit render`, and a BSDF of type "brdffit" (the plugin of the Python
 * package, python/brdffit/mitsuba.py) holding the fit.  docs/mitsuba.md. */
#include "export.h"

#include <math.h>
#include <string.h>

int mitsuba_scene_default(mitsuba_scene *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->width = 256;
    sc->spp = 64;
    sc->nlights = brdffit_render_default_lights(sc->lights);
    return 0;
}

const char *mitsuba_fit_check(const fit_record *r, char *why, size_t len)
{
    brdffit_model m;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (brdffit_model_from_name(r->model, &m, &err) != BRDFFIT_OK) {
        snprintf(why, len, "%s", err.message);
        return why;
    }
    const brdffit_model_info *info = brdffit_model_get(m);
    if (!r->has_params || r->nparams < info->nparams) {
        snprintf(why, len, "no parameters d, s, p (%d lobe parameters)", info->nparams);
        return why;
    }
    if (brdffit_params_check(m, &r->params, &err) != BRDFFIT_OK) {
        snprintf(why, len, "%s", err.message);
        return why;
    }
    return NULL;
}

/* s as XML attribute text (quotes, ampersands and angle brackets escaped). */
static void xml_text(FILE *f, const char *s)
{
    for (; *s; s++)
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        default: fputc(*s, f);
        }
}

/* A name for an XML comment: "--" cannot be in one. */
static void xml_comment_text(FILE *f, const char *s)
{
    for (; *s; s++)
        fputc(*s == '-' && s[1] == '-' ? '_' : *s, f);
}

static void rgb(FILE *f, const char *indent, const char *name, const double v[3])
{
    fprintf(f, "%s<rgb name=\"%s\" value=\"%.9g, %.9g, %.9g\"/>\n", indent, name, v[0], v[1],
            v[2]);
}

static void write_bsdf(FILE *f, const fit_record *r)
{
    brdffit_model m;
    brdffit_model_from_name(r->model, &m, NULL);
    const brdffit_model_info *info = brdffit_model_get(m);
    fputs("        <bsdf type=\"brdffit\">\n            <string name=\"model\" value=\"", f);
    xml_text(f, info->name);
    fputs("\"/>\n", f);
    rgb(f, "            ", "d", r->params.d);
    rgb(f, "            ", "s", r->params.s);
    for (int k = 0; k < info->nparams; k++)
        fprintf(f, "            <float name=\"%s\" value=\"%.9g\"/>\n", info->params[k].name,
                r->params.p[k]);
    const double *lam = r->params.lambda_um;
    if (info->chromatic && (lam[0] != 0 || lam[1] != 0 || lam[2] != 0))
        rgb(f, "            ", "lambda_um", lam);
    fputs("        </bsdf>\n", f);
}

/* Direct lighting (the sphere is convex: nothing else reaches the camera);
 * BSDF samples only when an environment can be hit by them (a directional
 * light cannot).  The stratified sampler spreads each pixel's samples over
 * its area and over the choice of the light evenly. */
static void write_camera(FILE *f, const mitsuba_scene *sc)
{
    fprintf(f,
            "    <integrator type=\"direct\">\n"
            "        <integer name=\"emitter_samples\" value=\"1\"/>\n"
            "        <integer name=\"bsdf_samples\" value=\"%d\"/>\n"
            "        <boolean name=\"hide_emitters\" value=\"true\"/>\n"
            "    </integrator>\n"
            "    <sensor type=\"orthographic\">\n"
            "        <transform name=\"to_world\">\n"
            "            <lookat origin=\"0, 0, 10\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>\n"
            "        </transform>\n"
            "        <sampler type=\"stratified\">\n"
            "            <integer name=\"sample_count\" value=\"%d\"/>\n"
            "        </sampler>\n"
            "        <film type=\"hdrfilm\">\n"
            "            <integer name=\"width\" value=\"%d\"/>\n"
            "            <integer name=\"height\" value=\"%d\"/>\n"
            "            <string name=\"pixel_format\" value=\"rgba\"/>\n"
            "            <rfilter type=\"box\"/>\n"
            "        </film>\n"
            "    </sensor>\n",
            sc->env[0] ? 1 : 0, sc->spp, sc->width, sc->width);
}

static void write_lights(FILE *f, const mitsuba_scene *sc)
{
    for (int k = 0; k < sc->nlights; k++) {
        const double *d = sc->lights[k].dir;
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        /* Mitsuba's direction is the one the light travels: away from the light */
        fprintf(f,
                "    <emitter type=\"directional\">\n"
                "        <vector name=\"direction\" value=\"%.9g, %.9g, %.9g\"/>\n",
                -d[0] / len, -d[1] / len, -d[2] / len);
        rgb(f, "        ", "irradiance", sc->lights[k].rgb);
        fputs("    </emitter>\n", f);
    }
    if (sc->env[0]) {
        /* Mitsuba's map has -z at u = 0, brdffit's at its centre: turned half a turn about y */
        fputs("    <emitter type=\"envmap\">\n        <string name=\"filename\" value=\"", f);
        xml_text(f, sc->env);
        fputs("\"/>\n"
              "        <transform name=\"to_world\">\n"
              "            <rotate y=\"1\" angle=\"180\"/>\n"
              "        </transform>\n"
              "    </emitter>\n",
              f);
    }
}

void mitsuba_write(FILE *f, const fit_record *r, const char *name, const mitsuba_scene *sc)
{
    fputs("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!-- ", f);
    xml_comment_text(f, name);
    fprintf(f,
            ": a brdffit %s fit on brdffit's render sphere, written by brdffit %s.\n"
            "     Render it with the brdffit Python package's plugin (docs/mitsuba.md):\n"
            "     mi.set_variant(\"llvm_ad_rgb\"); brdffit.mitsuba.register();\n"
            "     mi.render(mi.load_file(\"THIS.xml\")) -->\n"
            "<scene version=\"3.0.0\">\n",
            r->model, brdffit_version());
    write_camera(f, sc);
    fputs("    <shape type=\"sphere\">\n"
          "        <point name=\"center\" value=\"0, 0, 0\"/>\n"
          "        <float name=\"radius\" value=\"1\"/>\n",
          f);
    write_bsdf(f, r);
    fputs("    </shape>\n", f);
    write_lights(f, sc);
    fputs("</scene>\n", f);
}
