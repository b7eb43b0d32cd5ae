/* SPDX-License-Identifier: MIT */
/* test_render_files.c -- a material's render and plot files (src/cli/images/render_files.c):
 * EXR read back through OpenEXR, PNG decoded through libpng and compared with
 * the sRGB curve written here, SVG parsed as XML (expat); bad directories and
 * bad EXR files. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "image_io.h"
#include "render_files.h"

#include <check.h>
#include <dirent.h>
#include <math.h>
#include <openexr.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static brdffit_params ct_params(void)
{
    brdffit_params p;
    memset(&p, 0, sizeof p);
    const double d[3] = { 0.05, 0.08, 0.12 }, s[3] = { 0.3, 0.25, 0.2 };
    memcpy(p.d, d, sizeof d);
    memcpy(p.s, s, sizeof s);
    p.p[0] = 0.6, p.p[1] = 0.3;
    return p;
}

static brdffit_table *ct_table(void)
{
    brdffit_table *t = NULL;
    brdffit_params p = ct_params();
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p,
                                              BRDFFIT_SCALE_STANDARD, NULL), BRDFFIT_OK);
    return t;
}

/* A fresh empty directory path into buf. */
static const char *tmpdir(char *buf, size_t len)
{
    const char *dir = getenv("TMPDIR");
    snprintf(buf, len, "%s/brdffit-test-XXXXXX", dir && *dir ? dir : "/tmp");
    ck_assert_ptr_nonnull(mkdtemp(buf));
    return buf;
}

static void rm_tree(const char *dir)
{
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}

/* The sRGB encoding, written from IEC 61966-2-1 for the test. */
static int srgb8(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    double e = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
    return (int)floor(e * 255 + 0.5);
}

/* A PNG through libpng's simplified reader: RGB bytes (malloc'd), size. */
static unsigned char *read_png(const char *path, int *w, int *h)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    ck_assert_msg(png_image_begin_read_from_file(&im, path), "%s: %s", path, im.message);
    im.format = PNG_FORMAT_RGB;
    unsigned char *buf = malloc(PNG_IMAGE_SIZE(im));
    ck_assert_ptr_nonnull(buf);
    ck_assert_msg(png_image_finish_read(&im, NULL, buf, 0, NULL), "%s: %s", path, im.message);
    *w = (int)im.width, *h = (int)im.height;
    return buf;
}

static const rf_file *find_file(const rf_result *r, const char *name)
{
    for (int i = 0; i < r->nfiles; i++)
        if (strcmp(r->files[i].file, name) == 0)
            return &r->files[i];
    return NULL;
}

/* The files rf_write_material lists: each written, not empty and listed,
 * the captions those of the fits. */
static void check_listed(const char *dir, const rf_result *r)
{
    char path[1024];
    const char *names[] = { "reference.exr", "reference.png", "cook-torrance.exr",
                            "cook-torrance.png", "cook-torrance-diff.png", "ward.exr", "ward.png",
                            "ward-diff.png", "cook-torrance-flip.png", "ward-flip.png",
                            "diff-scale.svg", "flip-scale.svg", "renders.json",
                            "plot-measured.svg", "plot-cook-torrance.svg", "plot-ward.svg" };
    ck_assert_int_eq(r->nfiles, 16);
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        ck_assert_msg(stat(path, &st) == 0 && st.st_size > 0, "%s missing", path);
        ck_assert_msg(find_file(r, names[i]) != NULL, "%s not listed", names[i]);
    }
    ck_assert_str_eq(find_file(r, "cook-torrance.png")->caption, "Cook-Torrance: 0.0123");
    ck_assert_str_eq(find_file(r, "ward.png")->caption, "Ward");
    ck_assert_int_eq(find_file(r, "ward.png")->fit, 1);
    ck_assert_msg(r->image_error[0] < 0.01 && r->image_error[1] > 0.05, "FLIP %g %g",
                  r->image_error[0], r->image_error[1]);
    ck_assert(r->relative_rms[0] < 0.01 && r->relative_rms[1] > 0.05);
    const char *cap = find_file(r, "ward-diff.png")->caption, *want = "Ward: \xce\x94L*, \xea\x9f\xbbLIP 0.";
    ck_assert_msg(strncmp(cap, want, strlen(want)) == 0, "%s", cap);
}

