/* SPDX-License-Identifier: MIT */
/* test_draw.c -- `brdffit render` and `brdffit plot` ($BRDFFIT_CLI): files
 * from a FITS.jsonl, the image errors printed, SVG parsed; bad light specs,
 * an unwritable --out, a malformed --env EXR and one too bright to render
 * get a message and a status; a TSV of parameters is scored (render prints
 * the Error score prints), and one stating another scale is refused. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "image_io.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[512], table[1024], fits[1024];

/* A Cook-Torrance table and a FITS.jsonl with one record of it, as `fit --json` writes. */
static void setup(void)
{
    const char *t = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/brdffit-draw-XXXXXX", t && *t ? t : "/tmp");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    snprintf(table, sizeof table, "%s/ct.binary", dir);
    brdffit_table *tb = NULL;
    brdffit_params p = { { 0.05, 0.08, 0.12 }, { 0.3, 0.25, 0.2 }, { 0.6, 0.3, 0 }, { 0, 0, 0 } };
    ck_assert_int_eq(brdffit_table_create(&tb, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(tb, BRDFFIT_COOK_TORRANCE, &p, BRDFFIT_SCALE_STANDARD, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_write(tb, table, NULL), BRDFFIT_OK);
    brdffit_table_free(tb);
    snprintf(fits, sizeof fits, "%s/fits.jsonl", dir);
    FILE *f = fopen(fits, "w");
    ck_assert_ptr_nonnull(f);
    fputs("{\"material\":\"other\",\"model\":\"ward\",\"status\":\"ok\",\"d\":[1,1,1],\"s\":[1,1,1],\"p\":[0.1],\"error\":1}\n"
          "{\"material\":\"ct\",\"file\":null,\"model\":\"cook-torrance\",\"status\":\"ok\",\"param_names\":[\"F0\",\"m\"],"
          "\"d\":[0.05,0.08,0.12],\"s\":[0.3,0.25,0.2],\"p\":[0.6,0.3],\"error\":0.0123,"
          "\"metric\":{\"name\":\"ngan-l2\",\"cutoff_deg\":80,\"scale\":\"standard\"}}\n"
          "{\"material\":\"ct\",\"model\":\"ward\",\"status\":\"ok\",\"d\":[0.05,0.08,0.12],\"s\":[0.3,0.25,0.2],"
          "\"p\":[0.2],\"error\":0.0456,\"metric\":{\"scale\":\"standard\"}}\n", f);
    fclose(f);
}

static void teardown(void)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
}

/* `brdffit ARGS`: exit status; stdout and stderr into out / err (malloc'd). */
static int run(const char *args, char **out, char **err)
{
    const char *cli = getenv("BRDFFIT_CLI");
    char cmd[4096], fo[1100], fe[1100];
    snprintf(fo, sizeof fo, "%s/stdout", dir);
    snprintf(fe, sizeof fe, "%s/stderr", dir);
    snprintf(cmd, sizeof cmd, "'%s' %s >'%s' 2>'%s' </dev/null", cli && *cli ? cli : "./build/brdffit",
             args, fo, fe);
    int rc = system(cmd);
    char *bufs[2] = { NULL, NULL };
    const char *paths[2] = { fo, fe };
    for (int k = 0; k < 2; k++) {
        FILE *f = fopen(paths[k], "rb");
        ck_assert_ptr_nonnull(f);
        bufs[k] = calloc(1, 1 << 16);
        size_t n = fread(bufs[k], 1, (1 << 16) - 1, f);
        bufs[k][n] = '\0';
        fclose(f);
    }
    *out = bufs[0];
    *err = bufs[1];
    return rc != -1 && WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static int exists(const char *sub, const char *name)
{
    char p[1200];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s/%s", dir, sub, name);
    return stat(p, &st) == 0 && st.st_size > 0;
}

START_TEST(render_from_fits_file)
{
    char args[4096], *out, *err;
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/r' --size 48 "
             "--light 0,0,1 --light=-1,1,1:2,2,2", table, fits, dir);
    int rc = run(args, &out, &err);
    ck_assert_msg(rc == 0, "exit %d\n%s\n%s", rc, out, err);
    const char *names[] = { "reference.exr", "reference.png", "cook-torrance.png", "cook-torrance-diff.png",
                            "ward.exr", "ward.png", "ward-diff.png", "renders.json" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        ck_assert_msg(exists("r", names[i]), "%s missing", names[i]);
    ck_assert(!exists("r", "plot-measured.svg")); /* render draws no plots */
    ck_assert_ptr_nonnull(strstr(out, "image error"));
    ck_assert_ptr_nonnull(strstr(out, "Cook-Torrance: 0.0123"));
    ck_assert_ptr_nonnull(strstr(out, "Ward: 0.0456"));
    free(out);
    free(err);
}
END_TEST

START_TEST(plot_svgs_parse)
{
    char args[4096], *out, *err, path[1200];
    snprintf(args, sizeof args, "plot '%s' --fits '%s' --model cook-torrance --out '%s/p' --theta-i 30,60",
             table, fits, dir);
    int rc = run(args, &out, &err);
    ck_assert_msg(rc == 0, "exit %d\n%s\n%s", rc, out, err);
    ck_assert(!exists("p", "plot-ward.svg")); /* --model cook-torrance only */
    const char *names[2] = { "plot-measured.svg", "plot-cook-torrance.svg" };
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/p/%s", dir, names[k]);
        tu_xml_doc doc;
        ck_assert_msg(tu_xml_load(path, &doc) == 0, "%s", doc.error);
        int legend = 0;
        for (int i = 0; i < doc.n; i++)
            legend += strcmp(doc.e[i].name, "text") == 0 && strstr(doc.e[i].text, "\xce\xb8i = ") != NULL;
        ck_assert_int_eq(legend, 2);
        tu_xml_free(&doc);
    }
    free(out);
    free(err);
}
END_TEST

START_TEST(bad_inputs_are_reported)
{
    char args[4096], *out, *err, path[1200];
    /* bad light specs: usage errors (2) naming the spec */
    const char *bad[] = { "1,2", "1,2,x", "0,0,0", "1,1,1:1,1", "1,1,1:-1,0,0", "1,1,1,1" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/b' --light '%s'", table, fits, dir, bad[i]);
        int rc = run(args, &out, &err);
        ck_assert_msg(rc == 2, "--light %s: exit %d", bad[i], rc);
        ck_assert_msg(strstr(err, "--light") != NULL, "%s", err);
        free(out);
        free(err);
    }
    /* an unwritable --out: under a regular file */
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/fits.jsonl/x'", table, fits, dir);
    ck_assert_int_eq(run(args, &out, &err), 1);
    ck_assert_ptr_nonnull(strstr(err, "fits.jsonl/x"));
    free(out);
    free(err);
    /* a malformed EXR, a missing one */
    snprintf(path, sizeof path, "%s/bad.exr", dir);
    ck_assert_int_eq(tu_write_bytes(path, "v/1\x01not an exr at all", 20), 0);
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/e' --env '%s'", table, fits, dir, path);
    ck_assert_int_eq(run(args, &out, &err), 1);
    ck_assert_msg(strstr(err, "bad.exr") != NULL, "%s", err);
    free(out);
    free(err);
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/e' --env '%s/none.exr'", table, fits, dir, dir);
    ck_assert_int_eq(run(args, &out, &err), 1);
    ck_assert_ptr_nonnull(strstr(err, "none.exr"));
    free(out);
    free(err);
    /* a float EXR with a finite texel too bright to render (1e36): refused, named */
    float px[4 * 4 * 2];
    for (int i = 0; i < 4 * 4 * 2; i++)
        px[i] = 1.0f;
    px[4 * (1 * 4 + 2) + 1] = 1e36f;
    brdffit_error xerr;
    out_dir od;
    ck_assert_msg(od_open(&od, dir, 0, &xerr) == 0, "%s", xerr.message);
    ck_assert_msg(exr_write_rgba(&od, "bright.exr", px, 4, 2, 0, &xerr) == 0, "%s", xerr.message);
    od_close(&od);
    snprintf(path, sizeof path, "%s/bright.exr", dir);
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/x' --env '%s'", table, fits, dir, path);
    ck_assert_int_eq(run(args, &out, &err), 1);
    ck_assert_msg(strstr(err, "texel (2, 1) channel 1 is 1e+36, above BRDFFIT_RADIANCE_MAX"), "%s", err);
    free(out);
    free(err);
    /* no --out; no fit of this material in the file; bad --theta-i */
    snprintf(args, sizeof args, "render '%s' --fits '%s'", table, fits);
    ck_assert_int_eq(run(args, &out, &err), 2);
    free(out);
    free(err);
    snprintf(args, sizeof args, "render '%s' --fits '%s' --model he --out '%s/n'", table, fits, dir);
    ck_assert_int_eq(run(args, &out, &err), 1);
    ck_assert_ptr_nonnull(strstr(err, "no successful fit"));
    free(out);
    free(err);
    snprintf(args, sizeof args, "plot '%s' --fits '%s' --out '%s/n' --theta-i 30,95", table, fits, dir);
    ck_assert_int_eq(run(args, &out, &err), 2);
    free(out);
    free(err);
}
END_TEST

/* The number after "\nKEY" in text (KEY starts a line), or NAN when no line has it. */
static double number_after(const char *text, const char *key)
{
    char k[128];
    snprintf(k, sizeof k, "\n%s", key);
    const char *p = strstr(text, k);
    return p ? strtod(p + strlen(k), NULL) : NAN;
}

START_TEST(render_scores_a_tsv_of_parameters)
{
    char tsv[1024], args[4096], *out, *err;
    snprintf(tsv, sizeof tsv, "%s/pub.tsv", dir);
    FILE *f = fopen(tsv, "w");
    ck_assert_ptr_nonnull(f);
    fputs("# published fits\n# scale: flat\n"
          "material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\n"
          "ct\tward\t0.05\t0.07\t0.1\t0.25\t0.2\t0.15\t0.25\t\t\n"
          "ct\tcook-torrance\t0.05\t0.08\t0.12\t0.3\t0.25\t0.2\t0.6\t0.3\t\n", f);
    fclose(f);
    /* the file's scale is not --scale's (standard by default): refused, both named */
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/m' --size 32", table, tsv, dir);
    ck_assert_int_eq(run(args, &out, &err), 1); /* as for any --fits file it cannot use */
    ck_assert_msg(strstr(err, "'# scale: flat' (line 2)") && strstr(err, "--scale standard") &&
                      strstr(err, "--allow-scale-mismatch"), "%s", err);
    free(out);
    free(err);
    snprintf(args, sizeof args, "score '%s' --fits '%s'", table, tsv);
    ck_assert_int_eq(run(args, &out, &err), 2);
    ck_assert_msg(strstr(err, "'# scale: flat'") && strstr(err, "--scale standard"), "%s", err);
    free(out);
    free(err);
    /* on its own scale: the Error of each row, as score computes it */
    snprintf(args, sizeof args, "score '%s' --fits '%s' --scale flat", table, tsv);
    ck_assert_int_eq(run(args, &out, &err), 0);
    double sw = number_after(out, "ward "), sc = number_after(out, "cook-torrance ");
    free(out);
    free(err);
    ck_assert_msg(isfinite(sw) && isfinite(sc) && sw > 0 && sc > 0, "score: %g %g", sw, sc);
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/f' --size 32 --scale flat",
             table, tsv, dir);
    ck_assert_int_eq(run(args, &out, &err), 0);
    double rw = number_after(out, "  ward "), rc = number_after(out, "  cook-torrance ");
    ck_assert_msg(!strstr(out, "nan"), "%s", out);
    ck_assert_msg(tu_reldiff(rw, sw) < 1e-3 && tu_reldiff(rc, sc) < 1e-3,
                  "render %g %g, score %g %g:\n%s", rw, rc, sw, sc, out);
    free(out);
    free(err);
    /* compared anyway when asked: said on stderr */
    snprintf(args, sizeof args, "render '%s' --fits '%s' --out '%s/a' --size 32 "
             "--allow-scale-mismatch", table, tsv, dir);
    ck_assert_int_eq(run(args, &out, &err), 0);
    ck_assert_msg(strstr(err, "warning") && strstr(err, "not fitted to"), "%s", err);
    ck_assert_msg(isfinite(number_after(out, "  ward ")), "%s", out);
    free(out);
    free(err);
}
END_TEST

Suite *draw_suite(void)
{
    Suite *s = suite_create("draw");
    TCase *tc = tcase_create("draw");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, render_from_fits_file);
    tcase_add_test(tc, plot_svgs_parse);
    tcase_add_test(tc, bad_inputs_are_reported);
    tcase_add_test(tc, render_scores_a_tsv_of_parameters);
    suite_add_tcase(s, tc);
    return s;
}
