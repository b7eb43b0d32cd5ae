/* SPDX-License-Identifier: MIT */
/* mtlx_write.c -- a fit of model openpbr as a MaterialX 1.39 document: an
 * open_pbr_surface node (nodedef ND_open_pbr_surface_surfaceshader) holding
 * the fitted base and specular inputs, and a surfacematerial using it.  The
 * document's colour space is lin_rec709, MaterialX's name for linear sRGB,
 * the space of the fit's colours.  Every other input of the node (coat,
 * fuzz, transmission, subsurface, thin film, emission, geometry) is left
 * out: it keeps the nodedef's default, a weight (or luminance) of 0.
 *
 * Names: MaterialX element names are letters, digits and '_' (':' separates
 * namespaces), so the element names are made from MATERIAL-MODEL by writing
 * each run of other bytes as one '_' (and '_' before a leading digit); the
 * name itself is kept, XML-escaped, in the material's doc attribute. */
#include "export.h"
#include "svg.h"

#include <math.h>
#include <string.h>

static int in01(double x)
{
    return isfinite(x) && x >= 0 && x <= 1;
}

const char *mtlx_material_check(const mtlx_material *m, char *why, size_t len)
{
    static const char *const ch[3] = { "r", "g", "b" };
    for (int c = 0; c < 3; c++)
        if (!in01(m->base_color[c])) {
            snprintf(why, len, "base_color %s = %.9g is not in [0, 1]", ch[c], m->base_color[c]);
            return why;
        }
    for (int c = 0; c < 3; c++)
        if (!in01(m->specular_color[c])) {
            snprintf(why, len, "specular_color %s = %.9g is not in [0, 1]", ch[c],
                     m->specular_color[c]);
            return why;
        }
    if (!in01(m->base_metalness)) {
        snprintf(why, len, "base_metalness = %.9g is not in [0, 1]", m->base_metalness);
        return why;
    }
    if (!in01(m->specular_roughness)) {
        snprintf(why, len, "specular_roughness = %.9g is not in [0, 1]", m->specular_roughness);
        return why;
    }
    if (!isfinite(m->specular_ior) || m->specular_ior < 1) {
        snprintf(why, len, "specular_ior = %.9g is not a number >= 1", m->specular_ior);
        return why;
    }
    if (!isfinite(m->specular_weight) || m->specular_weight < 0) {
        snprintf(why, len, "specular_weight = %.9g is not a number >= 0", m->specular_weight);
        return why;
    }
    return NULL;
}

const char *mtlx_material_of(const fit_record *r, mtlx_material *m, char *why, size_t len)
{
    if (!r->has_params || r->nparams < 4)
        return "no parameters d, s, p (4 numbers: base_metalness, specular_roughness, "
               "specular_ior, specular_weight)";
    memset(m, 0, sizeof *m);
    for (int c = 0; c < 3; c++) {
        m->base_color[c] = r->params.d[c];
        m->specular_color[c] = r->params.s[c];
    }
    m->base_metalness = r->params.p[0];
    m->specular_roughness = r->params.p[1];
    m->specular_ior = r->params.p[2];
    m->specular_weight = r->params.p[3];
    return mtlx_material_check(m, why, len);
}

void mtlx_element_name(char *out, size_t len, const char *name, const char *prefix)
{
    size_t n = 0;
    if (len == 0)
        return;
    for (const char *p = prefix; *p && n + 1 < len; p++)
        out[n++] = *p;
    if (n == 0 && name[0] >= '0' && name[0] <= '9' && n + 1 < len)
        out[n++] = '_';
    int run = 0; /* in a run of bytes written as one '_' */
    for (const unsigned char *p = (const unsigned char *)name; *p && n + 1 < len; p++) {
        int ok = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
                 (*p >= '0' && *p <= '9') || *p == '_';
        if (ok)
            out[n++] = (char)*p;
        else if (!run)
            out[n++] = '_';
        run = !ok;
    }
    out[n] = '\0';
}

