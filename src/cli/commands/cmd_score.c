/* SPDX-License-Identifier: MIT */
/* cmd_score.c -- `brdffit score TABLE --model M --params d_r,d_g,d_b,s_r,s_g,s_b,p0[,p1,p2,p3]`
 * or `--fits FITS.tsv`: the Error of given parameters on a table, as a
 * researcher checks a published number.  With --fits, every row of the
 * table's material (named by its file) is scored, or those of --model. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const cli_help_block *cli_score_help(void)
{
    static const cli_help_item items[] = {
        { "--model M", "the model of --params; with --fits, only these models" },
        { "--params d_r,d_g,d_b,s_r,s_g,s_b,p0[,p1,p2,p3]", "the parameters to score, in the\n"
                                                         "paper's units (gltf, gltf-ext: base colour,\n"
                                                         "specular colour, metallic,roughness,ior,specular)" },
        { "--fits FILE", "score the rows of this material (named by TABLE's file)\n"
                         "in an ngan2005-fits.tsv-style TSV; a file stating\n"
                         "'# scale: S' needs --scale S" },
        { "--allow-scale-mismatch", "score a --fits file of another scale anyway" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK(
        "Options of score", "and the options of fit: --scale, --cutoff, --backend, --device",
        items);
    return &block;
}

/* "0.1,0.2,..." into p for the model: 6 + nparams numbers. */
static int parse_params(const char *v, brdffit_model model, brdffit_params *p)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    double x[6 + BRDFFIT_MAX_LOBE_PARAMS];
    int n = 0;
    const char *s = v;
    for (;;) {
        size_t len = strcspn(s, ",");
        char one[64];
        if (len == 0 || len >= sizeof one || n >= 6 + BRDFFIT_MAX_LOBE_PARAMS)
            return -1;
        memcpy(one, s, len);
        one[len] = '\0';
        if (cli_parse_double(one, &x[n++]) != 0)
            return -1;
        if (s[len] == '\0')
            break;
        s += len + 1;
    }
    if (n != 6 + mi->nparams)
        return -1;
    memset(p, 0, sizeof *p);
    memcpy(p->d, x, sizeof p->d);
    memcpy(p->s, x + 3, sizeof p->s);
    memcpy(p->p, x + 6, (size_t)mi->nparams * sizeof p->p[0]);
    return 0;
}

typedef struct score_job {
    brdffit_context *ctx;
    const brdffit_samples *s;
    int failures;
    brdffit_metric metric; /* --metric: the Error printed */
} score_job;

/* The Error of p, printed; origin names where p came from ("--params",
 * "--fits FILE") in a message about it.  Nothing is fitted: an Error that is
 * not finite (a data pass summing to inf) is said as such, not as a failed fit. */
static void score_one(score_job *J, brdffit_model model, const brdffit_params *p,
                      const char *label, const char *origin)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    brdffit_error err;
    memset(&err, 0, sizeof err);
    double e = NAN;
    brdffit_status st = brdffit_params_check(model, p, &err);
    int checked = st == BRDFFIT_OK;
    if (checked) {
        int note = kernel_note_begin(stderr, J->ctx, model);
        st = brdffit_error_metric(J->ctx, J->s, model, p, J->metric, &e, &err);
        kernel_note_end(stderr, note, J->ctx, model);
    }
    if (checked && (st == BRDFFIT_E_FIT_FAILED || (st == BRDFFIT_OK && !isfinite(e)))) {
        J->failures++;
        printf("%-18s -  (Error not finite)\n", mi->name);
        cli_error("%s: %s: the Error of these parameters is not a finite number (the model's "
                  "values or their squares overflow a double: d, s or the lobe too large)",
                  origin, mi->name);
        return;
    }
    if (st != BRDFFIT_OK) {
        J->failures++;
        printf("%-18s -  (%s)\n", mi->name, brdffit_strerror(st));
        cli_error("%s: %s", origin, err.message); /* the message names the model */
        return;
    }
    printf("%-18s %.10g%s%s\n", mi->name, e, label ? "  " : "", label ? label : "");
}

typedef struct score_args {
    cli_options common;
    const char *params;
    const char *fits;
    int model_given;   /* --model was on the command line */
    int allow_scale_mismatch;
} score_args;