/* reference.exr: the pixels the library renders (want, 64 x 64 RGBA), A the coverage. */
static void check_reference_exr(const char *dir, const float *want)
{
    char path[1024];
    brdffit_error err;
    float *rgb = NULL, *a = NULL;
    int w = 0, h = 0;
    snprintf(path, sizeof path, "%s/reference.exr", dir);
    ck_assert_msg(exr_read_rgb(path, &rgb, &a, &w, &h, &err) == 0, "%s", err.message);
    ck_assert_int_eq(w, 64);
    ck_assert_int_eq(h, 64);
    for (int i = 0; i < 64 * 64; i++) {
        for (int c = 0; c < 3; c++)
            ck_assert(rgb[3 * i + c] == want[4 * i + c]);
        ck_assert(a[i] == want[4 * i + 3]);
    }
    free(rgb);
    free(a);
}

/* The value a masked pixel (x, y) of want takes: the mean of the measured
 * pixels (A = 1) among its 8 neighbours, else within 2 pixels. */
static double filled_value(const float *want, int x, int y, int c)
{
    for (int r = 1; r <= 2; r++) {
        double s = 0;
        int k = 0;
        for (int yy = y - r; yy <= y + r; yy++)
            for (int xx = x - r; xx <= x + r; xx++)
                if (yy >= 0 && yy < 64 && xx >= 0 && xx < 64 && want[4 * (yy * 64 + xx) + 3] == 1.0f)
                    s += want[4 * (yy * 64 + xx) + c], k++;
        if (k > 0)
            return (double)(float)(s / k);
    }
    return -1;
}

/* reference.png: 64 x 64, sRGB of exposure x radiance (the exposure from the
 * reference), masked pixels filled from their measured neighbours; the
 * difference image of a poor fit (ward) further from white than that of the
 * exact model (cook-torrance), pixels off the sphere black. */
static void check_pngs(const char *dir, const float *want, double exposure)
{
    char path[1024];
    int w = 0, h = 0;
    snprintf(path, sizeof path, "%s/reference.png", dir);
    unsigned char *png = read_png(path, &w, &h);
    ck_assert_int_eq(w, 64);
    ck_assert_int_eq(h, 64);
    int bright = 0, masked = 0;
    for (int i = 0; i < 64 * 64; i++)
        for (int c = 0; c < 3; c++) {
            int m = want[4 * i + 3] == BRDFFIT_COVERAGE_MASKED;
            double lin = m ? filled_value(want, i % 64, i / 64, c) : want[4 * i + c];
            masked += m;
            int v = want[4 * i + 3] > 0 ? srgb8(exposure * lin) : 0;
            ck_assert_msg(abs(png[3 * i + c] - v) <= 0, "pixel %d ch %d: %d want %d", i, c,
                          png[3 * i + c], v);
            bright += png[3 * i + c] == 255;
        }
    ck_assert(bright > 0 && bright < 64 * 64 / 10); /* ~1% of the sphere may clip */
    ck_assert(masked > 0);
    free(png);
    long sum[2] = { 0, 0 };
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/%s-diff.png", dir, k ? "ward" : "cook-torrance");
        png = read_png(path, &w, &h);
        for (int i = 0; i < 64 * 64; i++) {
            if (want[4 * i + 3] == 0)
                ck_assert(png[3 * i] == 0 && png[3 * i + 1] == 0 && png[3 * i + 2] == 0);
            else /* filled, never grey */
                for (int c = 0; c < 3; c++) {
                    ck_assert(!(png[3 * i] == 128 && png[3 * i + 1] == 128 && png[3 * i + 2] == 128));
                    sum[k] += abs(png[3 * i + c] - 247); /* the diverging map's white */
                }
        }
        free(png);
    }
    ck_assert(sum[1] > 5 * sum[0]);
}

/* The plots: well-formed XML; the title with model, Error and the escaped
 * material name; dashed model curves and solid measured ones, one colour
 * per theta_i; the measured plot has no dashed curve. */
