/* SPDX-License-Identifier: MIT */
/* gltf_write.c -- a fitted material as a glTF 2.0 file: one JSON text with
 * its buffer embedded as a data URI, one scene, one node, one mesh (the
 * sphere of gltf_mesh.c), one material.  The material of model gltf-ext
 * also has KHR_materials_ior and KHR_materials_specular, named in
 * extensionsUsed but never in extensionsRequired: a viewer without them
 * still opens the file and shows the core material. */
#include "export.h"

#include <math.h>

/* glTF's enumerations (the glTF 2.0 specification, 5.1.x). */
enum {
    GL_ARRAY_BUFFER = 34962,
    GL_ELEMENT_ARRAY_BUFFER = 34963,
    GL_FLOAT = 5126,
    GL_UNSIGNED_SHORT = 5123,
    GL_TRIANGLES = 4
};

static int in01(double x)
{
    return isfinite(x) && x >= 0 && x <= 1;
}

const char *gltf_material_check(const gltf_material *m, char *why, size_t len)
{
    static const char *const ch[3] = { "r", "g", "b" };
    for (int c = 0; c < 3; c++)
        if (!in01(m->base_color[c])) {
            snprintf(why, len, "base colour %s = %.9g is not in [0, 1]", ch[c], m->base_color[c]);
            return why;
        }
    if (!in01(m->metallic)) {
        snprintf(why, len, "metallic = %.9g is not in [0, 1]", m->metallic);
        return why;
    }
    if (!in01(m->roughness)) {
        snprintf(why, len, "roughness = %.9g is not in [0, 1]", m->roughness);
        return why;
    }
    if (!m->ext)
        return NULL;
    if (!isfinite(m->ior) || m->ior < 1) {
        snprintf(why, len, "ior = %.9g is not a number >= 1", m->ior);
        return why;
    }
    if (!in01(m->specular)) {
        snprintf(why, len, "specular = %.9g is not in [0, 1]", m->specular);
        return why;
    }
    for (int c = 0; c < 3; c++)
        if (!isfinite(m->specular_color[c]) || m->specular_color[c] < 0) {
            snprintf(why, len, "specular colour %s = %.9g is not a number >= 0", ch[c],
                     m->specular_color[c]);
            return why;
        }
    return NULL;
}

static void num(FILE *f, double x)
{
    fprintf(f, "%.9g", x);
}

static void vec(FILE *f, const double *x, int n)
{
    putc('[', f);
    for (int i = 0; i < n; i++) {
        if (i)
            putc(',', f);
        num(f, x[i]);
    }
    putc(']', f);
}

void gltf_write_material(FILE *f, const gltf_material *m)
{
    double base[4] = { m->base_color[0], m->base_color[1], m->base_color[2], 1 };
    fputs("{\"name\":", f);
    json_string(f, m->name);
    fputs(",\"pbrMetallicRoughness\":{\"baseColorFactor\":", f);
    vec(f, base, 4);
    fputs(",\"metallicFactor\":", f);
    num(f, m->metallic);
    fputs(",\"roughnessFactor\":", f);
    num(f, m->roughness);
    putc('}', f);
    if (m->ext) {
        fputs(",\"extensions\":{\"KHR_materials_ior\":{\"ior\":", f);
        num(f, m->ior);
        fputs("},\"KHR_materials_specular\":{\"specularFactor\":", f);
        num(f, m->specular);
        fputs(",\"specularColorFactor\":", f);
        vec(f, m->specular_color, 3);
        fputs("}}", f);
    }
    putc('}', f);
}

static void write_material(FILE *f, const gltf_material *m)
{
    fputs("\"materials\":[", f);
    gltf_write_material(f, m);
    fputs("],\n", f);
}

static void write_accessors(FILE *f, const gltf_mesh *mesh)
{
    double lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
        lo[c] = mesh->min[c];
        hi[c] = mesh->max[c];
    }
    fprintf(f, "\"accessors\":[{\"bufferView\":0,\"componentType\":%d,\"count\":%d,"
               "\"type\":\"VEC3\",\"min\":",
            GL_FLOAT, GLTF_NVERTS);
    vec(f, lo, 3);
    fputs(",\"max\":", f);
    vec(f, hi, 3);
    fprintf(f, "},\n {\"bufferView\":1,\"componentType\":%d,\"count\":%d,\"type\":\"VEC3\"},\n",
            GL_FLOAT, GLTF_NVERTS);
    fprintf(f, " {\"bufferView\":2,\"componentType\":%d,\"count\":%d,\"type\":\"VEC2\"},\n",
            GL_FLOAT, GLTF_NVERTS);
    fprintf(f, " {\"bufferView\":3,\"componentType\":%d,\"count\":%d,\"type\":\"SCALAR\"}],\n",
            GL_UNSIGNED_SHORT, GLTF_NINDICES);
}

static void write_buffer(FILE *f, const gltf_mesh *mesh)
{
    fputs("\"bufferViews\":[", f);
    for (int k = 0; k < 4; k++)
        fprintf(f, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":%d}",
                k ? ",\n " : "", mesh->offset[k], mesh->length[k],
                k == 3 ? GL_ELEMENT_ARRAY_BUFFER : GL_ARRAY_BUFFER);
    fprintf(f, "],\n\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,",
            mesh->nbytes);
    gltf_base64(f, mesh->bytes, mesh->nbytes);
    fputs("\"}]\n", f);
}

void gltf_write(FILE *f, const gltf_material *m, const gltf_mesh *mesh)
{
    fputs("{\"asset\":{\"version\":\"2.0\",\"generator\":", f);
    char generator[64];
    snprintf(generator, sizeof generator, "brdffit %s", brdffit_version());
    json_string(f, generator);
    fputs("},\n", f);
    if (m->ext)
        fputs("\"extensionsUsed\":[\"KHR_materials_ior\",\"KHR_materials_specular\"],\n", f);
    fputs("\"scene\":0,\n\"scenes\":[{\"name\":", f);
    json_string(f, m->name);
    fputs(",\"nodes\":[0]}],\n\"nodes\":[{\"name\":", f);
    json_string(f, m->name);
    fputs(",\"mesh\":0}],\n\"meshes\":[{\"name\":", f);
    json_string(f, m->name);
    fprintf(f, ",\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
               "\"indices\":3,\"material\":0,\"mode\":%d}]}],\n",
            GL_TRIANGLES);
    write_material(f, m);
    write_accessors(f, mesh);
    write_buffer(f, mesh);
    fputs("}\n", f);
}
