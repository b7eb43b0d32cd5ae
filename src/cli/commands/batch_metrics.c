/* SPDX-License-Identifier: MIT */
/* batch_metrics.c -- `batch --metric all`'s DIR/index.html: the model table
 * under each metric side by side (each model's median Error and on how many
 * materials it is best, for fits made under that metric), the three
 * headline figures, and links to the three reports (docs/metrics.md). */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int batch_metrics_page(const char *out, const metric_summary *sums);

static void table(FILE *f, const metric_summary *sums)
{
    fputs("<table>\n<tr><th rowspan=\"2\">model</th>", f);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
        fprintf(f, "<th colspan=\"2\"><a href=\"%s/index.html\">%s</a></th>",
                brdffit_metric_get_name((brdffit_metric)m),
                brdffit_metric_get_name((brdffit_metric)m));
    fputs("</tr>\n<tr>", f);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
        fputs("<th>median Error</th><th>best on</th>", f);
    fputs("</tr>\n", f);
    for (int k = 0; k < sums[0].nmodels; k++) {
        fprintf(f, "<tr><td>%s</td>", brdffit_model_get(sums[0].models[k])->name);
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
            const metric_summary *S = &sums[m];
            int here = k < S->nmodels && S->models[k] == sums[0].models[k];
            if (here && isfinite(S->median[k]))
                fprintf(f, "<td%s>%.4g</td><td>%d</td>",
                        S->sort_model == k ? " class=\"best\"" : "", S->median[k], S->nbest[k]);
            else
                fputs("<td>-</td><td>-</td>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("</table>\n", f);
}

int batch_metrics_page(const char *out, const metric_summary *sums)
{
    brdffit_error err;
    out_dir dir;
    out_file o;
    memset(&err, 0, sizeof err);
    if (od_open(&dir, out, 0, &err) != 0) {
        cli_error("%s", err.message);
        return -1;
    }
    int rc = out_open(&o, &dir, "index.html", &err);
    if (rc == 0) {
        FILE *f = o.f;
        fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
              "<title>brdffit: the models under each metric</title>\n"
              "<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
              "td,th{border:1px solid #bbb;padding:0.2em 0.6em;text-align:right}"
              "td:first-child{text-align:left}.best{font-weight:bold}</style>\n</head>\n<body>\n"
              "<h1>The models under each metric</h1>\n", f);
        fprintf(f, "<p>%d material%s; each metric's fits minimise that metric (docs/metrics.md). "
                   "Per model its median Error and on how many materials it is the best; the "
                   "lowest median of each metric marked. Each metric's report: ",
                sums[0].nmaterials, sums[0].nmaterials == 1 ? "" : "s");
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
            const char *name = brdffit_metric_get_name((brdffit_metric)m);
            fprintf(f, "%s<a href=\"%s/index.html\">%s</a>", m ? ", " : "", name, name);
        }
        fputs(".</p>\n", f);
        table(f, sums);
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
            const char *name = brdffit_metric_get_name((brdffit_metric)m);
            fprintf(f, "<h2>%s</h2>\n<p><img src=\"%s/headline.svg\" alt=\"the headline figure "
                       "under %s\"></p>\n", name, name, name);
        }
        fputs("</body>\n</html>\n", f);
        rc = out_commit(&o, &err);
    }
    if (rc != 0)
        cli_error("%s", err.message);
    od_close(&dir);
    return rc;
}
