/* SPDX-License-Identifier: MIT */
/* html_mitsuba.c -- a material's fits as Mitsuba 3 scenes in the report:
 * MATERIAL-MODEL.xml for each fit that succeeded (the scene `brdffit
 * export --format mitsuba` writes, with its default scene: render's sphere
 * and default lights), and a line on the page linking them. */
#include "html_report.h"

#include "export.h"

#include <stdio.h>
#include <string.h>

/* Fit k of m as a scene (its name MATERIAL-MODEL into name): 1, or 0 when it
 * is not an ok fit with parameters the model takes. */
static int fit_of(const rp_report *rep, const rp_material *m, int k, char *name, size_t len)
{
    const fit_record *f = m->fit[k];
    char why[BRDFFIT_MESSAGE_MAX];
    if (!f || !fr_ok(f) || mitsuba_fit_check(f, why, sizeof why) != NULL)
        return 0;
    snprintf(name, len, "%s-%s", m->name, brdffit_model_get(rep->models[k])->name);
    return 1;
}

int rp_write_mitsuba_files(const rp_report *rep, const rp_material *m, const out_dir *dir,
                           brdffit_error *err)
{
    mitsuba_scene sc;
    mitsuba_scene_default(&sc);
    for (int k = 0; k < rep->nmodels; k++) {
        char name[BJ_NAME_MAX + 32], file[BJ_NAME_MAX + 40];
        if (!fit_of(rep, m, k, name, sizeof name))
            continue;
        snprintf(file, sizeof file, "%s.xml", name);
        out_file o;
        if (out_open(&o, dir, file, err) != 0)
            return -1;
        mitsuba_write(o.f, m->fit[k], name, &sc);
        if (out_commit(&o, err) != 0)
            return -1;
    }
    return 0;
}

void rp_mitsuba_section(xml_writer *w, const rp_report *rep, const rp_material *m)
{
    int any = 0;
    for (int k = 0; k < rep->nmodels; k++) {
        char name[BJ_NAME_MAX + 32], href[BJ_NAME_MAX * 3 + 64], file[BJ_NAME_MAX + 40];
        if (!fit_of(rep, m, k, name, sizeof name))
            continue;
        if (!any++) {
            xml_element_text(w, "h2", "For a renderer: Mitsuba 3");
            xml_open(w, "p");
            xml_attr(w, "class", "note");
            xml_text(w, "Each fit on the render sphere as a Mitsuba 3 scene, rendered with the "
                        "brdffit Python package's plugin (docs/mitsuba.md): ");
        } else {
            xml_text(w, ", ");
        }
        snprintf(file, sizeof file, "%s.xml", name);
        rp_url_segment(href, sizeof href, file);
        rp_link(w, href, file);
    }
    if (any)
        xml_close(w);
}
