/* SPDX-License-Identifier: MIT */
/* html_export.c -- a material's fits for a renderer in the report: the file
 * of each (the same file `brdffit export` writes: MATERIAL-MODEL.gltf for the
 * glTF models, MATERIAL-MODEL.mtlx for openpbr) and, on its page, a section
 * a format with the material to paste (glTF's material object, MaterialX's
 * elements) and its values in a line. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include "html_report.h"

#include "export.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What a format's section of the page says above its fits. */
static const struct {
    const char *heading, *note;
} section[EXPORT_NFORMATS] = {
    [EXPORT_GLTF] = { "For a renderer: glTF 2.0",
                      "Each material as glTF's metallic-roughness material holds it (paste it "
                      "into a .gltf's \"materials\"), and a .gltf file with it on a sphere "
                      "(docs/gltf.md). gltf-ext uses KHR_materials_ior and "
                      "KHR_materials_specular; a viewer without them shows ior 1.5, specular 1." },
    [EXPORT_MTLX] = { "For a renderer: OpenPBR Surface in MaterialX",
                      "Each material as a MaterialX 1.39 open_pbr_surface node and the "
                      "surfacematerial using it (paste them into a <materialx> document whose "
                      "colorspace is lin_rec709, linear sRGB), and a .mtlx file with them "
                      "(docs/materialx.md). Only the base and specular inputs are set; coat, "
                      "fuzz, transmission, subsurface, thin film and emission keep the "
                      "nodedef's weight 0." },
};

/* Fit k of m as a material of format fmt: 1, or 0 when it is not an ok fit
 * of a model fmt takes or its values are not the format's material's. */
static int material_of(const rp_report *rep, const rp_material *m, int k, export_format fmt,
                       export_material *x)
{
    const fit_record *f = m->fit[k];
    const brdffit_model_info *mi = brdffit_model_get(rep->models[k]);
    char why[256];
    if (!f || !fr_ok(f) || !export_takes(fmt, mi->name))
        return 0;
    if (export_material_of(fmt, f, x, why, sizeof why) != NULL)
        return 0;
    snprintf(x->name, sizeof x->name, "%s-%s", m->name, mi->name); /* the page's names */
    return 1;
}

int rp_write_export_files(const rp_report *rep, const rp_material *m, const out_dir *dir,
                          brdffit_error *err)
{
    gltf_mesh mesh;
    int made = 0, rc = 0;
    for (int fmt = 0; fmt < EXPORT_NFORMATS && rc == 0; fmt++)
        for (int k = 0; k < rep->nmodels && rc == 0; k++) {
            export_material x;
            char file[sizeof x.name + 8];
            if (!material_of(rep, m, k, (export_format)fmt, &x))
                continue;
            if (fmt == EXPORT_GLTF && !made) {
                if (gltf_mesh_make(&mesh) != 0) {
                    err->status = BRDFFIT_E_NO_MEMORY;
                    snprintf(err->message, sizeof err->message,
                             "out of memory making the glTF sphere");
                    return -1;
                }
                made = 1;
            }
            snprintf(file, sizeof file, "%s.%s", x.name, export_format_name(x.format));
            out_file o;
            if (out_open(&o, dir, file, err) != 0) {
                rc = -1;
                break;
            }
            export_write_file(o.f, &x, made ? &mesh : NULL);
            rc = out_commit(&o, err);
        }
    if (made)
        gltf_mesh_free(&mesh);
    return rc;
}

/* What to paste as text (malloc'd), or NULL. */
static char *paste_text(const export_material *x)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    export_write_paste(f, x);
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* Its values in one line, in the format's names. */
static void material_line(xml_writer *w, const export_material *x)
{
    const gltf_material *g = &x->gltf;
    const mtlx_material *o = &x->mtlx;
    if (x->format == EXPORT_MTLX) {
        xml_textf(w, "base_color %.4g %.4g %.4g (linear) \xc2\xb7 base_metalness %.4g \xc2\xb7 "
                     "specular_roughness %.4g (alpha %.4g) \xc2\xb7 specular_ior %.4g \xc2\xb7 "
                     "specular_weight %.4g \xc2\xb7 specular_color %.4g %.4g %.4g",
                  o->base_color[0], o->base_color[1], o->base_color[2], o->base_metalness,
                  o->specular_roughness, o->specular_roughness * o->specular_roughness,
                  o->specular_ior, o->specular_weight, o->specular_color[0],
                  o->specular_color[1], o->specular_color[2]);
        return;
    }
    xml_textf(w, "baseColorFactor %.4g %.4g %.4g (linear) \xc2\xb7 metallicFactor %.4g \xc2\xb7 "
                 "roughnessFactor %.4g (alpha %.4g)",
              g->base_color[0], g->base_color[1], g->base_color[2], g->metallic, g->roughness,
              g->roughness * g->roughness);
    if (g->ext)
        xml_textf(w, " \xc2\xb7 ior %.4g \xc2\xb7 specularFactor %.4g \xc2\xb7 specularColorFactor "
                     "%.4g %.4g %.4g",
                  g->ior, g->specular, g->specular_color[0], g->specular_color[1],
                  g->specular_color[2]);
}

/* The section of format fmt: nothing when m has no fit it takes. */
static void format_section(xml_writer *w, const rp_report *rep, const rp_material *m,
                           export_format fmt)
{
    int any = 0;
    for (int k = 0; k < rep->nmodels; k++) {
        export_material x;
        char href[BJ_NAME_MAX * 3 + 64], file[sizeof x.name + 8];
        if (!material_of(rep, m, k, fmt, &x))
            continue;
        if (!any++) {
            xml_element_text(w, "h2", section[fmt].heading);
            xml_open(w, "p");
            xml_attr(w, "class", "note");
            xml_text(w, section[fmt].note);
            xml_close(w);
        }
        snprintf(file, sizeof file, "%s.%s", x.name, export_format_name(fmt));
        rp_url_segment(href, sizeof href, file);
        xml_open(w, "p");
        rp_link(w, href, file);
        xml_text(w, ": ");
        material_line(w, &x);
        xml_close(w);
        char *text = paste_text(&x);
        if (text) {
            xml_open(w, "pre");
            xml_text(w, text);
            xml_close(w);
            free(text);
        }
    }
}

void rp_export_sections(xml_writer *w, const rp_report *rep, const rp_material *m)
{
    for (int fmt = 0; fmt < EXPORT_NFORMATS; fmt++)
        format_section(w, rep, m, (export_format)fmt);
}
