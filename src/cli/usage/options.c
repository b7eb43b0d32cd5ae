/* SPDX-License-Identifier: MIT */
/* options.c -- the options of `fit` and `demo`: parsing them into a
 * cli_options, and their block of the --help text. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

const cli_help_block *cli_options_help(void)
{
    /* the models and their starts come from the registry */
    static char model_text[640], starts_text[320];
    static cli_help_item items[] = {
        { "--model NAME[,NAME...]|all", model_text },
        { "--scale standard|flat", "channel scale of the stored values (default standard,\n"
                                   "(1, 1.15, 1.66)/1500; flat = 1/1500, as Ngan et al.)" },
        { "--cutoff DEG", "fit directions with theta_i, theta_o <= DEG, in (0, 90]\n(default 80)" },
        { "--starts N", starts_text },
        { "--metric NAME", "the Error each fit minimises: ngan-l2 (default, the\n"
                           "paper's), log or cube-root (docs/metrics.md); a fit under\n"
                           "log or cube-root reports its Error under all three.\n"
                           "batch: also all (the three in turn, into OUT/ngan-l2,\n"
                           "OUT/log, OUT/cube-root; implies --errors all)" },
        { "--errors metric|all", "all: every fit's Error under every metric (an ngan-l2\n"
                                 "fit: one more pass over the samples); metric\n"
                                 "(default): an ngan-l2 fit's under ngan-l2 alone" },
        { "--backend auto|opencl|host", "where the data passes run (default auto: OpenCL when a\n"
                                        "device is found, else C on the host)" },
        { "--device SPEC", "OpenCL device, PLATFORM:DEVICE by index or name\n"
                           "substring (default $BRDFFIT_DEVICE, else PoCL's CPU)" },
        { "--json", "one JSON object per fit per line (JSON Lines)" },
        { "--no-read-ahead", "read each table only when its fits begin (default:\n"
                             "the next one is read in a thread meanwhile, which\n"
                             "saves wall time but shares the cores with the fits,\n"
                             "so that the fits beside it take longer)" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK("Options of fit and demo", NULL, items);
    char names[512], starts[256];
    cli_model_names(names, sizeof names);
    char *wrap = strchr(names + strlen(names) / 2, ' '); /* two lines, at a ", " */
    if (wrap)
        *wrap = '\n';
    char extra[128] = ""; /* the models fitted only when named (registry: in_default_set) */
    for (int k = 0; k < brdffit_model_count(); k++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)k);
        size_t used = strlen(extra);
        if (!mi->in_default_set)
            snprintf(extra + used, sizeof extra - used, "%s%s", used ? ", " : "", mi->name);
    }
    snprintf(model_text, sizeof model_text,
             "models to fit (repeatable; any case; default all but\n"
             "%s: their fits take longer):\n%s", extra, names);
    snprintf(starts_text, sizeof starts_text,
             "starting points screened per model, 1..1000\n(default: the model's own, %s)",
             cli_default_starts(starts, sizeof starts));
    return &block;
}

/* ------------------------------------------------------------------ one option each */

static void add_model(cli_options *o, brdffit_model m)
{
    for (int i = 0; i < o->nmodels; i++)
        if (o->models[i] == m)
            return;
    o->models[o->nmodels++] = m;
}

static int add_model_named(cli_options *o, const char *one)
{
    char names[512];
    brdffit_model m;
    if (strcasecmp(one, "all") == 0) { /* model names are matched in any case */
        for (int k = 0; k < brdffit_model_count(); k++)
            add_model(o, (brdffit_model)k);
    } else if (brdffit_model_from_name(one, &m, NULL) == BRDFFIT_OK) {
        add_model(o, m);
    } else {
        return cli_usage_error("unknown model '%s' (valid: all, %s)", one,
                               cli_model_names(names, sizeof names));
    }
    return CLI_OK;
}

/* --model "ward,cook-torrance" or "all". */
static int set_models(cli_options *o, const char *value)
{
    char names[512];
    if (!*value)
        return cli_usage_error("--model needs a model name (one of: all, %s)",
                               cli_model_names(names, sizeof names));
    const char *p = value;
    for (;;) {
        size_t n = strcspn(p, ",");
        char one[64];
        if (n == 0 || n >= sizeof one)
            return cli_usage_error("unknown model '%.*s' in --model %s (valid: all, %s)",
                                   (int)(n < 200 ? n : 200), p, value,
                                   cli_model_names(names, sizeof names));
        memcpy(one, p, n);
        one[n] = '\0';
        int rc = add_model_named(o, one);
        if (rc != CLI_OK)
            return rc;
        if (p[n] == '\0')
            return CLI_OK;
        p += n + 1;
    }
}

static int set_scale(cli_options *o, const char *v)
{
    if (brdffit_scale_from_name(v, &o->sample.scale, NULL) != BRDFFIT_OK)
        return cli_usage_error("--scale '%s': expected standard or flat", v);
    return CLI_OK;
}

