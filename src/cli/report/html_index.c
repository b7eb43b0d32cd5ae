/* SPDX-License-Identifier: MIT */
/* html_index.c -- the report's own files: DIR/index.html (settings, per-model
 * summary, the headline figure, the Error matrix: sortable by any column with
 * a few lines of inline script, readable without) and DIR/fits.tsv
 * (DIR/headline.svg: html_headline.c). */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ settings and Error cells */

static void settings_table(xml_writer *w, const rp_report *rep)
{
    char b[256];
    xml_open(w, "table");
    xml_open(w, "tbody");
    const char *rows[][2] = {
        { "metric", rep->settings.metric[0] ? rep->settings.metric : brdffit_metric_name() },
        { "cutoff", (snprintf(b, sizeof b, "%g deg (theta_i, theta_o)", rep->settings.cutoff_deg), b) },
    };
    for (int i = 0; i < 2; i++) {
        xml_open(w, "tr");
        rp_cell(w, "th", "name", rows[i][0]);
        rp_cell(w, "td", "wrap", rows[i][1]);
        xml_close(w);
    }
    char starts[320], dflt[256];
    if (rep->settings.starts > 0)
        snprintf(starts, sizeof starts, "%d per model", rep->settings.starts);
    else
        snprintf(starts, sizeof starts, "each model's default (%s)",
                 cli_default_starts(dflt, sizeof dflt));
    char pub_how[512];
    snprintf(pub_how, sizeof pub_how, "computed here: the published parameters scored on the "
             "tables given, with the settings above (scale %s), not the figures printed in the "
             "paper%s", rep->settings.scale,
             rep->scale_note[0] ? "; the file states another scale (see the warning above)" : "");
    const char *more[][2] = {
        { "scale", rep->settings.scale },
        { "starts", starts },
        { "brdffit version", rep->settings.version },
        { "backend", rep->backend },
        { "report written", rep->started },
        { "published fits", rep->have_published ? rep->published_path : "(none given)" },
        { "published Errors", rep->have_published ? pub_how : NULL },
    };
    for (size_t i = 0; i < sizeof more / sizeof more[0]; i++) {
        if (!more[i][1])
            continue;
        xml_open(w, "tr");
        rp_cell(w, "th", "name", more[i][0]);
        rp_cell(w, "td", "wrap", more[i][1]);
        xml_close(w);
    }
    xml_close(w);
    xml_close(w);
}

/* An Error cell: the fitted Error (data-v, what the matrix sorts by) and ★
 * when it is the material's lowest; under it the published Error and the
 * ratio (×r = Error / published Error), in full on hover. */
static void error_cell(xml_writer *w, const fit_record *fit, const fit_record *pub, int best,
                       int have_pub)
{
    char b[64], p[64], r[64];
    xml_open(w, "td");
    if (best)
        xml_attr(w, "class", "best");
    int ok = fit && fr_ok(fit) && isfinite(fit->error);
    xml_attrf(w, "data-v", "%s", ok ? rp_num(b, sizeof b, "%.10g", fit->error) : "");
    if (!fit)
        xml_text(w, "-");
    else if (!fr_ok(fit))
        xml_textf(w, "failed: %s", fr_status_text(fit));
    else /* a no-break space keeps the star with its number */
        xml_textf(w, "%s%s", rp_compact(b, sizeof b, 4, fit->error), best ? "\xc2\xa0\xe2\x98\x85" : "");
    if (have_pub && pub) {
        xml_open(w, "span");
        xml_attr(w, "class", "pub");
        if (fr_ok(pub)) {
            double ratio = fr_ratio(fit, pub);
            xml_attrf(w, "title", "published Error %s; ratio Error / published Error %s",
                      rp_num(p, sizeof p, "%.5g", pub->error), rp_num(r, sizeof r, "%.4g", ratio));
            xml_textf(w, "%s\xc2\xa0\xc3\x97%s", rp_compact(p, sizeof p, 3, pub->error),
                      rp_compact(r, sizeof r, 3, ratio));
        } else {
            xml_attr(w, "title", pub->message);
            xml_text(w, "published: invalid");
        }
        xml_close(w);
    }
    xml_close(w);
}

