/* SPDX-License-Identifier: MIT */
/* test_export.c -- `brdffit export --format gltf|mitsuba` run as a program (under the
 * sanitizers in `make sanitize`): the .gltf of a core and an extended fit is
 * one strict JSON object with the record's material, the extensions only in
 * the extended one and never required; a value outside glTF's ranges is
 * refused naming its line.  python/tests/test_export_gltf.py reads the
 * files in depth (the buffer, pygltflib, Blender). */
#define _DEFAULT_SOURCE
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RECORD(material, model, d, s, p)                                                       \
    "{\"kind\":\"fit\",\"material\":\"" material "\",\"model\":\"" model "\",\"status\":\"ok\"," \
    "\"status_code\":0,\"d\":" d ",\"s\":" s ",\"p\":" p ",\"error\":0.05}\n"

static const char core[] = RECORD("red", "gltf", "[0.8,0.05,0.0125]", "[1,1,1]", "[0,0.45,1.5,1]");
static const char ext[] = RECORD("metal", "gltf-ext", "[0.9123456789,0.7,0.3]", "[0.95,0.8,0.6]",
                                 "[0.85,0.25,2.25,0.75]");
static const char ward[] = RECORD("bronze", "ward", "[0.1,0.1,0.1]", "[0.2,0.2,0.2]", "[0.05]");

static char dir[64];

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/brdffit-export-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void remove_dir(void)
{
    tu_remove_tree(dir);
}

/* Write text to DIR/name; the path into path. */
static void put(const char *name, const char *text, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", dir, name);
    ck_assert_int_eq(tu_write_bytes(path, text, strlen(text)), 0);
}

/* The one material of a .gltf file: 1 extended (the extensions there), 0 core. */
static void expect_material(const char *doc, const double *base, double metallic,
                            double roughness, int extended)
{
    const char *mat = tu_json_element(tu_json_member(doc, "materials"), 0);
    ck_assert_ptr_nonnull(mat);
    const char *pbr = tu_json_member(mat, "pbrMetallicRoughness");
    double x;
    for (int c = 0; c < 4; c++) {
        ck_assert(tu_json_get_element(pbr, "baseColorFactor", c, &x));
        ck_assert_double_eq_tol(x, c < 3 ? base[c] : 1, 1e-9);
    }
    ck_assert(tu_json_get_number(pbr, "metallicFactor", &x) && fabs(x - metallic) < 1e-9);
    ck_assert(tu_json_get_number(pbr, "roughnessFactor", &x) && fabs(x - roughness) < 1e-9);
    ck_assert(tu_json_member(doc, "extensionsRequired") == NULL);
    ck_assert_int_eq(tu_json_member(doc, "extensionsUsed") != NULL, extended);
    ck_assert_int_eq(tu_json_member(mat, "extensions") != NULL, extended);
}

START_TEST(export_writes_strict_gltf)
{
    char fits[128], args[512], path[256];
    make_dir();
    char text[2048];
    snprintf(text, sizeof text, "%s%s%s", ward, core, ext);
    put("fits.jsonl", text, fits, sizeof fits);
    snprintf(args, sizeof args, "export %s --format gltf --out %s/out", fits, dir);
    tu_run_out r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 0, args);
    ck_assert_msg(strstr(r.err, "ward: not a glTF model") != NULL, "%s", r.err);
    const double red[3] = { 0.8, 0.05, 0.0125 }, metal[3] = { 0.9123456789, 0.7, 0.3 };
    snprintf(path, sizeof path, "%s/out/red-gltf.gltf", dir);
    char *doc = tu_slurp(path);
    ck_assert_msg(doc && tu_json_object_line(doc), "%s: not one JSON object", path);
    expect_material(doc, red, 0, 0.45, 0);
    free(doc);
    snprintf(path, sizeof path, "%s/out/metal-gltf-ext.gltf", dir);
    doc = tu_slurp(path);
    ck_assert_msg(doc && tu_json_object_line(doc), "%s: not one JSON object", path);
    expect_material(doc, metal, 0.85, 0.25, 1);
    ck_assert(strstr(doc, "\"KHR_materials_ior\":{\"ior\":2.25}") != NULL);
    free(doc);
    tu_run_free(&r);
    remove_dir();
}
END_TEST

