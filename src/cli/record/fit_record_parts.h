/* SPDX-License-Identifier: MIT */
/* fit_record_parts.h -- what fit_record.c, fit_record_json.c and
 * fit_record_tsv.c share. */
#ifndef BRDFFIT_FIT_RECORD_PARTS_H
#define BRDFFIT_FIT_RECORD_PARTS_H

#include "fit_record.h"

/* The bit of the parameter named name (len bytes) of model, or 0. */
unsigned fr_bound_bit(brdffit_model model, const char *name, size_t len);
/* The model the record names: 1 when it is one of brdffit's, with *m set. */
int fr_record_model(const fit_record *r, brdffit_model *m);

#endif
