/* SPDX-License-Identifier: MIT */
/* assets.c -- the renders and plots of one material for the batch report. */
#include "batch.h"

#include <string.h>

int batch_assets(const char *dir, const char *material, const brdffit_table *table,
                 const brdffit_sample_options *sample, const bj_record *const *fits, int nfits,
                 int render, int plot, char *list, size_t len, brdffit_error *err)
{
    (void)dir; (void)material; (void)table; (void)sample; (void)fits; (void)nfits;
    (void)render; (void)plot; (void)err;
    if (len)
        list[0] = '\0';
    return 0;
}
