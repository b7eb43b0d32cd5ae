/* SPDX-License-Identifier: MIT */
/* html_report.c -- the report of a batch as static files with relative links:
 * per material DIR/<material>/params.tsv, params.json and index.html (the
 * parameter table, renders, plots: html_material.c); DIR/index.html (settings,
 * per-model summary, the headline figure, the Error matrix), DIR/fits.tsv and
 * DIR/headline.svg (html_index.c).  Here: the pieces they share and rp_write.
 * HTML and SVG go through the escaping writer of svg.h. */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------------ small text helpers */

/* x with fmt, or "-" when it is not finite. */
const char *rp_num(char *buf, size_t len, const char *fmt, double x)
{
    if (isfinite(x))
        snprintf(buf, len, fmt, x);
    else
        snprintf(buf, len, "-");
    return buf;
}

/* x with sig significant digits, short: "0.006531", "2.8e4", "1.2e-5" (no '+',
 * no leading zero in the exponent); "-" when it is not finite. */
const char *rp_compact(char *buf, size_t len, int sig, double x)
{
    if (!isfinite(x)) {
        snprintf(buf, len, "-");
        return buf;
    }
    char t[64];
    snprintf(t, sizeof t, "%.*g", sig, x);
    char *e = strchr(t, 'e');
    if (e) {
        char *q = e + 1;
        int neg = *q == '-';
        q += *q == '-' || *q == '+';
        q += strspn(q, "0");
        snprintf(e + 1, sizeof t - (size_t)(e + 1 - t), "%s%s", neg ? "-" : "", *q ? q : "0");
    }
    snprintf(buf, len, "%s", t);
    return buf;
}

/* A path segment of a relative URL: every byte but [A-Za-z0-9._~-] percent-encoded. */
const char *rp_url_segment(char *buf, size_t len, const char *s)
{
    static const char hex[] = "0123456789ABCDEF";
    size_t n = 0;
    for (const unsigned char *p = (const unsigned char *)s; *p && n + 4 < len; p++) {
        unsigned c = *p;
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
            c == '.' || c == '_' || c == '~' || c == '-') {
            buf[n++] = (char)c;
        } else {
            buf[n++] = '%';
            buf[n++] = hex[c >> 4];
            buf[n++] = hex[c & 15];
        }
    }
    buf[n] = '\0';
    return buf;
}

/* Finish a page written with the XML writer: commit it, or report the failure. */
int rp_finish(out_file *o, xml_writer *w, brdffit_error *err)
{
    if (xml_finish(w) != 0 && !ferror(o->f)) {
        out_abandon(o);
        err->status = BRDFFIT_E_FILE_WRITE;
        snprintf(err->message, sizeof err->message, "cannot write %.1800s: the page could not be "
                 "laid out (a non-finite number or unbalanced element)", o->path);
        return -1;
    }
    return out_commit(o, err);
}

/* ------------------------------------------------------------------ params.tsv, params.json */

/* The rows of a material in the TSV of fits (fit_record.h): its failure, or its fits. */
void rp_tsv_material(FILE *f, const rp_report *rep, const rp_material *m)
{
    if (m->failure) {
        fr_write_tsv_row(f, m->failure, NULL);
        return;
    }
    for (int k = 0; k < rep->nmodels; k++)
        if (m->fit[k])
            fr_write_tsv_row(f, m->fit[k], m->published[k]);
}

/* ------------------------------------------------------------------ HTML pieces */

/* Numbers and names never wrap (white-space:nowrap); prose cells (class
 * wrap, failed) do. */
static const char *const page_css =
    "body{font-family:sans-serif;margin:1.5em;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0;font-size:0.9em}"
    "td,th{border:1px solid #bbb;padding:2px 4px;text-align:right;"
    "font-variant-numeric:tabular-nums;white-space:nowrap}"
    "th{background:#eee}td.name,th.name{text-align:left}"
    "td.wrap{white-space:normal;text-align:left}th.wrap{white-space:normal}"
    "td.best{background:#d8f0d0;font-weight:bold}"
    "td.failed{color:#a00;text-align:left;white-space:normal}"
    "span.pub{display:block;color:#555;font-size:85%;font-weight:normal}"
    "tr.pub td{color:#555;background:#f7f7f7}tr.pub td.name{font-style:italic}"
    "tr.mhead th{background:#e4e4ee}tr.mhead th.name{font-weight:bold}"
    "table.sortable thead th{cursor:pointer}"
    "th[aria-sort=ascending]::after{content:\" \\25B2\"}"
    "th[aria-sort=descending]::after{content:\" \\25BC\"}"
    "p.warn{background:#fff3cd;border:1px solid #c9a400;padding:4px 8px}"
    "figure{display:inline-block;margin:4px;text-align:center}"
    "figure img{display:block}figcaption{font-size:90%}"
    "p.note{color:#555;font-size:90%}"
    "pre{white-space:pre-wrap;overflow-wrap:anywhere;background:#f6f6f6;padding:4px 6px}";

