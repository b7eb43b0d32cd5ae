/* SPDX-License-Identifier: MIT */
/* html_gltf.c -- a material's glTF fits in the report: the .gltf file of
 * each (the same file `brdffit export` writes) and, on its page, the
 * material to paste into a glTF file (JSON) and its values in a line. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include "html_report.h"

#include "export.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Fit k of m as a glTF material (named MATERIAL-MODEL into name): 1, or 0
 * when it is not an ok fit of a glTF model or its values are not a glTF
 * material's. */
static int material_of(const rp_report *rep, const rp_material *m, int k, gltf_material *g,
                       char *name, size_t len)
{
    const fit_record *f = m->fit[k];
    const brdffit_model_info *mi = brdffit_model_get(rep->models[k]);
    char why[256];
    if (!f || !fr_ok(f) || mi->colour_form != BRDFFIT_COLOUR_GLTF ||
        gltf_material_of(f, rep->models[k] == BRDFFIT_GLTF_EXT, g, why, sizeof why) != NULL)
        return 0;
    snprintf(name, len, "%s-%s", m->name, mi->name);
    g->name = name;
    return 1;
}

int rp_write_gltf_files(const rp_report *rep, const rp_material *m, const out_dir *dir,
                        brdffit_error *err)
{
    gltf_mesh mesh;
    int made = 0, rc = 0;
    for (int k = 0; k < rep->nmodels && rc == 0; k++) {
        gltf_material g;
        char name[BJ_NAME_MAX + 32], file[BJ_NAME_MAX + 40];
        if (!material_of(rep, m, k, &g, name, sizeof name))
            continue;
        if (!made && gltf_mesh_make(&mesh) != 0) {
            err->status = BRDFFIT_E_NO_MEMORY;
            snprintf(err->message, sizeof err->message, "out of memory making the glTF sphere");
            return -1;
        }
        made = 1;
        snprintf(file, sizeof file, "%s.gltf", name);
        out_file o;
        if (out_open(&o, dir, file, err) != 0) {
            rc = -1;
            break;
        }
        gltf_write(o.f, &g, &mesh);
        rc = out_commit(&o, err);
    }
    if (made)
        gltf_mesh_free(&mesh);
    return rc;
}

/* The material's JSON object as text (malloc'd), or NULL. */
static char *material_json(const gltf_material *g)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    gltf_write_material(f, g);
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* Its values in one line, in glTF's names. */
static void material_line(xml_writer *w, const gltf_material *g)
{
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

void rp_gltf_section(xml_writer *w, const rp_report *rep, const rp_material *m)
{
    int any = 0;
    for (int k = 0; k < rep->nmodels; k++) {
        gltf_material g;
        char name[BJ_NAME_MAX + 32], href[BJ_NAME_MAX * 3 + 64], file[BJ_NAME_MAX + 40];
        if (!material_of(rep, m, k, &g, name, sizeof name))
            continue;
        if (!any++) {
            xml_element_text(w, "h2", "For a renderer: glTF 2.0");
            xml_open(w, "p");
            xml_attr(w, "class", "note");
            xml_text(w, "Each material as glTF's metallic-roughness material holds it (paste it "
                        "into a .gltf's \"materials\"), and a .gltf file with it on a sphere "
                        "(docs/gltf.md). gltf-ext uses KHR_materials_ior and "
                        "KHR_materials_specular; a viewer without them shows ior 1.5, specular 1.");
            xml_close(w);
        }
        snprintf(file, sizeof file, "%s.gltf", name);
        rp_url_segment(href, sizeof href, file);
        xml_open(w, "p");
        rp_link(w, href, file);
        xml_text(w, ": ");
        material_line(w, &g);
        xml_close(w);
        char *json = material_json(&g);
        if (json) {
            xml_open(w, "pre");
            xml_text(w, json);
            xml_close(w);
            free(json);
        }
    }
}
