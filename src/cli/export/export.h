/* SPDX-License-Identifier: MIT */
/* export.h -- `brdffit export`: fitted materials as files for other programs.
 *
 *   fits_read.c   the files of fits it reads: the JSON Lines of `brdffit fit
 *                 --json` (or a batch journal), the TSV of a batch (fits.tsv)
 *   gltf_mesh.c   the sphere the material is shown on: its vertices and
 *                 triangles as glTF's little-endian buffer
 *   gltf_write.c  the glTF 2.0 file: one JSON text, the buffer embedded
 *   gltf_record.c a fit record of a glTF model as the material written
 *   mitsuba_write.c a fit as a Mitsuba 3 scene of the render sphere
 *   mitsuba_options.c its options (--size, --spp, --light, --env)
 *   mtlx_write.c  a fit of model openpbr as a MaterialX document
 *   format.c      the formats by name: which models each writes, its file,
 *                 what the report shows to paste (cmd_export.c, the batch) */
#ifndef BRDFFIT_EXPORT_H
#define BRDFFIT_EXPORT_H

#include "cli.h"
#include "fit_record.h"

#include <stddef.h>
#include <stdio.h>

/* ---- fits_read.c ---- */

/* Called for each record of a file of fits with the record and its line
 * (1-based); a line that is not a record is passed as r NULL with why.
 * Returns 0 to go on. */
typedef int (*fits_visit)(void *user, const fit_record *r, long line, const char *why);

/* Read path, a file of fits: JSON Lines when its first character that is
 * not white space is '{', else TSV with a header line naming its columns
 * (material, model, d_r..s_b, p0.., and status when present; '-' or empty:
 * no value).  0, or -1 with err when the file cannot be read. */
int fits_read(const char *path, fits_visit visit, void *user, brdffit_error *err);

/* ---- gltf_mesh.c ---- */

/* The sphere: radius 1 about the origin, +Y up, 64 segments around and 32
 * from pole to pole, a vertex ring a latitude (its first vertex repeated
 * at the seam, u = 1). */
enum { GLTF_SEG_LON = 64, GLTF_SEG_LAT = 32 };
#define GLTF_NVERTS ((GLTF_SEG_LON + 1) * (GLTF_SEG_LAT + 1))
#define GLTF_NINDICES (3 * GLTF_SEG_LON * (2 * GLTF_SEG_LAT - 2))

/* The buffer: POSITION (VEC3 float), NORMAL (VEC3 float), TEXCOORD_0 (VEC2
 * float), the indices (unsigned short), each a bufferView of a size that is
 * a multiple of 4. */
typedef struct gltf_mesh {
    unsigned char *bytes;   /* the buffer, little-endian                        */
    size_t nbytes;
    size_t offset[4];       /* position, normal, texcoord, index bufferViews    */
    size_t length[4];
    float min[3], max[3];   /* of the positions as stored                       */
} gltf_mesh;

/* Make the sphere.  0, or -1 when out of memory. */
int gltf_mesh_make(gltf_mesh *m);
void gltf_mesh_free(gltf_mesh *m);
/* The base64 text (RFC 4648, padded) of n bytes onto f. */
void gltf_base64(FILE *f, const unsigned char *p, size_t n);

/* ---- gltf_write.c ---- */

/* One material of glTF's metallic-roughness model (with KHR_materials_ior
 * and KHR_materials_specular when ext is 1). */
typedef struct gltf_material {
    const char *name;          /* the material's and the scene's name             */
    int ext;                   /* 1: write the two extensions (model gltf-ext)    */
    double base_color[3];      /* baseColorFactor rgb; its alpha is 1             */
    double metallic, roughness;
    double ior, specular;      /* ext only                                        */
    double specular_color[3];  /* ext only                                        */
} gltf_material;

/* NULL when the values are a glTF material's (finite, base colour, metallic,
 * roughness and specular in [0, 1], ior >= 1, specular colour >= 0), else
 * what is wrong, into why. */
const char *gltf_material_check(const gltf_material *m, char *why, size_t len);
/* The .gltf text of m on the sphere onto f. */
void gltf_write(FILE *f, const gltf_material *m, const gltf_mesh *mesh);
/* m as one glTF material object ({"name": ..., "pbrMetallicRoughness": ...,
 * "extensions": ...}, the extensions when m->ext) onto f: what a .gltf's
 * "materials" holds, and what the report shows to paste. */
void gltf_write_material(FILE *f, const gltf_material *m);

/* ---- gltf_record.c ---- */

/* The values of fit record r (model gltf: ext 0; gltf-ext: ext 1) as a glTF
 * material into m (its name left NULL): NULL, or why not (into why). */
const char *gltf_material_of(const fit_record *r, int ext, gltf_material *m, char *why,
                             size_t len);

/* ---- mitsuba_write.c ---- */

