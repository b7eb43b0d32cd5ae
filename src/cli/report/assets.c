/* SPDX-License-Identifier: MIT */
/* assets.c -- the renders and plots of one material for the batch report,
 * through rf_write_material (render_files.h), listed for its page. */
#include "batch.h"
#include "render_files.h"

#include <stdlib.h>
#include <string.h>

static int assets_write(const out_dir *dir, const char *material, const brdffit_table *table,
                        const rf_fit *rf, int n, const rf_settings *s, rf_result *res, char *list,
                        size_t len, brdffit_error *err)
{
    if (rf_write_material_at(dir, material, table, rf, n, s, res, err) != 0)
        return -1;
    size_t used = 0;
    list[0] = '\0';
    for (int i = 0; i < res->nfiles; i++) {
        const rf_file *f = &res->files[i];
        size_t fl = strlen(f->file);
        const char *kind = f->kind == RF_PLOT ? "plot"
                         : f->kind == RF_DATA ? "data"
                         : fl > 9 && strcmp(f->file + fl - 9, "-diff.png") == 0 ? "diff"
                         : fl > 9 && strcmp(f->file + fl - 9, "-flip.png") == 0 ? "flip"
                         : strcmp(f->file, "diff-scale.svg") == 0 ? "diffbar"
                         : strcmp(f->file, "flip-scale.svg") == 0 ? "flipbar"
                                                                  : "image";
        int w = snprintf(list + used, len - used, "%s\t%s\t%s\n", kind, f->file, f->caption);
        if (w < 0 || (size_t)w >= len - used) {
            err->status = BRDFFIT_E_INVALID_ARGUMENT;
            snprintf(err->message, sizeof err->message, "%s: too many render files to list", material);
            return -1;
        }
        used += (size_t)w;
    }
    return 0;
}

int batch_assets(const out_dir *dir, const char *material, const brdffit_table *table,
                 const brdffit_sample_options *sample, const fit_record *const *fits, int nfits,
                 int render, int plot, char *list, size_t len, brdffit_error *err)
{
    rf_fit rf[RF_MAX_FITS];
    int n = nfits < RF_MAX_FITS ? nfits : RF_MAX_FITS;
    for (int i = 0; i < n; i++) {
        memset(&rf[i], 0, sizeof rf[i]);
        if (brdffit_model_from_name(fits[i]->model, &rf[i].model, NULL) != BRDFFIT_OK) {
            err->status = BRDFFIT_E_UNKNOWN_MODEL;
            snprintf(err->message, sizeof err->message, "unknown model '%s'", fits[i]->model);
            return -1;
        }
        rf[i].params = fits[i]->params;
        rf[i].error = fits[i]->error;
    }
    rf_settings s;
    rf_settings_default(&s, sample->scale);
    s.render = render;
    s.plot = plot;
    rf_result *res = calloc(1, sizeof *res); /* large: not on the stack */
    if (!res) {
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "%s: out of memory for the renders", material);
        return -1;
    }
    int rc = assets_write(dir, material, table, rf, n, &s, res, list, len, err);
    free(res);
    return rc;
}
