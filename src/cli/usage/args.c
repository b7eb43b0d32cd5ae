/* SPDX-License-Identifier: MIT */
/* args.c -- what every subcommand's argument parsing uses: strict numbers,
 * --help, usage errors, the list of model names. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
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

int cli_is_help(const char *a)
{
    return strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0;
}

static const char *current_command; /* NULL: the program's own help */

void cli_set_command(const char *name)
{
    current_command = name;
}

int cli_usage_error(const char *fmt, ...)
{
    char msg[3 * BRDFFIT_MESSAGE_MAX]; /* arguments are quoted in it: printed plain */
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    cli_error("%s", msg);
    if (current_command)
        fprintf(stderr, "Try 'brdffit %s --help' for more information.\n", current_command);
    else
        fputs("Try 'brdffit --help' for more information.\n", stderr);
    return CLI_USAGE;
}

const char *cli_model_names(char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int m = 0; m < brdffit_model_count(); m++) {
        int w = snprintf(buf + used, len - used, "%s%s", m ? ", " : "",
                         brdffit_model_get((brdffit_model)m)->name);
        if (w < 0 || (size_t)w >= len - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

const char *cli_param_list(brdffit_model model, char sep, char *buf, size_t len)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    size_t used = 0;
    buf[0] = '\0';
    for (int k = 0; mi && k < 6 + mi->nparams; k++) {
        int w = k < 6 ? snprintf(buf + used, len - used, "%s%s_%c", k ? (sep == ',' ? "," : " ") : "",
                                 mi->colour_names[k / 3], "rgb"[k % 3])
                      : snprintf(buf + used, len - used, "%c%s", sep, mi->params[k - 6].name);
        if (w < 0 || (size_t)w >= len - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

const char *cli_default_starts(char *buf, size_t len)
{
    /* the count most models have, then the others by name */
    int n = brdffit_model_count(), common = 0, most = 0;
    for (int m = 0; m < n; m++) {
        int v = brdffit_model_get((brdffit_model)m)->default_starts, same = 0;
        for (int k = 0; k < n; k++)
            same += brdffit_model_get((brdffit_model)k)->default_starts == v;
        if (same > most)
            most = same, common = v;
    }
    size_t used = (size_t)snprintf(buf, len, "%d", common);
    for (int m = 0; m < n && used < len; m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        if (mi->default_starts != common)
            used += (size_t)snprintf(buf + used, len - used, "; %s %d", mi->name, mi->default_starts);
    }
    return buf;
}
