/* SPDX-License-Identifier: MIT */
/* html_material.c -- a material's files in the report: params.tsv,
 * params.json and its page, index.html (parameter table, renders, plots). */
#define _POSIX_C_SOURCE 200809L
#include "html_report.h"

#include <stdio.h>
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

/* The columns after the lobe parameters: Error, ratio (with published fits),
 * iterations, time, on a bound. */
static int tail_columns(const rp_report *rep)
{
    return rep->have_published ? 5 : 4;
}

/* The lobe-parameter columns: the most parameters of the report's models. */
static int lobe_columns(const rp_report *rep)
{
    int n = 0;
    for (int k = 0; k < rep->nmodels; k++)
        if (brdffit_model_get(rep->models[k])->nparams > n)
            n = brdffit_model_get(rep->models[k])->nparams;
    return n;
}

/* A header cell naming a parameter, which may break after an underscore
 * (specular_roughness): a long name does not widen the column of numbers
 * under it. */
static void name_cell(xml_writer *w, const char *name)
{
    xml_open(w, "th");
    xml_attr(w, "class", "wrap");
    for (const char *p = name; *p;) {
        const char *u = strchr(p, '_');
        size_t n = u ? (size_t)(u - p) + 1 : strlen(p);
        char part[64];
        snprintf(part, sizeof part, "%.*s", (int)(n < sizeof part ? n : sizeof part - 1), p);
        xml_text(w, part);
        if (u && u[1])
            xml_raw(w, "<wbr>");
        p += n;
    }
    xml_close(w);
}

/* A model's header row: its title, then d and s by channel and its lobe
 * parameters by name (the numbers under them carry no names). */
static void model_head(xml_writer *w, const rp_report *rep, int k)
{
    static const char *const ds[] = { "d_r", "d_g", "d_b", "s_r", "s_g", "s_b" };
    xml_open(w, "tr");
    xml_attr(w, "class", "mhead");
    rp_cell(w, "th", "name wrap", brdffit_model_get(rep->models[k])->title);
    for (int c = 0; c < 6; c++)
        rp_cell(w, "th", NULL, ds[c]);
    for (int q = 0; q < lobe_columns(rep); q++)
        name_cell(w, param_label(rep->models[k], q));
    rp_cell(w, "th", NULL, "Error");
    if (rep->have_published)
        rp_cell(w, "th", NULL, "ratio");
    rp_cell(w, "th", NULL, "iter.");
    rp_cell(w, "th", NULL, "time (s)");
    rp_cell(w, "th", "name", "at a bound");
    xml_close(w);
}

/* d, s and the lobe parameters of r, compact. */
static void param_cells(xml_writer *w, const rp_report *rep, const fit_record *r)
{
    char b[64];
    for (int c = 0; c < 3; c++)
        rp_cell(w, "td", NULL, rp_compact(b, sizeof b, 4, r->params.d[c]));
    for (int c = 0; c < 3; c++)
        rp_cell(w, "td", NULL, rp_compact(b, sizeof b, 4, r->params.s[c]));
    for (int q = 0; q < lobe_columns(rep); q++)
        rp_cell(w, "td", NULL, q < r->nparams ? rp_compact(b, sizeof b, 4, r->params.p[q]) : "");
}

/* The fitted row of model slot k (f: its record). */
static void fitted_row(xml_writer *w, const rp_report *rep, int k, const fit_record *f,
                       const fit_record *p, int best)
{
    char b[64], e[32];
    xml_open(w, "tr");
    rp_cell(w, "td", "name", "fitted");
    if (!fr_ok(f)) {
        xml_open(w, "td");
        xml_attr(w, "class", "failed");
        xml_attrf(w, "colspan", "%d", 6 + lobe_columns(rep) + tail_columns(rep));
        xml_textf(w, "failed: %s: %s", fr_status_text(f), f->message);
        xml_close(w);
        xml_close(w);
        return;
    }
    param_cells(w, rep, f);
    /* a no-break space keeps the star with its number */
    snprintf(b, sizeof b, "%s%s", rp_compact(e, sizeof e, 4, f->error),
             k == best ? "\xc2\xa0\xe2\x98\x85" : "");
    rp_cell(w, "td", k == best ? "best" : NULL, b);
    if (rep->have_published)
        rp_cell(w, "td", NULL, rp_compact(b, sizeof b, 3, fr_ratio(f, p)));
    snprintf(b, sizeof b, "%d", f->iterations);
    rp_cell(w, "td", NULL, f->has_counts ? b : "-");
    rp_cell(w, "td", NULL, rp_num(b, sizeof b, "%.2f", f->seconds));
    char bound[128] = "";
    if (f->has_counts)
        fr_at_bound_text(rep->models[k], f->at_bound, ", ", bound, sizeof bound);
    rp_cell(w, "td", "wrap", bound[0] ? bound : "-"); /* names, not numbers: may wrap */
    xml_close(w);
}

/* The published row under a model: the published parameters and their
 * Error on this table, or why they have none. */
