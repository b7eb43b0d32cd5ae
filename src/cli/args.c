/* args.c -- strict number parsing and the options of `fit` and `demo`. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int cli_parse_double(const char *s, double *out)
{
    if (!s || !*s || isspace((unsigned char)s[0]))
        return -1;
    char *end = NULL;
    errno = 0;
    double x = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(x))
        return -1;
    *out = x;
    return 0;
}

int cli_parse_int(const char *s, int lo, int hi, int *out)
{
    if (!s || !*s || isspace((unsigned char)s[0]))
        return -1;
    char *end = NULL;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || x < lo || x > hi)
        return -1;
    *out = (int)x;
    return 0;
}

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    fputs("brdffit: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputs("\nTry 'brdffit --help' for more information.\n", stderr);
    return CLI_USAGE;
}

const char *cli_model_names(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        int w = snprintf(buf + used, len - used, "%s%s", m ? ", " : "",
                         brdffit_model_get((brdffit_model)m)->name);
        if (w < 0 || (size_t)w >= len - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

static void add_model(cli_options *o, brdffit_model m)
{
    for (int i = 0; i < o->nmodels; i++)
        if (o->models[i] == m)
            return;
    o->models[o->nmodels++] = m;
}

/* "ward,cook-torrance" or "all". */
static int parse_models(cli_options *o, const char *value)
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
        brdffit_model m;
        if (strcmp(one, "all") == 0) {
            for (int k = 0; k < BRDFFIT_MODEL_COUNT; k++)
                add_model(o, (brdffit_model)k);
        } else if (brdffit_model_from_name(one, &m) == BRDFFIT_OK) {
            add_model(o, m);
        } else {
            return cli_usage_error("unknown model '%s' (valid: all, %s)", one,
                                   cli_model_names(names, sizeof names));
        }
        if (p[n] == '\0')
            return CLI_OK;
        p += n + 1;
    }
}

static int parse_backend(const char *v, brdffit_backend *out)
{
    if (strcmp(v, "auto") == 0)
        *out = BRDFFIT_BACKEND_AUTO;
    else if (strcmp(v, "opencl") == 0)
        *out = BRDFFIT_BACKEND_OPENCL;
    else if (strcmp(v, "host") == 0)
        *out = BRDFFIT_BACKEND_HOST;
    else
        return -1;
    return 0;
}

/* The options that take a value. */
static const char *const with_value[] = { "--model", "--scale", "--cutoff", "--starts",
                                          "--backend", "--device" };

int cli_parse_options(int argc, char **argv, cli_options *o)
{
    memset(o, 0, sizeof *o);
    brdffit_sample_options_default(&o->sample);
    brdffit_fit_options_default(&o->fit);
    brdffit_context_options_default(&o->context);
    o->files = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *o->files);
    if (!o->files) {
        fputs("brdffit: out of memory\n", stderr);
        return CLI_FAILED;
    }
    int only_files = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (only_files || a[0] != '-' || a[1] == '\0') {
            o->files[o->nfiles++] = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            only_files = 1;
            continue;
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0)
            return -1;
        if (strcmp(a, "--json") == 0) {
            o->json = 1;
            continue;
        }
        /* --name VALUE or --name=VALUE */
        const char *eq = strchr(a, '=');
        size_t nlen = eq ? (size_t)(eq - a) : strlen(a);
        const char *name = NULL;
        for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; k++)
            if (strlen(with_value[k]) == nlen && strncmp(a, with_value[k], nlen) == 0)
                name = with_value[k];
        if (!name)
            return cli_usage_error("unknown option '%s'", a);
        const char *v;
        if (eq) {
            v = eq + 1;
        } else {
            if (i + 1 >= argc)
                return cli_usage_error("%s needs a value", name);
            v = argv[++i];
        }

        if (strcmp(name, "--model") == 0) {
            int rc = parse_models(o, v);
            if (rc != CLI_OK)
                return rc;
        } else if (strcmp(name, "--scale") == 0) {
            if (brdffit_scale_from_name(v, &o->sample.scale) != BRDFFIT_OK)
                return cli_usage_error("--scale '%s': expected standard or flat", v);
        } else if (strcmp(name, "--cutoff") == 0) {
            double c;
            if (cli_parse_double(v, &c) != 0 || !(c > 0) || !(c <= 90))
                return cli_usage_error("--cutoff '%s': expected a number of degrees in (0, 90]",
                                       v);
            o->sample.cutoff_deg = c;
        } else if (strcmp(name, "--starts") == 0) {
            if (cli_parse_int(v, 1, 1000, &o->fit.starts) != 0)
                return cli_usage_error("--starts '%s': expected an integer in [1, 1000]", v);
        } else if (strcmp(name, "--backend") == 0) {
            if (parse_backend(v, &o->context.backend) != 0)
                return cli_usage_error("--backend '%s': expected auto, opencl or host", v);
        } else { /* --device */
            if (!*v)
                return cli_usage_error("--device needs a PLATFORM:DEVICE specification");
            o->context.device = v;
        }
    }
    if (o->nmodels == 0)
        for (int k = 0; k < BRDFFIT_MODEL_COUNT; k++)
            o->models[o->nmodels++] = (brdffit_model)k;
    return CLI_OK;
}

void cli_options_free(cli_options *o)
{
    free(o->files);
    o->files = NULL;
    o->nfiles = 0;
}
