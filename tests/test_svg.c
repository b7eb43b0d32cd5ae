/* SPDX-License-Identifier: MIT */
/* test_svg.c -- the program's XML/SVG writer (src/cli/images/svg.c): documents parse
 * as XML (expat), escaped text reads back as given, failures are reported. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "svg.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char *slurp_file(const char *path)
{
    char *s = tu_slurp(path);
    ck_assert_msg(s != NULL, "cannot read %s", path);
    return s;
}

START_TEST(svg_parses_and_escapes)
{
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    xml_writer w;
    svg_begin(&w, f, 640, 480);
    double x[3] = { 10, 20.5, 30 }, y[3] = { 100, 50, 75.25 };
    svg_polyline(&w, x, y, 3, svg_color(0), 1.5, "6,4");
    svg_line(&w, 0, 0, 640, 480, NULL, 1, NULL);
    svg_text(&w, 320, 20, "middle", 14, "Ward & \"Duer\" <0.5> 'q' \x01");
    svg_text_rotated(&w, 10, 240, -90, "middle", 12, "f^(1/3) \xff bad");
    xml_open(&w, "g");
    xml_attr(&w, "id", "a<b&c\"");
    svg_circle(&w, 5, 5, 2, "#000000", NULL);
    xml_close(&w);
    ck_assert_int_eq(svg_end(&w), 0);
    fclose(f);

    tu_xml_doc doc;
    ck_assert_msg(tu_xml_load(path, &doc) == 0, "%s", doc.error);
    ck_assert_str_eq(doc.e[0].name, "svg");
    ck_assert_str_eq(tu_xml_attr(&doc.e[0], "xmlns"), "http://www.w3.org/2000/svg");
    ck_assert_int_eq(tu_xml_count(&doc, "polyline"), 1);
    ck_assert_int_eq(tu_xml_count(&doc, "text"), 2);
    int texts = 0;
    for (int i = 0; i < doc.n; i++) {
        tu_xml_elem *e = &doc.e[i];
        if (strcmp(e->name, "polyline") == 0) {
            ck_assert_str_eq(tu_xml_attr(e, "points"), "10.00,100.00 20.50,50.00 30.00,75.25");
            ck_assert_str_eq(tu_xml_attr(e, "stroke-dasharray"), "6,4");
            ck_assert_str_eq(tu_xml_attr(e, "stroke"), "#0072b2");
        }
        if (strcmp(e->name, "text") == 0 && texts++ == 0)
            ck_assert_str_eq(e->text, "Ward & \"Duer\" <0.5> 'q' "); /* control char dropped */
        else if (strcmp(e->name, "text") == 0) {
            ck_assert_str_eq(e->text, "f^(1/3) \xEF\xBF\xBD bad"); /* U+FFFD */
            ck_assert_str_eq(tu_xml_attr(e, "transform"), "rotate(-90 10 240)");
        }
        if (strcmp(e->name, "g") == 0)
            ck_assert_str_eq(tu_xml_attr(e, "id"), "a<b&c\"");
    }
    tu_xml_free(&doc);
    unlink(path);
}
END_TEST

START_TEST(svg_failures_are_reported)
{
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    /* a NaN coordinate fails the document and nothing more is written */
    FILE *f = fopen(path, "w");
    xml_writer w;
    svg_begin(&w, f, 100, 100);
    svg_line(&w, 0, NAN, 1, 1, NULL, 1, NULL);
    ck_assert_int_eq(svg_end(&w), -1);
    fclose(f);
    char *s = slurp_file(path);
    ck_assert_ptr_null(strstr(s, "nan"));
    free(s);
    double x[2] = { 0, INFINITY }, y[2] = { 0, 0 };
    f = fopen(path, "w");
    svg_begin(&w, f, 100, 100);
    svg_polyline(&w, x, y, 2, NULL, 1, NULL);
    ck_assert_int_eq(svg_end(&w), -1);
    fclose(f);
    /* unbalanced: a close too many, an element left open, an attribute after text */
    f = fopen(path, "w");
    xml_init(&w, f, XML_MODE_XML);
    xml_open(&w, "a");
    xml_close(&w);
    xml_close(&w);
    ck_assert_int_eq(xml_finish(&w), -1);
    xml_init(&w, f, XML_MODE_XML);
    xml_open(&w, "a");
    ck_assert_int_eq(xml_finish(&w), -1);
    xml_init(&w, f, XML_MODE_XML);
    xml_open(&w, "a");
    xml_text(&w, "t");
    xml_attr(&w, "k", "v");
    xml_close(&w);
    ck_assert_int_eq(xml_finish(&w), -1);
    fclose(f);
    /* a stream that cannot be written (full device) */
    FILE *full = fopen("/dev/full", "w");
    if (full) {
        svg_begin(&w, full, 10, 10);
        ck_assert_int_eq(svg_end(&w), -1);
        fclose(full);
    }
    unlink(path);
}
END_TEST

START_TEST(html_mode_closes_non_void_elements)
{
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    FILE *f = fopen(path, "w");
    xml_writer w;
    xml_init(&w, f, XML_MODE_HTML);
    xml_raw(&w, "<!DOCTYPE html>\n");
    xml_open(&w, "html");
    xml_open(&w, "body");
    xml_open(&w, "div");
    xml_attr(&w, "class", "x");
    xml_close(&w);
    xml_open(&w, "p");
    xml_text(&w, "a ");
    xml_open(&w, "b");
    xml_textf(&w, "%d < %d", 1, 2);
    xml_close(&w);
    xml_open(&w, "br");
    xml_close(&w);
    xml_close(&w);
    xml_close(&w);
    xml_close(&w);
    ck_assert_int_eq(xml_finish(&w), 0);
    fclose(f);
    char *s = slurp_file(path);
    ck_assert_ptr_nonnull(strstr(s, "<div class=\"x\"></div>"));
    ck_assert_ptr_nonnull(strstr(s, "<p>a <b>1 &lt; 2</b><br></p>")); /* no indent after text */
    ck_assert_ptr_null(strstr(s, "/>"));
    free(s);
    unlink(path);
}
END_TEST

/* The palette cycles through its eight colours. */
START_TEST(palette_cycles)
{
    ck_assert_str_eq(svg_color(0), svg_color(8));
    ck_assert_str_ne(svg_color(0), svg_color(1));
}
END_TEST

Suite *svg_suite(void)
{
    Suite *s = suite_create("svg");
    TCase *tc = tcase_create("svg");
    tcase_add_test(tc, svg_parses_and_escapes);
    tcase_add_test(tc, svg_failures_are_reported);
    tcase_add_test(tc, html_mode_closes_non_void_elements);
    tcase_add_test(tc, palette_cycles);
    suite_add_tcase(s, tc);
    return s;
}