static void check_svgs(const char *dir)
{
    char path[1024];
    tu_xml_doc doc;
    snprintf(path, sizeof path, "%s/plot-cook-torrance.svg", dir);
    ck_assert_msg(tu_xml_load(path, &doc) == 0, "%s", doc.error);
    ck_assert_str_eq(doc.e[0].name, "svg");
    int title = 0, dashed = 0, solid = 0, legend = 0;
    const char *colours[4] = { NULL };
    for (int i = 0; i < doc.n; i++) {
        const tu_xml_elem *e = &doc.e[i];
        if (strcmp(e->name, "title") == 0) {
            ck_assert_ptr_nonnull(strstr(e->text, "Cook-Torrance: Error 0.0123"));
            ck_assert_ptr_nonnull(strstr(e->text, "ct-test <&>")); /* escaped, read back */
            title++;
        }
        if (strcmp(e->name, "polyline") == 0) {
            const char *d = tu_xml_attr(e, "stroke-dasharray");
            *(d ? &dashed : &solid) += 1;
            if (!d && solid <= 4)
                colours[solid - 1] = tu_xml_attr(e, "stroke");
        }
        if (strcmp(e->name, "text") == 0 && strstr(e->text, "\xce\xb8i = "))
            legend++;
    }
    ck_assert_int_eq(title, 1);
    ck_assert_int_eq(legend, 4);
    ck_assert(dashed >= 4 && solid >= 4);
    ck_assert_str_ne(colours[0], colours[1]);
    tu_xml_free(&doc);
    snprintf(path, sizeof path, "%s/plot-measured.svg", dir);
    ck_assert_msg(tu_xml_load(path, &doc) == 0, "%s", doc.error);
    for (int i = 0; i < doc.n; i++)
        if (strcmp(doc.e[i].name, "polyline") == 0)
            ck_assert_ptr_null(tu_xml_attr(&doc.e[i], "stroke-dasharray"));
    tu_xml_free(&doc);
}

START_TEST(material_files_read_back)
{
    char dir[512];
    tmpdir(dir, sizeof dir);
    brdffit_table *t = ct_table();
    rf_fit fits[2];
    memset(fits, 0, sizeof fits);
    fits[0].model = BRDFFIT_COOK_TORRANCE;
    fits[0].params = ct_params();
    fits[0].error = 0.0123;
    fits[1].model = BRDFFIT_WARD;
    fits[1].params = ct_params();
    fits[1].params.p[0] = 0.2;
    fits[1].error = NAN;
    rf_settings s;
    rf_settings_default(&s, BRDFFIT_SCALE_STANDARD);
    s.render_opt.width = 64;
    rf_result r;
    brdffit_error err;
    ck_assert_msg(rf_write_material(dir, "ct-test <&>", t, fits, 2, &s, &r, &err) == 0, "%s",
                  err.message);
    check_listed(dir, &r);
    float *want = malloc(sizeof(float) * 4 * 64 * 64);
    ck_assert_int_eq(brdffit_render_table(t, &s.render_opt, want, 0, NULL), BRDFFIT_OK);
    check_reference_exr(dir, want);
    check_pngs(dir, want, r.exposure);
    check_svgs(dir);
    free(want);
    brdffit_table_free(t);
    rm_tree(dir);
}
END_TEST

/* Five fits, written by the two writer threads (models alternately): the
 * files listed in the models' order (the reference's, then each model's
 * EXR, PNG and difference PNG with its index), each model's image error its
 * own; then with models 1 and 3 refused (a parameter out of range), the
 * error is model 1's, the first in order, whichever thread met it. */
