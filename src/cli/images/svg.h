/* SPDX-License-Identifier: MIT */
/* svg.h -- a small XML text writer (SVG figures, HTML pages) with escaping.
 *
 * The writer keeps a stack of open elements and writes start tags,
 * attributes, text and end tags to a FILE, escaping every attribute value and
 * text it is given (& < > " ' become entities; invalid UTF-8 bytes become
 * U+FFFD; control characters XML 1.0 forbids are dropped).  Element and
 * attribute NAMES are not escaped: pass literals.  A non-finite number given
 * to a numeric attribute, a write error, or an unbalanced close makes the
 * document "failed": the writer then writes nothing more and xml_finish
 * reports it, so a figure never silently carries NaN coordinates.
 *
 * Modes: XML_MODE_XML writes an element without content as <name .../>;
 * XML_MODE_HTML does so only for HTML's void elements (img, br, meta, link,
 * hr, input, col, ...) and writes <name ...></name> for the others, as HTML
 * parsers require.  Output is indented by depth while an element holds only
 * elements; once text is written into an element its content is not
 * re-indented (whitespace there would show).
 *
 * Usage (SVG):
 *     xml_writer w;
 *     svg_begin(&w, f, 640, 480);             // <?xml ...?><svg xmlns=...>
 *     svg_polyline(&w, x, y, n, "#0072b2", 1.5, NULL);
 *     svg_text(&w, 320, 20, "middle", 14, "Ward: 0.562");
 *     if (svg_end(&w) != 0) ... failed ...   // closes <svg>, checks the stream
 * Usage (HTML):
 *     xml_init(&w, f, XML_MODE_HTML);
 *     xml_raw(&w, "<!DOCTYPE html>");
 *     xml_open(&w, "html"); ... xml_close(&w);
 *     xml_finish(&w);
 */
#ifndef BRDFFIT_SVG_H
#define BRDFFIT_SVG_H

#include <stdio.h>

#if defined(__GNUC__)
#define XML_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define XML_PRINTF(a, b)
#endif

#define XML_MAX_DEPTH 64

typedef enum xml_mode { XML_MODE_XML = 0, XML_MODE_HTML = 1 } xml_mode;

typedef struct xml_writer {
    FILE *f;
    xml_mode mode;
    int depth;                          /* open elements                         */
    const char *stack[XML_MAX_DEPTH];   /* their names (literals)                */
    unsigned char has_child[XML_MAX_DEPTH]; /* element content written so far    */
    unsigned char has_text[XML_MAX_DEPTH];  /* text written (no re-indenting)    */
    int tag_open;                       /* a start tag awaits '>' (attributes may follow) */
    int failed;                         /* see above; nothing is written after   */
} xml_writer;

/* Start a document on f (writes nothing). */
void xml_init(xml_writer *w, FILE *f, xml_mode mode);
/* Text written as given, not escaped (a doctype, a trusted fragment). */
void xml_raw(xml_writer *w, const char *s);
/* <name ...  (attributes may follow until the next content or close). */
void xml_open(xml_writer *w, const char *name);
/* name="value" on the start tag just opened; value is escaped. */
void xml_attr(xml_writer *w, const char *name, const char *value);
void xml_attrf(xml_writer *w, const char *name, const char *fmt, ...) XML_PRINTF(3, 4);
/* name="x" with the shortest of %.6g; a non-finite x fails the document. */
void xml_attr_num(xml_writer *w, const char *name, double x);
/* Escaped character data inside the innermost element. */
void xml_text(xml_writer *w, const char *s);
void xml_textf(xml_writer *w, const char *fmt, ...) XML_PRINTF(2, 3);
/* Close the innermost element. */
void xml_close(xml_writer *w);
/* <name>text</name> */
void xml_element_text(xml_writer *w, const char *name, const char *text);
/* Close nothing more; 0 when every element was closed, nothing failed and the
 * stream has no error (after fflush), else -1. */
int xml_finish(xml_writer *w);

/* s escaped for XML text and attribute values onto f (the writer's rules). */
void xml_escape(FILE *f, const char *s);

/* ---- SVG on top of the writer ---- */

/* The XML declaration and <svg xmlns=... width height viewBox="0 0 width height">,
 * left open, with a white background rectangle. */
void svg_begin(xml_writer *w, FILE *f, double width, double height);
/* Close every open element (the <svg>) and xml_finish: 0 on success, -1 failed. */
int svg_end(xml_writer *w);
/* A line; dash is a stroke-dasharray ("6,4") or NULL for solid. */
void svg_line(xml_writer *w, double x1, double y1, double x2, double y2, const char *stroke,
              double width, const char *dash);
/* An open polyline through n points (n >= 2; fewer writes nothing). */
void svg_polyline(xml_writer *w, const double *x, const double *y, int n, const char *stroke,
                  double width, const char *dash);
/* A rectangle; fill / stroke may be NULL ("none"). */
void svg_rect(xml_writer *w, double x, double y, double width, double height, const char *fill,
              const char *stroke);
/* A circle (markers); fill / stroke may be NULL. */
void svg_circle(xml_writer *w, double cx, double cy, double r, const char *fill,
                const char *stroke);
/* Text at (x, y) (baseline), anchor "start" | "middle" | "end", font size in px,
 * rotated by angle degrees about (x, y) when angle != 0. */
void svg_text(xml_writer *w, double x, double y, const char *anchor, double size,
              const char *text);
void svg_text_rotated(xml_writer *w, double x, double y, double angle, const char *anchor,
                      double size, const char *text);

/* The i-th colour (i >= 0, cycling) of a colour-blind-safe categorical palette
 * (Okabe & Ito's eight, black last), as "#rrggbb". */
const char *svg_color(int i);

#endif