/* ------------------------------------------------------------------ fits.tsv */

int rp_write_fits_tsv(const rp_report *rep, const out_dir *dir, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "fits.tsv", err) != 0)
        return -1;
    fprintf(o.f, "# every fit of the report: metric %s, cutoff %g deg, scale %s, starts %d, "
                 "brdffit %s; ratio = error / published_error; the columns: docs/fit-record.md\n",
            rep->settings.metric, rep->settings.cutoff_deg, rep->settings.scale,
            rep->settings.starts, rep->settings.version);
    fr_write_tsv_header(o.f);
    for (int i = 0; i < rep->n; i++)
        rp_tsv_material(o.f, rep, &rep->m[i]);
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ DIR/index.html */

static void summary_table(xml_writer *w, const rp_report *rep)
{
    char b[64];
    xml_open(w, "table");
    xml_open(w, "thead");
    xml_open(w, "tr");
    rp_cell(w, "th", "name", "model");
    rp_cell(w, "th", NULL, "median Error");
    if (rep->have_published)
        rp_cell(w, "th", NULL, "median ratio to published");
    rp_cell(w, "th", NULL, "best on");
    rp_cell(w, "th", NULL, "fitted");
    xml_close(w);
    xml_close(w);
    xml_open(w, "tbody");
    for (int k = 0; k < rep->nmodels; k++) {
        int nbest = 0, nfit = 0, nratio = 0;
        double med = rp_median(rep, k, &nbest, &nfit);
        xml_open(w, "tr");
        rp_cell(w, "td", "name", brdffit_model_get(rep->models[k])->title);
        rp_cell(w, "td", NULL, rp_compact(b, sizeof b, 4, med));
        if (rep->have_published) {
            double r = rp_median_ratio(rep, k, &nratio);
            char t[96];
            snprintf(t, sizeof t, "%s (of %d)", rp_compact(b, sizeof b, 3, r), nratio);
            rp_cell(w, "td", NULL, nratio ? t : "-");
        }
        snprintf(b, sizeof b, "%d", nbest);
        rp_cell(w, "td", NULL, b);
        snprintf(b, sizeof b, "%d of %d", nfit, rep->n);
        rp_cell(w, "td", NULL, b);
        xml_close(w);
    }
    xml_close(w);
    xml_close(w);
}

static void error_matrix(xml_writer *w, const rp_report *rep)
{
    char href[BJ_NAME_MAX * 3 + 16];
    xml_open(w, "table");
    xml_attr(w, "class", "sortable");
    xml_attr(w, "id", "matrix");
    xml_open(w, "thead");
    xml_open(w, "tr");
    rp_cell(w, "th", "name", "material");
    for (int k = 0; k < rep->nmodels; k++) /* a title may wrap at its spaces */
        rp_cell(w, "th", "wrap", brdffit_model_get(rep->models[k])->title);
    xml_close(w);
    xml_close(w);
    xml_open(w, "tbody");
    for (int i = 0; i < rep->n; i++) {
        const rp_material *m = &rep->m[i];
        int best = rp_best(rep, i);
        xml_open(w, "tr");
        xml_open(w, "td");
        xml_attr(w, "class", "name");
        rp_url_segment(href, sizeof href - 12, m->name);
        strcat(href, "/index.html");
        rp_link(w, href, m->name);
        xml_close(w);
        if (m->failure) {
            xml_open(w, "td");
            xml_attr(w, "class", "failed");
            xml_attrf(w, "colspan", "%d", rep->nmodels);
            xml_textf(w, "not fitted: %s", m->failure->message);
            xml_close(w);
        } else {
            for (int k = 0; k < rep->nmodels; k++)
                error_cell(w, m->fit[k], m->published[k], k == best, rep->have_published);
        }
        xml_close(w);
    }
    xml_close(w);
    xml_close(w);
}

/* Click (or Enter on) a column's header: the rows sorted by it, again: the
 * other way; a cell's data-v is its number ("" none: last), else its text. */