START_TEST(model_files_in_order)
{
    char dir[512];
    tmpdir(dir, sizeof dir);
    brdffit_table *t = ct_table();
    const brdffit_model models[5] = { BRDFFIT_COOK_TORRANCE, BRDFFIT_WARD, BRDFFIT_GGX,
                                      BRDFFIT_BLINN_PHONG, BRDFFIT_WARD_DUER };
    /* ct_params' (F0, m) = (0.6, 0.3) serve Cook-Torrance and GGX (F0, alpha); the others' p[0] */
    const double p0[5] = { 0.6, 0.2, 0.6, 50, 0.2 };
    rf_fit fits[5];
    memset(fits, 0, sizeof fits);
    for (int k = 0; k < 5; k++) {
        fits[k].model = models[k];
        fits[k].params = ct_params();
        fits[k].params.p[0] = p0[k];
        fits[k].error = NAN;
    }
    rf_settings s;
    rf_settings_default(&s, BRDFFIT_SCALE_STANDARD);
    s.render_opt.width = 32;
    s.plot = 0;
    rf_result r;
    brdffit_error err;
    ck_assert_msg(rf_write_material(dir, "order", t, fits, 5, &s, &r, &err) == 0, "%s", err.message);
    ck_assert_int_eq(r.nfiles, 2 + 3 * 5 + 5 + 2 + 1); /* diffs, bars, renders.json */
    ck_assert_str_eq(r.files[0].file, "reference.exr");
    ck_assert_str_eq(r.files[1].file, "reference.png");
    for (int k = 0; k < 5; k++) {
        const char *stem = brdffit_model_get(models[k])->name, *suffix[3] = { ".exr", ".png", "-flip.png" };
        for (int q = 0; q < 3; q++) {
            char want[64];
            snprintf(want, sizeof want, "%s%s", stem, suffix[q]);
            ck_assert_str_eq(r.files[2 + 3 * k + q].file, want);
            ck_assert_int_eq(r.files[2 + 3 * k + q].fit, k);
        }
        ck_assert_msg(isfinite(r.image_error[k]) && r.image_error[k] >= 0, "model %d: image error %g",
                      k, r.image_error[k]);
        char diff[64];
        snprintf(diff, sizeof diff, "%s-diff.png", stem);
        ck_assert_str_eq(r.files[17 + k].file, diff); /* once all are known: one scale */
        ck_assert_int_eq(r.files[17 + k].fit, k);
    }
    ck_assert_str_eq(r.files[22].file, "diff-scale.svg");
    ck_assert_str_eq(r.files[23].file, "flip-scale.svg");
    ck_assert(r.image_error[0] < r.image_error[1]); /* the exact model beats Ward */
    fits[1].params.p[0] = -1.0;
    fits[3].params.p[0] = -1.0;
    memset(&err, 0, sizeof err);
    ck_assert_int_eq(rf_write_material(dir, "order", t, fits, 5, &s, &r, &err), -1);
    ck_assert_int_eq(err.status, BRDFFIT_E_PARAM_RANGE);
    ck_assert_msg(strstr(err.message, "render ward:") != NULL, "%s", err.message);
    brdffit_table_free(t);
    rm_tree(dir);
}
END_TEST

START_TEST(unwritable_directory)
{
    char dir[512], path[1024];
    tmpdir(dir, sizeof dir);
    brdffit_table *t = ct_table();
    rf_settings s;
    rf_settings_default(&s, BRDFFIT_SCALE_STANDARD);
    s.render_opt.width = 16;
    brdffit_error err;
    /* a path under a regular file */
    snprintf(path, sizeof path, "%s/file", dir);
    ck_assert_int_eq(tu_write_bytes(path, "x", 1), 0);
    snprintf(path, sizeof path, "%s/file/sub", dir);
    ck_assert_int_eq(rf_write_material(path, "m", t, NULL, 0, &s, NULL, &err), -1);
    ck_assert_int_eq(err.status, BRDFFIT_E_FILE_WRITE);
    ck_assert_ptr_nonnull(strstr(err.message, path));
    snprintf(path, sizeof path, "%s/file", dir);
    ck_assert_int_eq(rf_write_material(path, "m", t, NULL, 0, &s, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.message, "not a directory"));
    /* a directory without write permission (root may write anyway) */
    snprintf(path, sizeof path, "%s/ro", dir);
    ck_assert_int_eq(mkdir(path, 0555), 0);
    if (geteuid() != 0) {
        ck_assert_int_eq(rf_write_material(path, "m", t, NULL, 0, &s, NULL, &err), -1);
        ck_assert_ptr_nonnull(strstr(err.message, path));
    }
    /* a link to a device at a file's name: never followed, never renamed
     * over; the device stays and no temporary is left */
    snprintf(path, sizeof path, "%s/full", dir);
    if (access("/dev/full", W_OK) == 0 && symlink("/dev/full", path) == 0) {
        out_dir d;
        ck_assert_int_eq(od_open(&d, dir, 0, &err), 0);
        ck_assert_int_eq(exr_write_rgba(&d, "full", (float[4]){ 0, 0, 0, 1 }, 1, 1, 0, &err), -1);
        ck_assert_int_eq(err.status, BRDFFIT_E_FILE_WRITE);
        ck_assert_msg(strstr(err.message, "symbolic link (not followed)"), "%s", err.message);
        ck_assert_int_eq(png_write_rgb8(&d, "full", (unsigned char[3]){ 0, 0, 0 }, 1, 1, &err), -1);
        ck_assert_int_eq(err.status, BRDFFIT_E_FILE_WRITE);
        od_close(&d);
        struct stat st;
        ck_assert_int_eq(stat(path, &st), 0);
        ck_assert(S_ISCHR(st.st_mode));
        ck_assert_int_eq(lstat(path, &st), 0);
        ck_assert(S_ISLNK(st.st_mode));
        DIR *dd = opendir(dir);
        struct dirent *e;
        while ((e = readdir(dd)) != NULL)
            ck_assert_msg(!strstr(e->d_name, ".tmp"), "a temporary is left: %s", e->d_name);
        closedir(dd);
    }
    brdffit_table_free(t);
    rm_tree(dir);
}
END_TEST

