/* SPDX-License-Identifier: MIT */
/* html_material.c -- a material's files in the report: params.tsv,
 * params.json and its page, index.html (parameter table, renders, plots). */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <string.h>

static const char *param_label(brdffit_model model, int k)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    return k < mi->nparams ? mi->params[k].name : "";
}

/* ------------------------------------------------------------------ params.tsv, params.json */

int rp_write_params_tsv(const rp_report *rep, const rp_material *m, const out_dir *dir,
                            brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "params.tsv", err) != 0)
        return -1;
    fputs("# ", o.f);
    fr_write_tsv_text(o.f, m->name); /* escaped: a line break cannot end the comment */
    fprintf(o.f, ": metric %s, cutoff %g deg, scale %s, starts %d, brdffit %s; "
                 "ratio = error / published_error; p0..p3 per model (gltf: d = base_color, "
                 "s = specular_color): brdffit models; "
                 "the columns: docs/fit-record.md\n",
            rep->settings.metric, rep->settings.cutoff_deg, rep->settings.scale,
            rep->settings.starts, rep->settings.version);
    fr_write_tsv_header(o.f);
    rp_tsv_material(o.f, rep, m);
    return out_commit(&o, err);
}

/* params.json: the material, its failure record (or null), its fit records
 * and the records of its published parameters (fit_record.h). */
int rp_write_params_json(const rp_report *rep, const rp_material *m, const out_dir *dir,
                             brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "params.json", err) != 0)
        return -1;
    FILE *f = o.f;
    fputs("{\"material\":", f);
    json_string(f, m->name);
    fputs(",\"failure\":", f);
    if (m->failure)
        fr_write_json(f, m->failure);
    else
        fputs("null", f);
    for (int pass = 0; pass < 2; pass++) {
        fputs(pass ? ",\"published\":[" : ",\"fits\":[", f);
        int first = 1;
        for (int k = 0; k < rep->nmodels; k++) {
            const fit_record *r = pass ? m->published[k] : m->fit[k];
            if (!r)
                continue;
            if (!first)
                putc(',', f);
            first = 0;
            fr_write_json(f, r);
        }
        putc(']', f);
    }
    fputs("}\n", f);
    return out_commit(&o, err);
}

/* ------------------------------------------------------------------ a material's page */

/* The parameter table of a material. */
static void params_table(xml_writer *w, const rp_report *rep, const rp_material *m, int best)
{
    static const char *const head[] = { "d_r", "d_g", "d_b", "s_r", "s_g", "s_b",
                                        "p0", "p1", "p2", "p3" };
    char b[64];
    xml_open(w, "table");
    xml_open(w, "tr");
    rp_cell(w, "th", "name", "model");
    for (int i = 0; i < 10; i++)
        rp_cell(w, "th", NULL, head[i]);
    rp_cell(w, "th", NULL, "Error");
    if (rep->have_published) {
        rp_cell(w, "th", NULL, "published Error");
        rp_cell(w, "th", NULL, "ratio");
    }
    rp_cell(w, "th", NULL, "iterations");
    rp_cell(w, "th", NULL, "seconds");
    rp_cell(w, "th", "name", "on a bound");
    xml_close(w);
    for (int k = 0; k < rep->nmodels; k++) {
        const fit_record *f = m->fit[k], *p = m->published[k];
        if (!f)
            continue;
        xml_open(w, "tr");
        rp_cell(w, "td", "name", f->model);
        if (!fr_ok(f)) {
            xml_open(w, "td");
            xml_attr(w, "class", "failed");
            xml_attr(w, "colspan", "11");
            xml_textf(w, "failed: %s: %s", fr_status_text(f), f->message);
            xml_close(w);
        } else {
            for (int c = 0; c < 3; c++)
                rp_cell(w, "td", NULL, rp_num(b, sizeof b, "%.4g", f->params.d[c]));
            for (int c = 0; c < 3; c++)
                rp_cell(w, "td", NULL, rp_num(b, sizeof b, "%.4g", f->params.s[c]));
            for (int q = 0; q < BRDFFIT_MAX_LOBE_PARAMS; q++) {
                char t[96];
                if (q < f->nparams)
                    snprintf(t, sizeof t, "%s %.4g", param_label(rep->models[k], q), f->params.p[q]);
                else
                    snprintf(t, sizeof t, "-");
                rp_cell(w, "td", NULL, t);
            }
            snprintf(b, sizeof b, "%.5g%s", f->error, k == best ? " \xe2\x98\x85" : "");
            rp_cell(w, "td", k == best ? "best" : NULL, b);
        }
        if (rep->have_published) {
            rp_cell(w, "td", NULL, p && fr_ok(p) ? rp_num(b, sizeof b, "%.5g", p->error) : p ? "invalid" : "-");
            rp_cell(w, "td", NULL, rp_num(b, sizeof b, "%.3g", fr_ratio(f, p)));
        }
        snprintf(b, sizeof b, "%d", f->iterations);
        rp_cell(w, "td", NULL, f->has_counts ? b : "-");
        rp_cell(w, "td", NULL, rp_num(b, sizeof b, "%.2f", f->seconds));
        char bound[128] = "";
        if (f->has_counts)
            fr_at_bound_text(rep->models[k], f->at_bound, ", ", bound, sizeof bound);
        rp_cell(w, "td", "name", bound[0] ? bound : "-");
        xml_close(w);
    }
    xml_close(w);
}