START_TEST(export_refuses_values_outside_gltf)
{
    static const char bad[] = RECORD("hot", "gltf", "[1.5,0.5,0.5]", "[1,1,1]", "[0,0.5,1.5,1]");
    char fits[128], args[512], text[1024];
    make_dir();
    snprintf(text, sizeof text, "%s%s", core, bad);
    put("fits.jsonl", text, fits, sizeof fits);
    snprintf(args, sizeof args, "export %s --out %s/out", fits, dir);
    tu_run_out r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 1, args);
    ck_assert_msg(strstr(r.err, "line 2: hot, gltf: base colour r = 1.5 is not in [0, 1]") != NULL,
                  "%s", r.err);
    ck_assert_msg(strstr(r.out, "red-gltf.gltf") != NULL && strstr(r.out, "hot") == NULL, "%s",
                  r.out);
    tu_run_free(&r);
    remove_dir();
}
END_TEST

/* --format mitsuba: every model's fit is a scene whose BSDF holds the fit
 * under the registry's parameter names; one out of its model's bounds is
 * refused naming its line.  python/tests/test_mitsuba.py renders them. */
START_TEST(export_writes_mitsuba_scenes)
{
    static const char he[] = RECORD("tin", "he", "[0.1,0.2,0.3]", "[0.5,0.5,0.5]", "[16,0.5,2]");
    static const char bad[] = RECORD("wide", "ward", "[0.1,0.1,0.1]", "[0.2,0.2,0.2]", "[5]");
    char fits[128], args[512], path[256], text[2048];
    make_dir();
    snprintf(text, sizeof text, "%s%s%s%s", ward, core, he, bad);
    put("fits.jsonl", text, fits, sizeof fits);
    snprintf(args, sizeof args, "export %s --format mitsuba --size 32 --out %s/out", fits, dir);
    tu_run_out r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 1, args);
    ck_assert_msg(strstr(r.err, "line 4: wide, ward:") != NULL && strstr(r.err, "alpha") != NULL,
                  "%s", r.err);
    static const char *const want[3][3] = {
        { "bronze-ward.xml", "<float name=\"alpha\" value=\"0.05\"/>", "\"model\" value=\"ward\"" },
        { "red-gltf.xml", "<float name=\"roughness\" value=\"0.45\"/>", "<rgb name=\"d\" value=\"0.8, 0.05, 0.0125\"/>" },
        { "tin-he.xml", "<float name=\"sigma0\" value=\"0.5\"/>", "<float name=\"tau\" value=\"16\"/>" },
    };
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/out/%s", dir, want[k][0]);
        char *doc = tu_slurp(path);
        ck_assert_msg(doc != NULL, "%s: not written", path);
        ck_assert(strstr(doc, "<scene version=\"3.0.0\">") != NULL);
        ck_assert(strstr(doc, "<sensor type=\"orthographic\">") != NULL);
        ck_assert(strstr(doc, "<integer name=\"width\" value=\"32\"/>") != NULL);
        ck_assert(strstr(doc, "<bsdf type=\"brdffit\">") != NULL);
        ck_assert_msg(strstr(doc, want[k][1]) && strstr(doc, want[k][2]), "%s:\n%s", path, doc);
        free(doc);
    }
    tu_run_free(&r);
    remove_dir();
}
END_TEST

Suite *export_suite(void)
{
    Suite *s = suite_create("export");
    TCase *tc = tcase_create("gltf");
    tcase_add_test(tc, export_writes_strict_gltf);
    tcase_add_test(tc, export_refuses_values_outside_gltf);
    suite_add_tcase(s, tc);
    TCase *mi = tcase_create("mitsuba");
    tcase_add_test(mi, export_writes_mitsuba_scenes);
    suite_add_tcase(s, mi);
    return s;
}