/* An RGB EXR of w x h half floats through OpenEXR's C API, value(i, j, c). */
static void write_half_exr(const char *path, int w, int h, float (*value)(int, int, int))
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t f;
    int part;
    ck_assert_int_eq(exr_start_write(&f, path, EXR_WRITE_FILE_DIRECTLY, &init), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exr_add_part(f, "env", EXR_STORAGE_SCANLINE, &part), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exr_initialize_required_attr_simple(f, part, w, h, EXR_COMPRESSION_PIZ),
                     EXR_ERR_SUCCESS);
    const char *ch[3] = { "B", "G", "R" };
    for (int c = 0; c < 3; c++)
        ck_assert_int_eq(exr_add_channel(f, part, ch[c], EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LINEAR, 1, 1), 0);
    ck_assert_int_eq(exr_write_header(f), EXR_ERR_SUCCESS);
    float *px = malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            for (int c = 0; c < 3; c++)
                px[3 * (j * w + i) + c] = value(i, j, c);
    int32_t lines;
    ck_assert_int_eq(exr_get_scanlines_per_chunk(f, part, &lines), EXR_ERR_SUCCESS);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    for (int y = 0; y < h; y += lines) {
        exr_chunk_info_t ci;
        ck_assert_int_eq(exr_write_scanline_chunk_info(f, part, y, &ci), EXR_ERR_SUCCESS);
        ck_assert_int_eq(y ? exr_encoding_update(f, part, &ci, &enc)
                           : exr_encoding_initialize(f, part, &ci, &enc), EXR_ERR_SUCCESS);
        for (int k = 0; k < enc.channel_count; k++) {
            int c = enc.channels[k].channel_name[0] == 'R' ? 0 : enc.channels[k].channel_name[0] == 'G' ? 1 : 2;
            enc.channels[k].encode_from_ptr = (const uint8_t *)(px + 3 * (size_t)y * w + c);
            enc.channels[k].user_pixel_stride = 12;
            enc.channels[k].user_line_stride = 12 * w;
            enc.channels[k].user_data_type = EXR_PIXEL_FLOAT;
            enc.channels[k].user_bytes_per_element = 4;
        }
        if (y == 0)
            ck_assert_int_eq(exr_encoding_choose_default_routines(f, part, &enc), EXR_ERR_SUCCESS);
        ck_assert_int_eq(exr_encoding_run(f, part, &enc), EXR_ERR_SUCCESS);
    }
    exr_encoding_destroy(f, &enc);
    ck_assert_int_eq(exr_finish(&f), EXR_ERR_SUCCESS);
    free(px);
}

static float ramp(int i, int j, int c)
{
    return 0.25f * (float)(i % 8) + 0.5f * (float)j + (float)c; /* exact in half */
}

static float with_inf(int i, int j, int c)
{
    return (i == 3 && j == 2 && c == 1) ? INFINITY : 1.0f;
}

