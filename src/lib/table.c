/* SPDX-License-Identifier: MIT */
/* table.c -- the MERL table object: create, free, and its stored values. */
#include "internal.h"
#include "grid.h"

#include <stdlib.h>
#include <string.h>

brdffit_status brdffit_table_create(brdffit_table **out, brdffit_error *err)
{
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_create: out is NULL");
    *out = NULL;
    brdffit_table *t = bf_alloc_aligned(sizeof *t); /* 35 MB: huge pages */
    if (!t)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_table_create: cannot allocate %zu bytes",
                       sizeof *t);
    memset(t, 0, sizeof *t);
    *out = t;
    bf_ok(err);
    return BRDFFIT_OK;
}

void brdffit_table_free(brdffit_table *table)
{
    bf_free_aligned(table);
}

double *brdffit_table_values(brdffit_table *table)
{
    return table ? table->v : NULL;
}

const double *brdffit_table_values_const(const brdffit_table *table)
{
    return table ? table->v : NULL;
}
