/* SPDX-License-Identifier: MIT */
/* format.c -- the formats `brdffit export` and the batch write, by name:
 * which models each takes, the material it makes of a fit, its file and what
 * the report shows to paste (export.h). */
#include "export.h"

#include <string.h>

typedef struct format_info {
    const char *name, *models, *kind;
    const char *model[2];      /* the models it takes (NULL: no more)        */
} format_info;

static const format_info formats[EXPORT_NFORMATS] = {
    [EXPORT_GLTF] = { "gltf", "gltf or gltf-ext", "a glTF model", { "gltf", "gltf-ext" } },
    [EXPORT_MTLX] = { "mtlx", "openpbr", "an OpenPBR model", { "openpbr", NULL } },
};

int export_format_named(const char *name, export_format *fmt)
{
    for (int k = 0; k < EXPORT_NFORMATS; k++)
        if (strcmp(name, formats[k].name) == 0) {
            *fmt = (export_format)k;
            return 0;
        }
    return -1;
}

const char *export_format_name(export_format fmt)
{
    return formats[fmt].name;
}

const char *export_format_models(export_format fmt)
{
    return formats[fmt].models;
}

const char *export_format_kind(export_format fmt)
{
    return formats[fmt].kind;
}

int export_takes(export_format fmt, const char *model)
{
    for (int k = 0; k < 2; k++)
        if (formats[fmt].model[k] && strcmp(model, formats[fmt].model[k]) == 0)
            return 1;
    return 0;
}

const char *export_material_of(export_format fmt, const fit_record *r, export_material *m,
                               char *why, size_t len)
{
    memset(m, 0, sizeof *m);
    m->format = fmt;
    snprintf(m->name, sizeof m->name, "%s-%s", r->material, r->model);
    const char *bad;
    if (fmt == EXPORT_GLTF) {
        bad = gltf_material_of(r, strcmp(r->model, "gltf-ext") == 0, &m->gltf, why, len);
        m->gltf.name = m->name;
    } else {
        bad = mtlx_material_of(r, &m->mtlx, why, len);
        m->mtlx.name = m->name;
    }
    return bad;
}

void export_write_file(FILE *f, const export_material *m, const gltf_mesh *mesh)
{
    if (m->format == EXPORT_GLTF)
        gltf_write(f, &m->gltf, mesh);
    else
        mtlx_write(f, &m->mtlx);
}

void export_write_paste(FILE *f, const export_material *m)
{
    if (m->format == EXPORT_GLTF)
        gltf_write_material(f, &m->gltf);
    else
        mtlx_write_elements(f, &m->mtlx, 0);
}