START_TEST(env_exr_reading)
{
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    write_half_exr(path, 37, 19, ramp); /* odd sizes, half floats */
    float *rgb = NULL;
    int w, h;
    brdffit_error err;
    ck_assert_msg(exr_read_rgb(path, &rgb, NULL, &w, &h, &err) == 0, "%s", err.message);
    ck_assert_int_eq(w, 37);
    ck_assert_int_eq(h, 19);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            for (int c = 0; c < 3; c++)
                ck_assert(rgb[3 * (j * w + i) + c] == ramp(i, j, c));
    free(rgb);
    /* a non-finite texel is refused, named */
    write_half_exr(path, 8, 4, with_inf);
    ck_assert_int_eq(exr_read_rgb(path, &rgb, NULL, &w, &h, &err), -1);
    ck_assert_int_eq(err.status, BRDFFIT_E_FILE_NONFINITE);
    ck_assert_ptr_nonnull(strstr(err.message, "pixel (3, 2) channel G"));
    ck_assert_ptr_null(rgb);
    /* not an EXR; a truncated one; a missing file */
    ck_assert_int_eq(tu_write_bytes(path, "P6\n1 1\n255\nabc", 14), 0);
    ck_assert_int_eq(exr_read_rgb(path, &rgb, NULL, &w, &h, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.message, path));
    write_half_exr(path, 64, 64, ramp);
    FILE *f = fopen(path, "rb");
    char buf[4096];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    ck_assert(n > 600);
    ck_assert_int_eq(tu_write_bytes(path, buf, n / 2), 0);
    ck_assert_int_eq(exr_read_rgb(path, &rgb, NULL, &w, &h, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.message, path));
    unlink(path);
    ck_assert_int_eq(exr_read_rgb(path, &rgb, NULL, &w, &h, &err), -1);
    ck_assert_int_eq(err.status, BRDFFIT_E_FILE_OPEN);
}
END_TEST

START_TEST(srgb_and_colour_maps)
{
    for (int i = 0; i <= 1000; i++) {
        double v = i / 1000.0;
        ck_assert_int_eq(tm_srgb8(v), srgb8(v));
    }
    ck_assert_int_eq(tm_srgb8(-1), 0);
    ck_assert_int_eq(tm_srgb8(NAN), 0);
    ck_assert_int_eq(tm_srgb8(7), 255);
    unsigned char c[3];
    cm_diverging(0, c); /* ColorBrewer RdBu's white */
    ck_assert(c[0] == 247 && c[1] == 247 && c[2] == 247);
    cm_diverging(-1, c);
    ck_assert(c[0] == 5 && c[1] == 48 && c[2] == 97);
    cm_diverging(7, c);
    ck_assert(c[0] == 103 && c[1] == 0 && c[2] == 31);
    cm_diverging(-0.5, c);
    ck_assert(c[2] > c[0]); /* darker: blue */
    cm_diverging(0.5, c);
    ck_assert(c[0] > c[2]); /* brighter: red */
    cm_magma(0, c); /* NVIDIA's MapMagma[0] and [255] as its tool writes them */
    ck_assert(c[0] == 0 && c[1] == 0 && c[2] == 4);
    cm_magma(1, c);
    ck_assert(c[0] == 252 && c[1] == 253 && c[2] == 191);
    /* exposure: 1 / the 99th percentile of max(R, G, B) over pixels with A > 0 */
    float img[4 * 200];
    for (int i = 0; i < 200; i++) {
        img[4 * i] = (float)(i + 1), img[4 * i + 1] = 0, img[4 * i + 2] = 0;
        img[4 * i + 3] = i < 100 ? 1.0f : 0.0f;
    }
    ck_assert_double_eq_tol(tm_auto_exposure(img, 200, 1, 0), 1.0 / 99.0, 1e-12);
}
END_TEST

/* The difference scale: the 95th percentile of |dL*| (NaN left out), rounded
 * up to 1, 1.5, 2, 3, 5, 7 x 10^k within [1, 100]. */
START_TEST(difference_scale)
{
    float v[200];
    for (int i = 0; i < 200; i++)
        v[i] = i < 100 ? (float)(i % 2 ? -i : i) * 0.1f : NAN; /* |v| 0 .. 9.9 */
    ck_assert_double_eq(ci_diff_scale(v, 200), 10);
    for (int i = 0; i < 100; i++)
        v[i] *= 0.25f; /* 95th percentile 2.35 */
    ck_assert_double_eq(ci_diff_scale(v, 200), 3);
    ck_assert_double_eq(ci_diff_scale(v + 100, 100), 1); /* none finite */
    v[0] = 1e6f;
    for (int i = 1; i < 200; i++)
        v[i] = 500;
    ck_assert_double_eq(ci_diff_scale(v, 200), 100);
}
END_TEST

/* Masked pixels: a measured neighbour's mean within 1, else within 2 pixels;
 * none: left masked. */