static const char *const sort_script =
    "(function(){var t=document.getElementById('matrix');if(!t||!t.tHead)return;"
    "var hs=t.tHead.rows[0].cells,b=t.tBodies[0];"
    "function key(r,c){if(r.cells.length<hs.length)return null;var x=r.cells[c],"
    "v=x.getAttribute('data-v');return v===null?x.textContent:v===''?null:parseFloat(v);}"
    "function go(c){var th=hs[c],up=th.getAttribute('aria-sort')!=='ascending';"
    "for(var i=0;i<hs.length;i++)hs[i].removeAttribute('aria-sort');"
    "th.setAttribute('aria-sort',up?'ascending':'descending');"
    "var rows=Array.prototype.slice.call(b.rows);rows.sort(function(a,z){"
    "var p=key(a,c),q=key(z,c);if(p===null||q===null)return (p===null)-(q===null);"
    "var d=typeof p==='number'?p-q:p.localeCompare(q);return up?d:-d;});"
    "rows.forEach(function(r){b.appendChild(r);});}"
    "Array.prototype.forEach.call(hs,function(th,c){th.tabIndex=0;"
    "th.title='sort by this column (again: the other way)';"
    "th.addEventListener('click',function(){go(c);});"
    "th.addEventListener('keydown',function(e){if(e.key==='Enter'||e.key===' ')"
    "{e.preventDefault();go(c);}});});})();";

int rp_write_index(const rp_report *rep, const out_dir *dir, int sort_k, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "index.html", err) != 0)
        return -1;
    xml_writer w;
    int failed = 0;
    for (int i = 0; i < rep->n; i++)
        failed += rep->m[i].failure != NULL;
    char title[256];
    snprintf(title, sizeof title, "brdffit report: %d material%s, %d model%s", rep->n,
             rep->n == 1 ? "" : "s", rep->nmodels, rep->nmodels == 1 ? "" : "s");
    rp_html_begin(&w, o.f, title);
    xml_element_text(&w, "h1", title);
    rp_scale_warning(&w, rep);
    if (failed) {
        xml_open(&w, "p");
        xml_attr(&w, "class", "failed");
        xml_textf(&w, "%d material%s could not be fitted: see the rows marked \"not fitted\".",
                  failed, failed == 1 ? "" : "s");
        xml_close(&w);
    }
    xml_element_text(&w, "h2", "Settings");
    settings_table(&w, rep);
    xml_element_text(&w, "h2", "Models");
    summary_table(&w, rep);
    xml_element_text(&w, "h2", "Error of every material");
    xml_open(&w, "figure");
    xml_open(&w, "object"); /* not an img: the SVG's <title>s show on hover */
    xml_attr(&w, "data", "headline.svg");
    xml_attr(&w, "type", "image/svg+xml");
    xml_open(&w, "img");
    xml_attr(&w, "src", "headline.svg");
    xml_attr(&w, "alt", "Error of every model per material, log scale");
    xml_close(&w);
    xml_close(&w);
    xml_open(&w, "figcaption");
    xml_textf(&w, "Each model's Error per material (log scale); materials sorted by %s's Error "
                  "(the lowest median); hover a point for its material, model and Error.",
              sort_k >= 0 ? brdffit_model_get(rep->models[sort_k])->title : "(none)");
    xml_close(&w);
    xml_close(&w);
    xml_element_text(&w, "h2", "Error matrix");
    error_matrix(&w, rep);
    xml_open(&w, "p");
    xml_attr(&w, "class", "note");
    xml_text(&w, "Error = ngan-l2 (1/sr); \xe2\x98\x85 the lowest Error of the material");
    if (rep->have_published)
        xml_text(&w, "; under it: the Error of the published parameters on the same table "
                     "and \xc3\x97 the ratio Error / published Error (below 1: this fit is "
                     "closer), in full on hover");
    xml_text(&w, "; click a column's header to sort by it. Every fit, one line: ");
    rp_link(&w, "fits.tsv", "fits.tsv");
    xml_close(&w);
    xml_open(&w, "script");
    xml_raw(&w, sort_script);
    xml_close(&w);
    rp_html_end(&w);
    return rp_finish(&o, &w, err);
}