/* What a Mitsuba scene shows besides the fit: brdffit render's sphere. */
typedef struct mitsuba_scene {
    int width;                /* N x N pixels (render's --size)               */
    int spp;                  /* samples per pixel                            */
    int nlights;
    brdffit_light lights[BRDFFIT_RENDER_MAX_LIGHTS]; /* toward the light, camera frame */
    char env[4096];           /* the environment map's absolute path, or ""   */
    int lights_given;         /* --light was given (else the defaults, or none with --env) */
} mitsuba_scene;

/* The defaults: 256 pixels, 64 samples, render's default lights, no map. */
int mitsuba_scene_default(mitsuba_scene *sc);
/* The options of the scene (mitsuba_options.c): --size N, --spp N,
 * --light X,Y,Z[:R,G,B], --env FILE.exr as render takes them.  CLI_OK,
 * CLI_USAGE (printed), or 1 when argv[*i] is none of them. */
int mitsuba_option(mitsuba_scene *sc, int argc, char **argv, int *i);
/* After the options: --env without --light lights the sphere by the map alone. */
void mitsuba_options_done(mitsuba_scene *sc);
/* NULL when fit record r names a model and holds parameters it accepts,
 * else why not (into why). */
const char *mitsuba_fit_check(const fit_record *r, char *why, size_t len);
/* The scene XML of the fit in r (checked) onto f; name MATERIAL-MODEL. */
void mitsuba_write(FILE *f, const fit_record *r, const char *name, const mitsuba_scene *sc);
/* ---- mtlx_write.c ---- */

/* The fitted inputs of an open_pbr_surface node (OpenPBR Surface's names). */
typedef struct mtlx_material {
    const char *name;          /* MATERIAL-MODEL: the doc string; the elements' names */
    double base_color[3];      /* linear sRGB (lin_rec709)                            */
    double specular_color[3];
    double base_metalness, specular_roughness, specular_ior, specular_weight;
} mtlx_material;

/* NULL when the values are an OpenPBR material's (finite; colours,
 * base_metalness and specular_roughness in [0, 1], specular_ior >= 1,
 * specular_weight >= 0), else what is wrong, into why. */
const char *mtlx_material_check(const mtlx_material *m, char *why, size_t len);
/* The values of fit record r (model openpbr: d = base_color, s =
 * specular_color, p = base_metalness, specular_roughness, specular_ior,
 * specular_weight) into m (its name left NULL): NULL, or why not. */
const char *mtlx_material_of(const fit_record *r, mtlx_material *m, char *why, size_t len);
/* A MaterialX element name made of prefix and name into out: each run of
 * bytes of name not in [A-Za-z0-9_] written as one '_', and '_' first when,
 * without a prefix, name begins with a digit. */
void mtlx_element_name(char *out, size_t len, const char *name, const char *prefix);
/* The open_pbr_surface node and the surfacematerial using it, indented by
 * depth (two spaces a level): what a document's <materialx> holds, and what
 * the report shows to paste. */
void mtlx_write_elements(FILE *f, const mtlx_material *m, int depth);
/* The .mtlx document of m onto f. */
void mtlx_write(FILE *f, const mtlx_material *m);

/* ---- format.c ---- */

typedef enum export_format { EXPORT_GLTF, EXPORT_MTLX, EXPORT_NFORMATS } export_format;

/* A fit as the material of one format. */
typedef struct export_material {
    export_format format;
    char name[BJ_NAME_MAX + BJ_MODEL_NAME_MAX + 8]; /* MATERIAL-MODEL            */
    gltf_material gltf;                              /* format EXPORT_GLTF        */
    mtlx_material mtlx;                              /* format EXPORT_MTLX        */
} export_material;

/* The format named name ("gltf", "mtlx"): 0, or -1 when there is none. */
int export_format_named(const char *name, export_format *fmt);
/* Its name, and its file name's ending ("gltf", "mtlx"). */
const char *export_format_name(export_format fmt);
/* The models it writes, in words ("gltf or gltf-ext", "openpbr"), and what
 * they are ("a glTF model", "an OpenPBR model"). */
const char *export_format_models(export_format fmt);
const char *export_format_kind(export_format fmt);
/* 1 when fits of model are written in format fmt. */
int export_takes(export_format fmt, const char *model);
/* The fit r (of a model fmt takes) as m, named MATERIAL-MODEL from r's
 * material and model: NULL, or why not (into why). */
const char *export_material_of(export_format fmt, const fit_record *r, export_material *m,
                               char *why, size_t len);
/* m's file onto f (mesh: the sphere a glTF material is shown on). */
void export_write_file(FILE *f, const export_material *m, const gltf_mesh *mesh);
/* What the report shows to paste: a glTF material object, the MaterialX
 * elements. */
void export_write_paste(FILE *f, const export_material *m);

#endif