/* s as an attribute value's text: xml_escape's, with tab, line feed and
 * carriage return as character references (a parser reads them back as
 * themselves, where written as such it reads spaces). */
static void attr_text(FILE *f, const char *s)
{
    char chunk[256];
    while (*s) {
        size_t n = strcspn(s, "\t\n\r");
        while (n > 0) {
            size_t k = n < sizeof chunk - 1 ? n : sizeof chunk - 1;
            while (k > 1 && k < n && ((unsigned char)s[k] & 0xC0) == 0x80)
                k--; /* never split a UTF-8 sequence */
            memcpy(chunk, s, k);
            chunk[k] = '\0';
            xml_escape(f, chunk);
            s += k;
            n -= k;
        }
        if (*s)
            fprintf(f, "&#%d;", *s++);
    }
}

static void indent(FILE *f, int depth)
{
    for (int i = 0; i < depth; i++)
        fputs("  ", f);
}

static void input_float(FILE *f, int depth, const char *name, double x)
{
    indent(f, depth);
    fprintf(f, "<input name=\"%s\" type=\"float\" value=\"%.9g\" />\n", name, x == 0 ? 0.0 : x);
}

static void input_color(FILE *f, int depth, const char *name, const double *c)
{
    indent(f, depth);
    fprintf(f, "<input name=\"%s\" type=\"color3\" value=\"%.9g, %.9g, %.9g\" />\n", name,
            c[0] == 0 ? 0.0 : c[0], c[1] == 0 ? 0.0 : c[1], c[2] == 0 ? 0.0 : c[2]);
}

void mtlx_write_elements(FILE *f, const mtlx_material *m, int depth)
{
    char shader[2 * BJ_NAME_MAX], material[2 * BJ_NAME_MAX];
    mtlx_element_name(shader, sizeof shader, m->name, "SR_");
    mtlx_element_name(material, sizeof material, m->name, "");
    indent(f, depth);
    fprintf(f, "<open_pbr_surface name=\"%s\" type=\"surfaceshader\" "
               "nodedef=\"ND_open_pbr_surface_surfaceshader\">\n", shader);
    input_float(f, depth + 1, "base_weight", 1);
    input_color(f, depth + 1, "base_color", m->base_color);
    input_float(f, depth + 1, "base_metalness", m->base_metalness);
    input_float(f, depth + 1, "base_diffuse_roughness", 0);
    input_float(f, depth + 1, "specular_weight", m->specular_weight);
    input_color(f, depth + 1, "specular_color", m->specular_color);
    input_float(f, depth + 1, "specular_roughness", m->specular_roughness);
    input_float(f, depth + 1, "specular_ior", m->specular_ior);
    indent(f, depth);
    fputs("</open_pbr_surface>\n", f);
    indent(f, depth);
    fprintf(f, "<surfacematerial name=\"%s\" type=\"material\" nodedef=\"ND_surfacematerial\" "
               "doc=\"", material);
    attr_text(f, m->name);
    fprintf(f, "\">\n");
    indent(f, depth + 1);
    fprintf(f, "<input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"%s\" />\n", shader);
    indent(f, depth);
    fputs("</surfacematerial>\n", f);
}

void mtlx_write(FILE *f, const mtlx_material *m)
{
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", f);
    fprintf(f, "<!-- brdffit %s: OpenPBR Surface's base and specular layers fitted to a measured "
               "material (model openpbr), colours in linear sRGB (lin_rec709). Every input not "
               "written keeps the nodedef's default: the coat, fuzz, transmission, subsurface "
               "and thin-film weights and the emission luminance are 0. -->\n",
            brdffit_version());
    fputs("<materialx version=\"1.39\" colorspace=\"lin_rec709\">\n", f);
    mtlx_write_elements(f, m, 1);
    fputs("</materialx>\n", f);
}
