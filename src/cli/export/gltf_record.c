/* SPDX-License-Identifier: MIT */
/* gltf_record.c -- a fit record of a glTF model (gltf, gltf-ext) as the
 * material glTF writes: its values checked (export.h). */
#include "export.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* NULL when every value of the record is a finite number, else which is not.
 * The core material does not write ior, specular and the specular colour,
 * but a record with a value that is not a number is refused whatever it is. */
static const char *all_finite(const fit_record *r, char *why, size_t len)
{
    static const char *const names[10] = { "base colour r", "base colour g", "base colour b",
                                           "specular colour r", "specular colour g",
                                           "specular colour b", "metallic", "roughness", "ior",
                                           "specular" };
    const double v[10] = { r->params.d[0], r->params.d[1], r->params.d[2], r->params.s[0],
                           r->params.s[1], r->params.s[2], r->params.p[0], r->params.p[1],
                           r->params.p[2], r->params.p[3] };
    for (int k = 0; k < 10; k++)
        if (!isfinite(v[k])) {
            snprintf(why, len, "%s = %g is not a finite number", names[k], v[k]);
            return why;
        }
    return NULL;
}

const char *gltf_material_of(const fit_record *r, int ext, gltf_material *m, char *why,
                               size_t len)
{
    if (!r->has_params || r->nparams < 4)
        return "no parameters d, s, p (4 numbers: metallic, roughness, ior, specular)";
    if (all_finite(r, why, len))
        return why;
    memset(m, 0, sizeof *m);
    m->ext = ext;
    for (int c = 0; c < 3; c++) {
        m->base_color[c] = r->params.d[c];
        m->specular_color[c] = r->params.s[c];
    }
    m->metallic = r->params.p[0];
    m->roughness = r->params.p[1];
    m->ior = r->params.p[2];
    m->specular = r->params.p[3];
    return gltf_material_check(m, why, len);
}