static int parse_score(int argc, char **argv, score_args *a)
{
    memset(a, 0, sizeof *a);
    char **rest = malloc((size_t)(argc + 1) * sizeof *rest);
    if (!rest)
        return CLI_FAILED;
    int nrest = 0, rc = CLI_OK;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        const char **dst = NULL;
        size_t n = 0;
        if (strncmp(argv[i], "--params", 8) == 0 && (argv[i][8] == '\0' || argv[i][8] == '='))
            dst = &a->params, n = 8;
        else if (strncmp(argv[i], "--fits", 6) == 0 && (argv[i][6] == '\0' || argv[i][6] == '='))
            dst = &a->fits, n = 6;
        if (strncmp(argv[i], "--model", 7) == 0 && (argv[i][7] == '\0' || argv[i][7] == '='))
            a->model_given = 1;
        if (strcmp(argv[i], "--allow-scale-mismatch") == 0) {
            a->allow_scale_mismatch = 1;
            continue;
        }
        if (!dst) {
            rest[nrest++] = argv[i];
            continue;
        }
        const char *opt = argv[i];
        const char *v = opt[n] == '=' ? opt + n + 1 : (i + 1 < argc ? argv[++i] : NULL);
        if (!v || !*v)
            rc = cli_usage_error("%.*s needs a value", (int)n, opt);
        *dst = v;
    }
    if (rc == CLI_OK)
        rc = cli_parse_options(nrest, rest, &a->common);
    free(rest);
    if (rc != CLI_OK)
        return rc;
    if (a->common.nfiles != 1)
        return cli_usage_error("score needs one table (got %d)", a->common.nfiles);
    if (a->common.all_metrics)
        return cli_usage_error("--metric all is batch's; score takes one of ngan-l2, log, "
                               "cube-root");
    if (!a->params == !a->fits)
        return cli_usage_error("score needs --params P,... (with one --model) or --fits FILE");
    if (a->params && (!a->model_given || a->common.nmodels != 1))
        return cli_usage_error("--params needs exactly one --model");
    return CLI_OK;
}

static int score_fits(score_job *J, const score_args *a, const char *material)
{
    pub_table t;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (pub_read(a->fits, &t, &err) != 0) {
        cli_error("--fits: %s", err.message);
        return CLI_USAGE;
    }
    char why[BRDFFIT_MESSAGE_MAX];
    if (pub_scale_mismatch(&t, a->common.sample.scale, why, sizeof why)) {
        if (!a->allow_scale_mismatch) {
            cli_error("--fits: %s; %s", why, pub_scale_advice(&t));
            pub_free(&t);
            return CLI_USAGE;
        }
        cli_error("warning: --fits: %s: %s", why, PUB_SCALE_NOTE);
    }
    int found = 0;
    char origin[BJ_PATH_MAX + 16];
    snprintf(origin, sizeof origin, "--fits %s", a->fits);
    for (int k = 0; k < a->common.nmodels; k++) {
        const pub_row *r = pub_find(&t, material, a->common.models[k]);
        if (!r)
            continue;
        found++;
        score_one(J, r->model, &r->params, NULL, origin);
    }
    pub_free(&t);
    if (!found) {
        cli_error("%s has no row for material '%s'%s", a->fits, material,
                  a->model_given ? " and the models asked" : "");
        return CLI_FAILED;
    }
    return J->failures ? CLI_FAILED : CLI_OK;
}

static int score_run(const score_args *a)
{
    const char *path = a->common.files[0];
    char material[BJ_NAME_MAX];
    cli_material_name(path, material, sizeof material);
    brdffit_params p;
    char names[512];
    if (a->params && parse_params(a->params, a->common.models[0], &p) != 0)
        return cli_usage_error("--params '%s': expected %d comma-separated numbers for %s (%s)",
                               a->params, 6 + brdffit_model_get(a->common.models[0])->nparams,
                               brdffit_model_get(a->common.models[0])->name,
                               cli_param_list(a->common.models[0], ',', names, sizeof names));
    brdffit_error err;
    memset(&err, 0, sizeof err);
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    score_job J = { NULL, NULL, 0, (brdffit_metric)a->common.fit.metric };
    int rc = CLI_FAILED;
    if (brdffit_table_read(path, &t, &err) != BRDFFIT_OK ||
        brdffit_samples_create(t, &a->common.sample, &s, &err) != BRDFFIT_OK ||
        brdffit_context_create(&a->common.context, &J.ctx, &err) != BRDFFIT_OK) {
        fputs("brdffit: ", stderr);
        plain_string(stderr, err.message);
        fputc('\n', stderr);
        goto done;
    }
    J.s = s;
    printf("# %s: metric %s, cutoff %g deg, scale %s, %zu samples\n", material,
           brdffit_metric_get_name(J.metric), a->common.sample.cutoff_deg,
           brdffit_scale_name(a->common.sample.scale), brdffit_samples_count(s));
    if (a->params) {
        score_one(&J, a->common.models[0], &p, NULL, "--params");
        rc = J.failures ? CLI_FAILED : CLI_OK;
    } else {
        rc = score_fits(&J, a, material);
    }
done:
    brdffit_context_free(J.ctx);
    brdffit_samples_free(s);
    brdffit_table_free(t);
    return rc;
}

int cmd_score(int argc, char **argv)
{
    score_args a;
    int rc = parse_score(argc, argv, &a);
    if (rc == CLI_OK)
        rc = score_run(&a);
    cli_options_free(&a.common);
    return rc;
}