/* The figures of one kind ("image", "plot") from the assets list. */
static void figures(xml_writer *w, const rp_material *m, const char *kind, const char *title)
{
    if (!m->assets)
        return;
    int any = 0;
    const char *p = m->assets->assets;
    while (*p) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        char line[1024], href[1024];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line - 1 ? n : sizeof line - 1), p);
        p += n + (end ? 1 : 0);
        char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
        if (!t2)
            continue;
        *t1 = *t2 = '\0';
        if (strcmp(line, kind) != 0)
            continue;
        if (!any++)
            xml_element_text(w, "h2", title);
        rp_url_segment(href, sizeof href, t1 + 1);
        if (strcmp(kind, "data") == 0) {
            xml_open(w, "p");
            rp_link(w, href, t1 + 1);
            xml_textf(w, " %s", t2 + 1);
            xml_close(w);
            continue;
        }
        xml_open(w, "figure");
        xml_open(w, "img");
        xml_attr(w, "src", href);
        xml_attr(w, "alt", t2 + 1);
        xml_close(w);
        xml_element_text(w, "figcaption", t2 + 1);
        xml_close(w);
    }
}

int rp_write_material_page(const rp_report *rep, const rp_material *m, int best,
                               const out_dir *dir, brdffit_error *err)
{
    out_file o;
    if (out_open(&o, dir, "index.html", err) != 0)
        return -1;
    xml_writer w;
    rp_html_begin(&w, o.f, m->name);
    xml_element_text(&w, "h1", m->name);
    xml_open(&w, "p");
    rp_link(&w, "../index.html", "all materials");
    xml_text(&w, " \xc2\xb7 ");
    rp_link(&w, "params.tsv", "params.tsv");
    xml_text(&w, " \xc2\xb7 ");
    rp_link(&w, "params.json", "params.json");
    xml_close(&w);
    xml_open(&w, "p");
    xml_attr(&w, "class", "note");
    if (m->id.size >= 0)
        xml_textf(&w, "table %s (%lld bytes, hash %s); metric %s, cutoff %g deg, scale %s",
                  m->id.path, m->id.size, m->id.hash, rep->settings.metric,
                  rep->settings.cutoff_deg, rep->settings.scale);
    else
        xml_textf(&w, "table %s", m->id.path);
    xml_close(&w);
    if (m->failure) {
        xml_open(&w, "p");
        xml_attr(&w, "class", "failed");
        xml_textf(&w, "Not fitted: %s", m->failure->message);
        xml_close(&w);
    } else {
        params_table(&w, rep, m, best);
        xml_open(&w, "p");
        xml_attr(&w, "class", "note");
        xml_text(&w, "d = Lambertian albedo (diffuse = d/pi), s = specular coefficient rho_s, "
                     "p0..p3 the lobe parameters in the paper's units (gltf, gltf-ext: "
                     "d = base_color, s = specular_color, linear sRGB; p in glTF's names); "
                     "Error = ngan-l2 (1/sr); "
                     "\xe2\x98\x85 the lowest Error");
        if (rep->have_published)
            xml_text(&w, "; published Error = the Error of the published parameters on this "
                         "table, ratio = Error / published Error (below 1: this fit is closer)");
        xml_close(&w);
        rp_gltf_section(&w, rep, m);
        figures(&w, m, "image", "Renders (reference and each model, same exposure)");
        figures(&w, m, "diff", "Differences from the reference");
        figures(&w, m, "plot", "Incidence-plane plots (cube root)");
        figures(&w, m, "data", "Data: linear images (OpenEXR, alpha = coverage), render settings");
    }
    rp_html_end(&w);
    return rp_finish(&o, &w, err);
}
