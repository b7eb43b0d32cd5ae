/* SPDX-License-Identifier: MIT */
/* svg.c -- the XML/SVG text writer of svg.h: escaping, element stack, SVG shapes. */
#include "svg.h"
#include "utf8.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ escaping */

/* Code point and length of the UTF-8 sequence at s, or 0 when it is not a
 * valid one (utf8_seq's faults, and U+FFFE / U+FFFF, which XML does not allow). */
static int xml_seq(const unsigned char *s, unsigned *cp)
{
    int n = utf8_seq(s, cp);
    return n > 0 && *cp != 0xFFFE && *cp != 0xFFFF ? n : 0;
}

void xml_escape(FILE *f, const char *s)
{
    const unsigned char *p = (const unsigned char *)(s ? s : "");
    while (*p) {
        unsigned cp;
        int n = xml_seq(p, &cp);
        if (n == 0) {
            fputs("\xEF\xBF\xBD", f); /* U+FFFD */
            p++;
            continue;
        }
        switch (cp) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default:
            if (cp < 0x20 && cp != '\t' && cp != '\n' && cp != '\r')
                break; /* not allowed in XML 1.0, not even as a reference */
            fwrite(p, 1, (size_t)n, f);
        }
        p += n;
    }
}

/* ------------------------------------------------------------------ the writer */

static const char *const html_void[] = { "area", "base", "br", "col", "embed", "hr", "img",
                                         "input", "link", "meta", "source", "track", "wbr" };

static int is_html_void(const char *name)
{
    for (size_t i = 0; i < sizeof html_void / sizeof html_void[0]; i++)
        if (strcmp(name, html_void[i]) == 0)
            return 1;
    return 0;
}

void xml_init(xml_writer *w, FILE *f, xml_mode mode)
{
    memset(w, 0, sizeof *w);
    w->f = f;
    w->mode = mode;
    if (!f)
        w->failed = 1;
}

void xml_raw(xml_writer *w, const char *s)
{
    if (w->failed || !s)
        return;
    if (w->tag_open) {
        fputc('>', w->f);
        w->tag_open = 0;
    }
    fputs(s, w->f);
}

/* Finish a pending start tag: its content begins. */
static void end_start_tag(xml_writer *w)
{
    if (w->tag_open) {
        fputc('>', w->f);
        w->tag_open = 0;
    }
}

static void indent(xml_writer *w, int depth)
{
    fputc('\n', w->f);
    for (int i = 0; i < depth; i++)
        fputs("  ", w->f);
}

void xml_open(xml_writer *w, const char *name)
{
    if (w->failed)
        return;
    if (!name || w->depth >= XML_MAX_DEPTH) {
        w->failed = 1;
        return;
    }
    end_start_tag(w);
    if (w->depth > 0) {
        w->has_child[w->depth - 1] = 1;
        if (!w->has_text[w->depth - 1])
            indent(w, w->depth);
    }
    fprintf(w->f, "<%s", name);
    w->stack[w->depth] = name;
    w->has_child[w->depth] = 0;
    w->has_text[w->depth] = 0;
    w->depth++;
    w->tag_open = 1;
}

void xml_attr(xml_writer *w, const char *name, const char *value)
{
    if (w->failed)
        return;
    if (!w->tag_open || !name) {
        w->failed = 1; /* an attribute after content: a bug in the caller */
        return;
    }
    fprintf(w->f, " %s=\"", name);
    xml_escape(w->f, value);
    fputc('"', w->f);
}

/* vsnprintf into a buffer that fits (buf when it is long enough); NULL on failure. */
static char *format(char *buf, size_t len, const char *fmt, va_list ap)
{
    va_list aq;
    va_copy(aq, ap);
    int n = vsnprintf(buf, len, fmt, aq);
    va_end(aq);
    if (n < 0)
        return NULL;
    if ((size_t)n < len)
        return buf;
    char *big = malloc((size_t)n + 1);
    if (big)
        vsnprintf(big, (size_t)n + 1, fmt, ap);
    return big;
}

