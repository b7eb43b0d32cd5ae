/* SPDX-License-Identifier: MIT */
/* cmd_export.c -- `brdffit export FITS... --out DIR [--format gltf|mitsuba]`:
 * each fit of model gltf or gltf-ext in the files of fits (the JSON Lines of
 * `fit --json`, a batch's fits.tsv) as DIR/MATERIAL-MODEL.gltf, the material
 * on a sphere (export/gltf_write.c); with --format mitsuba each fit of any
 * model as DIR/MATERIAL-MODEL.xml, a Mitsuba 3 scene of the render sphere
 * (export/mitsuba_write.c).  Fits of other models and fits that failed are
 * skipped with a line on stderr; a record whose values are not a material's
 * is refused naming its file and line. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"
#include "export.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define EXPORT_FORMATS "gltf, mitsuba"
#define MAX_OTHER_MODELS 16

const cli_help_block *cli_export_help(void)
{
    static const cli_help_item items[] = {
        { "FITS...", "files of fits: the JSON Lines of `brdffit fit --json`,\n"
                     "or a batch's fits.tsv; each fit of model gltf or gltf-ext\n"
                     "that succeeded (status ok or limit) is written, the\n"
                     "others skipped" },
        { "--out DIR", "where the files go (made when missing):\n"
                       "DIR/MATERIAL-MODEL.gltf (.xml for mitsuba)" },
        { "--format gltf", "the file format (default gltf): glTF 2.0, one .gltf a\n"
                           "fit, the material on a sphere, the buffer embedded;\n"
                           "a gltf-ext fit adds KHR_materials_ior and\n"
                           "KHR_materials_specular (a viewer without them shows\n"
                           "the core material)" },
        { "--format mitsuba", "a Mitsuba 3 scene XML a fit, of any model: render's\n"
                              "sphere, camera and lights with a BSDF of type brdffit\n"
                              "(the Python package's plugin, brdffit.mitsuba)" },
        { "--size N, --spp N", "mitsuba: N x N pixels (default 256), samples per\n"
                               "pixel, a square (default 64)" },
        { "--light X,Y,Z[:R,G,B]", "mitsuba: a directional light as render takes it\n"
                                   "(repeatable; default render's key and rim lights)" },
        { "--env FILE.exr", "mitsuba: render's latitude-longitude environment (its\n"
                            "absolute path in the scene); without --light the only light" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK("Arguments of export", NULL, items);
    return &block;
}

typedef struct export_run {
    const char *out;
    const char *path;              /* the file of fits being read             */
    gltf_mesh mesh;
    int mitsuba;                   /* --format mitsuba                        */
    mitsuba_scene scene;
    int made_out;                  /* DIR is open (dir)                       */
    out_dir dir;                   /* --out, opened once (outdir.h)            */
    int written, refused;
    int fatal;                     /* DIR cannot be made: nothing more is read */
    char other[MAX_OTHER_MODELS][BJ_MODEL_NAME_MAX]; /* models skipped        */
    int nother[MAX_OTHER_MODELS], nothers;
} export_run;

/* A fit of a model that is not a glTF one: counted, named at the end. */
static void note_other_model(export_run *X, const char *model)
{
    for (int k = 0; k < X->nothers; k++)
        if (strcmp(X->other[k], model) == 0) {
            X->nother[k]++;
            return;
        }
    if (X->nothers < MAX_OTHER_MODELS) {
        snprintf(X->other[X->nothers], sizeof X->other[0], "%s", model);
        X->nother[X->nothers++] = 1;
    }
}

/* 1 when name can be one component of a path. */
static int name_ok(const char *name)
{
    return name[0] && !strchr(name, '/') && strcmp(name, ".") != 0 && strcmp(name, "..") != 0;
}


static int write_file(export_run *X, const char *file, const gltf_material *m,
                      const fit_record *r)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    char path[BJ_PATH_MAX];
    out_file o;
    if (!X->made_out && od_open(&X->dir, X->out, 1, &err) != 0) {
        X->fatal = 1; /* no file can be written: stop */
        goto fail;
    }
    X->made_out = 1;
    if (out_join(path, sizeof path, X->out, file) != 0) {
        cli_error("%s/%s: path too long", X->out, file);
        return -1;
    }
    if (out_open(&o, &X->dir, file, &err) != 0)
        goto fail;
    if (X->mitsuba)
        mitsuba_write(o.f, r, m->name, &X->scene);
    else
        gltf_write(o.f, m, &X->mesh);
    if (out_commit(&o, &err) != 0)
        goto fail;
    plain_string(stdout, path);
    putchar('\n');
    return 0;
fail:
    cli_error("%s", err.message);
    return -1;
}

