/* SPDX-License-Identifier: MIT */
/* fit_record_tsv.c -- the fit record's TSV: its header and rows, the ratio
 * to the published Error; docs/fit-record.md describes the columns. */
#define _POSIX_C_SOURCE 200809L
#include "fit_record.h"
#include "fit_record_parts.h"
#include "batch.h"
#include "cli.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------------ TSV */

void fr_write_tsv_text(FILE *f, const char *s)
{
    if (!s || !s[0]) {
        putc('-', f);
        return;
    }
    if (strcmp(s, "-") == 0) {
        fputs("\\-", f);
        return;
    }
    for (const char *p = s; *p; p++) {
        const char *e = *p == '\\' ? "\\\\" : *p == '\t' ? "\\t" : *p == '\n' ? "\\n"
                      : *p == '\r' ? "\\r" : NULL;
        if (e)
            fputs(e, f);
        else
            putc(*p, f);
    }
}

static void tsv_num(FILE *f, const char *fmt, double x)
{
    putc('\t', f);
    if (isfinite(x))
        fprintf(f, fmt, x);
    else
        putc('-', f);
}

double fr_ratio(const fit_record *fit, const fit_record *pub)
{
    if (!fit || !pub || !fr_ok(fit) || !fr_ok(pub) || !(pub->error > 0))
        return NAN;
    return fit->error / pub->error;
}

void fr_write_tsv_header(FILE *f)
{
    fputs("material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\tp3\terror\tstatus\tstatus_code"
          "\titerations\tpasses\tcminpack_info\tseconds\tsamples\tat_bound\tflags\tbackend"
          "\tpublished_error\tratio\tfile\tsize\thash\tmetric\terror_ngan_l2\terror_log"
          "\terror_cube_root\tmessage",
          f);
    fr_albedo_tsv_header(f);
    putc('\n', f);
}

void fr_write_tsv_row(FILE *f, const fit_record *r, const fit_record *pub)
{
    fr_write_tsv_text(f, r->material);
    putc('\t', f);
    fr_write_tsv_text(f, r->model);
    for (int c = 0; c < 3; c++)
        tsv_num(f, "%.10g", r->has_params ? r->params.d[c] : NAN);
    for (int c = 0; c < 3; c++)
        tsv_num(f, "%.10g", r->has_params ? r->params.s[c] : NAN);
    for (int k = 0; k < BRDFFIT_MAX_LOBE_PARAMS; k++) {
        if (r->has_params && k >= r->nparams)
            putc('\t', f); /* the model has fewer lobe parameters */
        else
            tsv_num(f, "%.10g", r->has_params ? r->params.p[k] : NAN);
    }
    tsv_num(f, "%.10g", r->error);
    fprintf(f, "\t%s\t%d", fr_status_text(r), (int)r->status);
    if (r->has_counts)
        fprintf(f, "\t%d\t%d\t%d", r->iterations, r->passes, r->cminpack_info);
    else
        fputs("\t-\t-\t-", f);
    tsv_num(f, "%.3f", r->seconds);
    if (r->samples >= 0)
        fprintf(f, "\t%lld\t", r->samples);
    else
        fputs("\t-\t", f);
    brdffit_model model;
    if (r->has_counts) {
        char b[128];
        fputs(fr_at_bound_text(fr_record_model(r, &model) ? model : BRDFFIT_WARD,
                               fr_record_model(r, &model) ? r->at_bound : r->at_bound & ~(unsigned)BRDFFIT_AT_BOUND_LOBE, ",", b,
                               sizeof b),
              f);
        fprintf(f, "\t%s", r->flags & BRDFFIT_FIT_LIMIT ? "limit" : "");
    } else {
        fputs("-\t-", f);
    }
    putc('\t', f);
    fr_write_tsv_text(f, r->backend);
    tsv_num(f, "%.10g", pub && fr_ok(pub) ? pub->error : NAN);
    tsv_num(f, "%.6g", fr_ratio(r, pub));
    putc('\t', f);
    fr_write_tsv_text(f, r->id.path);
    if (r->id.size >= 0)
        fprintf(f, "\t%lld\t", r->id.size);
    else
        fputs("\t-\t", f);
    fr_write_tsv_text(f, r->id.hash);
    putc('\t', f);
    fr_write_tsv_text(f, r->kind == FR_FIT ? r->settings.metric : NULL);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
        tsv_num(f, "%.10g", r->errors[m]);
    putc('\t', f);
    if (r->message[0]) /* "" when the record did not fail */
        fr_write_tsv_text(f, r->message);
    fr_albedo_tsv_row(f, r);
    putc('\n', f);
}
