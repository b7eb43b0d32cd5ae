/* SPDX-License-Identifier: MIT */
/* fuzz_options.c -- libFuzzer target: the brdffit program's argument
 * parsers, with argv made from the input.
 *
 * The first input byte picks the parser: even, the options of `fit` and
 * `demo` (cli_parse_options); odd, `eval` (its parser and one evaluation,
 * which is cheap).  The rest is split at NUL bytes into the arguments (at
 * most 64).  What a successful parse returns is checked against the rules
 * the options have (models known and not repeated, cutoff in (0, 90], ...).
 * `make fuzz` builds this with clang and runs it; tests/fuzz/make_seeds.c
 * writes its seed corpus. */
#include "cli.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ARGS 64

static void check_options(const cli_options *o, int argc, char **argv)
{
    if (o->nmodels < 1 || o->nmodels > BRDFFIT_MODEL_COUNT)
        abort();
    for (int i = 0; i < o->nmodels; i++) {
        if (!brdffit_model_get(o->models[i]))
            abort();
        for (int j = 0; j < i; j++)
            if (o->models[j] == o->models[i])
                abort();
    }
    if (!(o->sample.cutoff_deg > 0 && o->sample.cutoff_deg <= 90))
        abort();
    if (o->fit.starts < 0 || o->fit.starts > 1000)
        abort();
    if (o->nfiles < 0 || o->nfiles > argc)
        abort();
    for (int i = 0; i < o->nfiles; i++) { /* every file is one of the arguments */
        int found = 0;
        for (int j = 0; j < argc && !found; j++)
            found = o->files[i] == argv[j];
        if (!found)
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    char *text = malloc(size); /* the arguments, NUL-terminated, in one block */
    if (!text)
        return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    char *argv[MAX_ARGS + 1];
    int argc = 0;
    for (char *p = text; argc < MAX_ARGS && p < text + size - 1; p += strlen(p) + 1)
        argv[argc++] = p;
    argv[argc] = NULL;
    if (data[0] & 1) {
        int rc = cmd_eval(argc, argv);
        if (rc != CLI_OK && rc != CLI_USAGE && rc != CLI_HELP && rc != CLI_FAILED)
            abort();
    } else {
        cli_options o;
        int rc = cli_parse_options(argc, argv, &o);
        if (rc == CLI_OK)
            check_options(&o, argc, argv);
        else if (rc != CLI_USAGE && rc != CLI_HELP && rc != CLI_FAILED)
            abort();
        cli_options_free(&o);
    }
    free(text);
    return 0;
}