/* One record of a file of fits (fits_visit). */
static int visit(void *user, const fit_record *r, long line, const char *why)
{
    export_run *X = user;
    if (!r) {
        cli_error("%s: line %ld: %s", X->path, line, why);
        X->refused++;
        return 0;
    }
    if (r->kind != FR_FIT && r->kind != FR_FAILURE)
        return 0; /* a journal's published Errors and renders */
    int ext = strcmp(r->model, "gltf-ext") == 0;
    if (r->kind == FR_FIT && !X->mitsuba && !ext && strcmp(r->model, "gltf") != 0) {
        note_other_model(X, r->model);
        return 0;
    }
    if (r->kind == FR_FAILURE || !fr_ok(r)) {
        cli_error("%s: line %ld: %s%s%s: not fitted (%s); skipped", X->path, line, r->material,
                  r->model[0] ? ", " : "", r->model, r->message[0] ? r->message : fr_status_text(r));
        return 0;
    }
    char name[BJ_NAME_MAX + BJ_MODEL_NAME_MAX + 8], reason[256];
    gltf_material m;
    if (!name_ok(r->material)) {
        cli_error("%s: line %ld: material '%s' (%s): its name is not a file name (empty, '.', "
                  "'..' or with '/'); not written",
                  X->path, line, r->material, r->model);
        X->refused++;
        return 0;
    }
    memset(&m, 0, sizeof m);
    const char *bad = X->mitsuba ? mitsuba_fit_check(r, reason, sizeof reason)
                                 : gltf_material_of(r, ext, &m, reason, sizeof reason);
    if (bad) {
        cli_error("%s: line %ld: %s, %s: %s; not written", X->path, line, r->material, r->model,
                  bad);
        X->refused++;
        return 0;
    }
    snprintf(name, sizeof name, "%s-%s", r->material, r->model);
    m.name = name;
    char file[sizeof name + 8];
    snprintf(file, sizeof file, "%s.%s", name, X->mitsuba ? "xml" : "gltf");
    if (write_file(X, file, &m, r) != 0)
        X->refused++;
    else
        X->written++;
    return X->fatal;
}

/* The options: CLI_OK with the files of fits in files[0..*nfiles). */
static int parse(int argc, char **argv, export_run *X, char **files, int *nfiles)
{
    const char *format = "gltf";
    int scene_opts = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (cli_is_help(a))
            return CLI_HELP;
        int r = mitsuba_option(&X->scene, argc, argv, &i);
        if (r != 1) {
            if (r != CLI_OK)
                return r;
            scene_opts = 1;
            continue;
        }
        if (strcmp(a, "--out") == 0 && i + 1 < argc)
            X->out = argv[++i];
        else if (strncmp(a, "--out=", 6) == 0)
            X->out = a + 6;
        else if (strcmp(a, "--format") == 0 && i + 1 < argc)
            format = argv[++i];
        else if (strncmp(a, "--format=", 9) == 0)
            format = a + 9;
        else if (a[0] == '-' && a[1])
            return cli_usage_error("export: unknown option '%s'", a);
        else
            files[(*nfiles)++] = argv[i];
    }
    X->mitsuba = strcmp(format, "mitsuba") == 0;
    if (strcmp(format, "gltf") != 0 && !X->mitsuba)
        return cli_usage_error("export: unknown format '%s' (formats: " EXPORT_FORMATS ")", format);
    if (scene_opts && !X->mitsuba)
        return cli_usage_error("export: --size, --spp, --light and --env are for --format mitsuba");
    mitsuba_options_done(&X->scene);
    if (!X->out || !X->out[0] || *nfiles == 0)
        return cli_usage_error("export needs files of fits and --out DIR");
    return CLI_OK;
}

/* The models skipped, one line each. */
static void report_others(const export_run *X)
{
    for (int k = 0; k < X->nothers; k++)
        cli_error("%s: not a glTF model; fit --model gltf or gltf-ext (%d fit%s skipped)",
                  X->other[k], X->nother[k], X->nother[k] == 1 ? "" : "s");
}

int cmd_export(int argc, char **argv)
{
    export_run X;
    memset(&X, 0, sizeof X);
    mitsuba_scene_default(&X.scene);
    int nfiles = 0;
    char **files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *files);
    if (!files)
        return CLI_FAILED;
    int rc = parse(argc, argv, &X, files, &nfiles);
    if (rc == CLI_OK && !X.mitsuba && gltf_mesh_make(&X.mesh) != 0) {
        cli_error("out of memory");
        rc = CLI_FAILED;
    }
    for (int i = 0; rc == CLI_OK && !X.fatal && i < nfiles; i++) {
        brdffit_error err;
        memset(&err, 0, sizeof err);
        X.path = files[i];
        if (fits_read(files[i], visit, &X, &err) != 0) {
            cli_error("%s", err.message);
            X.refused++;
        }
    }
    if (rc == CLI_OK) {
        report_others(&X);
        if (X.written == 0)
            cli_error(X.refused   ? "nothing written"
                      : X.mitsuba ? "nothing written: no fit to export"
                                  : "nothing written: no fit of model gltf or gltf-ext to export");
        rc = X.written == 0 || X.refused ? CLI_FAILED : CLI_OK;
    }
    gltf_mesh_free(&X.mesh);
    if (X.made_out)
        od_close(&X.dir);
    free(files);
    return rc;
}