void xml_attrf(xml_writer *w, const char *name, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    char *s = format(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (!s)
        w->failed = 1;
    else
        xml_attr(w, name, s);
    if (s != buf)
        free(s);
}

void xml_attr_num(xml_writer *w, const char *name, double x)
{
    if (!isfinite(x)) {
        w->failed = 1;
        return;
    }
    char buf[32];
    snprintf(buf, sizeof buf, "%.6g", x == 0 ? 0.0 : x); /* no "-0" */
    xml_attr(w, name, buf);
}

void xml_text(xml_writer *w, const char *s)
{
    if (w->failed)
        return;
    if (w->depth == 0) {
        w->failed = 1; /* text outside the root element */
        return;
    }
    end_start_tag(w);
    w->has_text[w->depth - 1] = 1;
    xml_escape(w->f, s);
}

void xml_textf(xml_writer *w, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    char *s = format(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (!s)
        w->failed = 1;
    else
        xml_text(w, s);
    if (s != buf)
        free(s);
}

void xml_close(xml_writer *w)
{
    if (w->failed)
        return;
    if (w->depth == 0) {
        w->failed = 1;
        return;
    }
    int d = --w->depth;
    const char *name = w->stack[d];
    if (w->tag_open) {
        w->tag_open = 0;
        if (w->mode == XML_MODE_XML)
            fputs("/>", w->f);
        else if (is_html_void(name))
            fputc('>', w->f);
        else
            fprintf(w->f, "></%s>", name);
    } else {
        if (w->has_child[d] && !w->has_text[d])
            indent(w, d);
        fprintf(w->f, "</%s>", name);
    }
    if (d == 0)
        fputc('\n', w->f);
}

void xml_element_text(xml_writer *w, const char *name, const char *text)
{
    xml_open(w, name);
    xml_text(w, text);
    xml_close(w);
}

int xml_finish(xml_writer *w)
{
    if (!w->f)
        return -1;
    if (fflush(w->f) != 0 || ferror(w->f))
        w->failed = 1;
    return (w->failed || w->depth != 0 || w->tag_open) ? -1 : 0;
}

/* ------------------------------------------------------------------ SVG */

void svg_begin(xml_writer *w, FILE *f, double width, double height)
{
    xml_init(w, f, XML_MODE_XML);
    xml_raw(w, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    xml_open(w, "svg");
    xml_attr(w, "xmlns", "http://www.w3.org/2000/svg");
    xml_attr(w, "version", "1.1");
    xml_attr_num(w, "width", width);
    xml_attr_num(w, "height", height);
    xml_attrf(w, "viewBox", "0 0 %.6g %.6g", width, height);
    xml_attr(w, "font-family", "DejaVu Sans, Helvetica, Arial, sans-serif");
    svg_rect(w, 0, 0, width, height, "#ffffff", NULL);
}

int svg_end(xml_writer *w)
{
    while (w->depth > 0 && !w->failed)
        xml_close(w);
    return xml_finish(w);
}

static void stroke_attrs(xml_writer *w, const char *stroke, double width, const char *dash)
{
    xml_attr(w, "fill", "none");
    xml_attr(w, "stroke", stroke ? stroke : "#000000");
    xml_attr_num(w, "stroke-width", width);
    if (dash)
        xml_attr(w, "stroke-dasharray", dash);
}

void svg_line(xml_writer *w, double x1, double y1, double x2, double y2, const char *stroke,
              double width, const char *dash)
{
    xml_open(w, "line");
    xml_attr_num(w, "x1", x1);
    xml_attr_num(w, "y1", y1);
    xml_attr_num(w, "x2", x2);
    xml_attr_num(w, "y2", y2);
    stroke_attrs(w, stroke, width, dash);
    xml_close(w);
}

void svg_polyline(xml_writer *w, const double *x, const double *y, int n, const char *stroke,
                  double width, const char *dash)
{
    if (n < 2 || w->failed)
        return;
    xml_open(w, "polyline");
    /* the points attribute, written directly (numbers need no escaping) */
    fputs(" points=\"", w->f);
    for (int i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i])) {
            w->failed = 1;
            return;
        }
        fprintf(w->f, "%s%.2f,%.2f", i ? " " : "", x[i], y[i]);
    }
    fputc('"', w->f);
    stroke_attrs(w, stroke, width, dash);
    xml_attr(w, "stroke-linejoin", "round");
    xml_close(w);
}

void svg_rect(xml_writer *w, double x, double y, double width, double height, const char *fill,
              const char *stroke)
{
    xml_open(w, "rect");
    xml_attr_num(w, "x", x);
    xml_attr_num(w, "y", y);
    xml_attr_num(w, "width", width);
    xml_attr_num(w, "height", height);
    xml_attr(w, "fill", fill ? fill : "none");
    xml_attr(w, "stroke", stroke ? stroke : "none");
    xml_close(w);
}

void svg_circle(xml_writer *w, double cx, double cy, double r, const char *fill,
                const char *stroke)
{
    xml_open(w, "circle");
    xml_attr_num(w, "cx", cx);
    xml_attr_num(w, "cy", cy);
    xml_attr_num(w, "r", r);
    xml_attr(w, "fill", fill ? fill : "none");
    xml_attr(w, "stroke", stroke ? stroke : "none");
    xml_close(w);
}

void svg_text_rotated(xml_writer *w, double x, double y, double angle, const char *anchor,
                      double size, const char *text)
{
    xml_open(w, "text");
    xml_attr_num(w, "x", x);
    xml_attr_num(w, "y", y);
    xml_attr(w, "text-anchor", anchor ? anchor : "start");
    xml_attr_num(w, "font-size", size);
    if (angle != 0)
        xml_attrf(w, "transform", "rotate(%.6g %.6g %.6g)", angle, x, y);
    xml_text(w, text);
    xml_close(w);
}

void svg_text(xml_writer *w, double x, double y, const char *anchor, double size,
              const char *text)
{
    svg_text_rotated(w, x, y, 0, anchor, size, text);
}

const char *svg_color(int i)
{
    /* Okabe & Ito (2008), yellow moved late: it is faint on white */
    static const char *const palette[] = { "#0072b2", "#d55e00", "#009e73", "#e69f00",
                                           "#cc79a7", "#56b4e9", "#f0e442", "#000000" };
    int n = (int)(sizeof palette / sizeof palette[0]);
    return palette[((i % n) + n) % n];
}