void rp_html_begin(xml_writer *w, FILE *f, const char *title)
{
    xml_init(w, f, XML_MODE_HTML);
    xml_raw(w, "<!DOCTYPE html>\n");
    xml_open(w, "html");
    xml_attr(w, "lang", "en");
    xml_open(w, "head");
    xml_open(w, "meta");
    xml_attr(w, "charset", "utf-8");
    xml_close(w);
    xml_element_text(w, "title", title);
    xml_open(w, "style");
    xml_raw(w, page_css); /* raw text in HTML: entities would not be decoded there */
    xml_close(w);
    xml_close(w);
    xml_open(w, "body");
}

void rp_html_end(xml_writer *w)
{
    xml_close(w); /* body */
    xml_close(w); /* html */
}

/* The scale mismatch of the published fits, when the report has one. */
void rp_scale_warning(xml_writer *w, const rp_report *rep)
{
    if (!rep->scale_note[0])
        return;
    xml_open(w, "p");
    xml_attr(w, "class", "warn");
    xml_textf(w, "Warning: %s.", rep->scale_note);
    xml_close(w);
}

void rp_link(xml_writer *w, const char *href, const char *text)
{
    xml_open(w, "a");
    xml_attr(w, "href", href);
    xml_text(w, text);
    xml_close(w);
}

void rp_cell(xml_writer *w, const char *tag, const char *cls, const char *text)
{
    xml_open(w, tag);
    if (cls)
        xml_attr(w, "class", cls);
    xml_text(w, text);
    xml_close(w);
}

/* ------------------------------------------------------------------ all of it */

/* Copy the asset files of a material kept in another directory (a shard);
 * a file name from its record must be one path component. */
static int copy_assets(const rp_material *m, const out_dir *mdir, brdffit_error *err)
{
    if (!m->assets || !m->asset_dir[0] || strcmp(m->asset_dir, mdir->path) == 0)
        return 0;
    const char *p = m->assets->assets;
    while (*p) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        char line[1024], from[BJ_PATH_MAX];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line - 1 ? n : sizeof line - 1), p);
        p += n + (end ? 1 : 0);
        char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
        if (!t2)
            continue;
        *t2 = '\0';
        const char *bad = od_name_problem(t1 + 1);
        if (bad) {
            err->status = BRDFFIT_E_FILE_READ;
            snprintf(err->message, sizeof err->message, "%.1200s: the file '%.300s' its record "
                     "lists cannot be copied: %s", m->asset_dir, t1 + 1, bad);
            return -1;
        }
        if (out_join(from, sizeof from, m->asset_dir, t1 + 1) != 0 ||
            out_copy(from, mdir, t1 + 1, err) != 0)
            return -1;
    }
    return 0;
}

/* A material's directory and files. */
static int write_material(const rp_report *rep, int i, const out_dir *dir, brdffit_error *err)
{
    const rp_material *m = &rep->m[i];
    out_dir mdir;
    if (od_sub(&mdir, dir, m->name, err) != 0)
        return -1;
    od_sweep(&mdir);
    int rc = copy_assets(m, &mdir, err) != 0 || rp_write_params_tsv(rep, m, &mdir, err) != 0 ||
                     rp_write_params_json(rep, m, &mdir, err) != 0 ||
                     rp_write_export_files(rep, m, &mdir, err) != 0 ||
                     rp_write_mitsuba_files(rep, m, &mdir, err) != 0 ||
                     rp_write_material_page(rep, m, rp_best(rep, i), &mdir, err) != 0
                 ? -1 : 0;
    od_close(&mdir);
    return rc;
}

int rp_write(const rp_report *rep, const out_dir *dir, brdffit_error *err)
{
    for (int i = 0; i < rep->n; i++) {
        if (write_material(rep, i, dir, err) != 0)
            return -1;
        cli_fault_point("page");
    }
    int sort_k = rp_sort_model(rep);
    if (rp_write_fits_tsv(rep, dir, err) != 0 || rp_write_headline(rep, dir, sort_k, err) != 0 ||
        rp_write_index(rep, dir, sort_k, err) != 0)
        return -1;
    return 0;
}