static int set_cutoff(cli_options *o, const char *v)
{
    double c;
    if (cli_parse_double(v, &c) != 0 || !(c > 0) || !(c <= 90))
        return cli_usage_error("--cutoff '%s': expected a number of degrees in (0, 90]", v);
    o->sample.cutoff_deg = c;
    return CLI_OK;
}

static int set_starts(cli_options *o, const char *v)
{
    if (cli_parse_int(v, 1, 1000, &o->fit.starts) != 0)
        return cli_usage_error("--starts '%s': expected an integer in [1, 1000]", v);
    return CLI_OK;
}

static int set_metric(cli_options *o, const char *v)
{
    brdffit_metric m;
    if (strcmp(v, "all") == 0) { /* batch alone takes it (cmd_batch.c); fit, score refuse */
        o->all_metrics = 1;
        o->fit.metric = BRDFFIT_METRIC_NGAN_L2;
        o->fit.all_errors = 1; /* each fit's Error under the three, for the side by side */
        return CLI_OK;
    }
    if (brdffit_metric_from_name(v, &m, NULL) != BRDFFIT_OK)
        return cli_usage_error("--metric '%s': expected ngan-l2, log or cube-root", v);
    o->fit.metric = (int)m;
    o->all_metrics = 0;
    return CLI_OK;
}

/* --errors all: every fit's Error under every metric (one more pass over
 * the samples for an ngan-l2 fit); metric (default): under its own, and
 * ngan-l2's. */
static int set_errors(cli_options *o, const char *v)
{
    if (strcmp(v, "all") != 0 && strcmp(v, "metric") != 0)
        return cli_usage_error("--errors '%s': expected all or metric", v);
    o->fit.all_errors = strcmp(v, "all") == 0;
    return CLI_OK;
}

static int set_backend(cli_options *o, const char *v)
{
    static const struct { const char *name; brdffit_backend backend; } backends[] = {
        { "auto", BRDFFIT_BACKEND_AUTO },
        { "opencl", BRDFFIT_BACKEND_OPENCL },
        { "host", BRDFFIT_BACKEND_HOST },
    };
    for (size_t k = 0; k < sizeof backends / sizeof backends[0]; k++)
        if (strcmp(v, backends[k].name) == 0) {
            o->context.backend = backends[k].backend;
            return CLI_OK;
        }
    return cli_usage_error("--backend '%s': expected auto, opencl or host", v);
}

static int set_device(cli_options *o, const char *v)
{
    if (!*v)
        return cli_usage_error("--device needs a PLATFORM:DEVICE specification");
    o->context.device = v;
    return CLI_OK;
}

/* The options that take a value. */
static const struct {
    const char *name;
    int (*set)(cli_options *o, const char *value);
} with_value[] = {
    { "--model", set_models },   { "--scale", set_scale },     { "--cutoff", set_cutoff },
    { "--starts", set_starts },  { "--backend", set_backend }, { "--device", set_device },
    { "--metric", set_metric },  { "--errors", set_errors },
};

/* ------------------------------------------------------------------ the parser */

static int options_init(cli_options *o, int argc)
{
    memset(o, 0, sizeof *o);
    brdffit_sample_options_default(&o->sample);
    brdffit_fit_options_default(&o->fit);
    brdffit_context_options_default(&o->context);
    o->read_ahead = 1;
    o->files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *o->files);
    if (!o->files) {
        fputs("brdffit: out of memory\n", stderr);
        return CLI_FAILED;
    }
    return CLI_OK;
}

/* argv[*i] is --name VALUE or --name=VALUE: set it (and step over VALUE). */
static int parse_valued(cli_options *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    const char *eq = strchr(a, '=');
    size_t nlen = eq ? (size_t)(eq - a) : strlen(a);
    for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; k++) {
        const char *name = with_value[k].name;
        if (strlen(name) != nlen || strncmp(a, name, nlen) != 0)
            continue;
        if (eq)
            return with_value[k].set(o, eq + 1);
        if (*i + 1 >= argc)
            return cli_usage_error("%s needs a value", name);
        return with_value[k].set(o, argv[++*i]);
    }
    return cli_usage_error("unknown option '%s'", a);
}

int cli_parse_options(int argc, char **argv, cli_options *o)
{
    int rc = options_init(o, argc);
    int only_files = 0;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        const char *a = argv[i];
        if (only_files || a[0] != '-' || a[1] == '\0')
            o->files[o->nfiles++] = a;
        else if (strcmp(a, "--") == 0)
            only_files = 1;
        else if (cli_is_help(a))
            return CLI_HELP;
        else if (strcmp(a, "--json") == 0)
            o->json = 1;
        else if (strcmp(a, "--no-read-ahead") == 0)
            o->read_ahead = 0;
        else
            rc = parse_valued(o, argc, argv, &i);
    }
    if (rc == CLI_OK && o->nmodels == 0)
        for (int k = 0; k < brdffit_model_count(); k++)
            if (brdffit_model_get((brdffit_model)k)->in_default_set)
                o->models[o->nmodels++] = (brdffit_model)k;
    return rc;
}

void cli_options_free(cli_options *o)
{
    free(o->files);
    o->files = NULL;
    o->nfiles = 0;
}