START_TEST(masked_pixels_filled)
{
    float px[4 * 7 * 7];
    for (int i = 0; i < 49; i++) {
        px[4 * i] = px[4 * i + 1] = px[4 * i + 2] = (float)i;
        px[4 * i + 3] = BRDFFIT_COVERAGE_MASKED;
    }
    px[4 * 0 + 3] = 1.0f;  /* (0, 0) measured */
    px[4 * 2 + 3] = 1.0f;  /* (2, 0) measured */
    ck_assert_int_eq(ci_fill_masked(px, 7), 13); /* the 5 x 3 block at the top left but the two */
    ck_assert(px[4 * 1 + 3] == 1.0f && px[4 * 1] == 1.0f);     /* (1, 0): mean of 0 and 2 */
    ck_assert(px[4 * 8 + 3] == 1.0f && px[4 * 8] == 1.0f);     /* (1, 1): the same */
    ck_assert(px[4 * 16 + 3] == 1.0f && px[4 * 16] == 1.0f);   /* (2, 2): within 2 */
    ck_assert(px[4 * 4 + 3] == 1.0f && px[4 * 4] == 2.0f);     /* (4, 0): (2, 0) alone */
    ck_assert(px[4 * 48 + 3] == BRDFFIT_COVERAGE_MASKED && px[4 * 48] == 48.0f); /* (6, 6) */
}
END_TEST

/* A model brighter than the reference everywhere shows red, a darker one
 * blue; both on one scale, given on the colour bar. */
START_TEST(difference_signs)
{
    char dir[512], path[1024];
    tmpdir(dir, sizeof dir);
    brdffit_table *t = ct_table();
    rf_fit fits[2];
    memset(fits, 0, sizeof fits);
    for (int k = 0; k < 2; k++) {
        fits[k].model = BRDFFIT_COOK_TORRANCE;
        fits[k].params = ct_params();
        for (int c = 0; c < 3; c++)
            fits[k].params.d[c] *= k ? 0.5 : 1.5, fits[k].params.s[c] *= k ? 0.5 : 1.5;
        fits[k].stem = k ? "darker" : "brighter";
        fits[k].error = NAN;
    }
    rf_settings s;
    rf_settings_default(&s, BRDFFIT_SCALE_STANDARD);
    s.render_opt.width = 48;
    s.plot = 0;
    rf_result r;
    brdffit_error err;
    ck_assert_msg(rf_write_material(dir, "signs", t, fits, 2, &s, &r, &err) == 0, "%s", err.message);
    for (int k = 0; k < 2; k++) {
        int w, h, red = 0, blue = 0;
        snprintf(path, sizeof path, "%s/%s-diff.png", dir, k ? "darker" : "brighter");
        unsigned char *png = read_png(path, &w, &h);
        for (int i = 0; i < w * h; i++) {
            red += png[3 * i] > png[3 * i + 2] + 30;
            blue += png[3 * i + 2] > png[3 * i] + 30;
        }
        free(png);
        ck_assert_msg(k ? blue > 20 * (red + 1) : red > 20 * (blue + 1), "%s: %d red, %d blue",
                      path, red, blue);
    }
    tu_xml_doc doc;
    snprintf(path, sizeof path, "%s/diff-scale.svg", dir);
    ck_assert_msg(tu_xml_load(path, &doc) == 0, "%s", doc.error);
    char top[32];
    snprintf(top, sizeof top, "%+g", r.diff_scale);
    int ticks = 0;
    for (int i = 0; i < doc.n; i++)
        if (strcmp(doc.e[i].name, "text") == 0)
            ticks += strcmp(doc.e[i].text, top) == 0;
    ck_assert_int_eq(ticks, 1);
    tu_xml_free(&doc);
    brdffit_table_free(t);
    rm_tree(dir);
}
END_TEST

Suite *render_files_suite(void)
{
    Suite *s = suite_create("render_files");
    TCase *tc = tcase_create("render_files");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, material_files_read_back);
    tcase_add_test(tc, model_files_in_order);
    tcase_add_test(tc, unwritable_directory);
    tcase_add_test(tc, env_exr_reading);
    tcase_add_test(tc, srgb_and_colour_maps);
    tcase_add_test(tc, difference_scale);
    tcase_add_test(tc, masked_pixels_filled);
    tcase_add_test(tc, difference_signs);
    suite_add_tcase(s, tc);
    return s;
}
