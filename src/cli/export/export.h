/* SPDX-License-Identifier: MIT */
/* export.h -- `brdffit export`: fitted materials as files for other programs.
 *
 *   fits_read.c   the files of fits it reads: the JSON Lines of `brdffit fit
 *                 --json` (or a batch journal), the TSV of a batch (fits.tsv)
 *   gltf_mesh.c   the sphere the material is shown on: its vertices and
 *                 triangles as glTF's little-endian buffer
 *   gltf_write.c  the glTF 2.0 file: one JSON text, the buffer embedded
 *   gltf_record.c a fit record of a glTF model as the material written
 *   mitsuba_write.c a fit as a Mitsuba 3 scene of the render sphere */
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

#endif