static void published_row(xml_writer *w, const rp_report *rep, const fit_record *p)
{
    char b[64];
    xml_open(w, "tr");
    xml_attr(w, "class", "pub");
    rp_cell(w, "td", "name", "published");
    if (!p) {
        xml_open(w, "td");
        xml_attr(w, "class", "wrap");
        xml_attrf(w, "colspan", "%d", 6 + lobe_columns(rep) + tail_columns(rep));
        xml_text(w, "(no published parameters of this material and model)");
        xml_close(w);
        xml_close(w);
        return;
    }
    if (p->has_params)
        param_cells(w, rep, p);
    else
        for (int c = 0; c < 6 + lobe_columns(rep); c++)
            rp_cell(w, "td", NULL, "-");
    xml_open(w, "td");
    if (!fr_ok(p))
        xml_attr(w, "title", p->message);
    xml_text(w, fr_ok(p) ? rp_compact(b, sizeof b, 4, p->error) : "invalid");
    xml_close(w);
    for (int c = 1; c < tail_columns(rep); c++)
        rp_cell(w, "td", NULL, "");
    xml_close(w);
}

/* The parameter table of a material: per model a header row naming its
 * parameters, the fitted row and (with published fits) the published row. */
static void params_table(xml_writer *w, const rp_report *rep, const rp_material *m, int best)
{
    xml_open(w, "table");
    xml_attr(w, "class", "params");
    for (int k = 0; k < rep->nmodels; k++) {
        const fit_record *f = m->fit[k], *p = m->published[k];
        if (!f)
            continue;
        xml_open(w, "tbody");
        model_head(w, rep, k);
        fitted_row(w, rep, k, f, p, best);
        if (rep->have_published)
            published_row(w, rep, p);
        xml_close(w);
    }
    xml_close(w);
}

/* The figures of one kind ("image", "plot") from the assets list, under the
 * heading title (none: NULL) when there is one. */
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
        if (!any++ && title)
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

static void legend(xml_writer *w, const char *text)
{
    xml_open(w, "p");
    xml_attr(w, "class", "note");
    xml_text(w, text);
    xml_close(w);
}

/* The difference images and FLIP maps, each kind under its colour bar and a
 * legend saying what the colours mean. */
static void comparisons(xml_writer *w, const rp_material *m)
{
    figures(w, m, "diffbar",
            "Differences from the reference: lightness of each model's PNG minus the reference's");
    if (m->assets && strstr(m->assets->assets, "diffbar\t")) {
        legend(w, "Blue: the model is darker than the reference there; red: brighter; white: "
                  "the same. \xce\x94L* is CIE lightness (0 black, 100 white) of the PNGs "
                  "above; one scale for all models of this material (the 95th percentile of "
                  "|\xce\x94L*| over them, rounded up), so that their images compare. Black: "
                  "off the sphere. Reference pixels whose table lookups met a masked bin (the "
                  "thin arc where the rim light's terminator crosses bins the table leaves "
                  "unmeasured) take the mean of their measured neighbours within 2 pixels, so a "
                  "faint trace of the arc can remain; any with none would be grey.");
    }
    figures(w, m, "diff", NULL);
    figures(w, m, "flipbar",
            "\xea\x9f\xbbLIP: the difference a viewer sees, per pixel (the image error is its mean)");
    if (m->assets && strstr(m->assets->assets, "flipbar\t"))
        legend(w, "\xea\x9f\xbbLIP (Andersson et al. 2020; NVIDIA's definition, LDR) of each "
                  "model's PNG against the reference's, viewed at 67 pixels per degree (a 0.7 m "
                  "wide 4K display at 0.7 m); black: no visible difference, yellow-white: the "
                  "most. Its mean over the image is the image error in renders.json; the same "
                  "number as NVIDIA's flip tool on these PNGs.");
    figures(w, m, "flip", NULL);
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
    rp_scale_warning(&w, rep);
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
                     "then the lobe parameters by name, in the paper's units (gltf, gltf-ext, "
                     "openpbr: d = base_color, s = specular_color, linear sRGB; the parameters in "
                     "glTF's and OpenPBR's names; brdffit models lists them); Error = ngan-l2 (1/sr); "
                     "\xe2\x98\x85 the lowest Error");
        if (rep->have_published)
            xml_text(&w, "; published = the published parameters and their Error, computed on "
                         "this table with this report's settings; ratio = Error / published "
                         "Error (below 1: this fit is closer)");
        xml_close(&w);
        rp_export_sections(&w, rep, m);
        rp_mitsuba_section(&w, rep, m);
        rp_energy_section(&w, rep, m);
        figures(&w, m, "image", "Renders (reference and each model, same exposure)");
        comparisons(&w, m);
        figures(&w, m, "plot", "Incidence-plane plots (cube root)");
        figures(&w, m, "data", "Data: linear images (OpenEXR, alpha = coverage), render settings");
    }
    rp_html_end(&w);
    return rp_finish(&o, &w, err);
}
