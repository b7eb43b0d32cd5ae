/* SPDX-License-Identifier: MIT */
/* usage.c -- the --help text: the subcommands, the options
 * of fit and demo, the exit statuses. */
#include "cli.h"

#include <string.h>

/* The column where a command's summary starts. */
#define SUMMARY_COLUMN 32

/* "  NAME SYNOPSIS" then the summary lines at SUMMARY_COLUMN. */
static void command_help(FILE *f, const cli_command *c)
{
    int w = fprintf(f, "  %s%s%s", c->name, c->synopsis[0] ? " " : "", c->synopsis);
    const char *line = c->summary;
    for (;;) {
        size_t n = strcspn(line, "\n");
        if (w >= SUMMARY_COLUMN) {
            fputc('\n', f);
            w = 0;
        }
        fprintf(f, "%*s%.*s\n", SUMMARY_COLUMN - w, "", (int)n, line);
        w = 0;
        if (line[n] == '\0')
            break;
        line += n + 1;
    }
}

void cli_usage(FILE *f, const cli_command *commands, int n)
{
    fprintf(f,
            "Usage: brdffit COMMAND [ARGUMENTS]\n"
            "\n"
            "Fit the analytic BRDF models of Ngan, Durand & Matusik (EGSR 2005) to MERL\n"
            "measured reflectance tables (.binary), with the library's \"%s\" Error.\n"
            "\n"
            "Commands:\n",
            brdffit_metric_name());
    for (int i = 0; i < n; i++)
        command_help(f, &commands[i]);
    fputc('\n', f);
    cli_options_help(f);
    fputc('\n', f);
    cli_batch_help(f);
    fputc('\n', f);
    cli_draw_help(f);
    fputs("\n"
          "  brdffit --help | --version\n"
          "\n"
          "Exit status: 0 success; 1 a file could not be read or a fit failed (the other\n"
          "files and models are still fitted); 2 a usage error; batch: 128 + the signal\n"
          "number when SIGINT or SIGTERM stopped it (what was done is kept).\n"
          "PoCL caches kernel builds in $POCL_CACHE_DIR (set to a user cache when unset).\n",
          f);
}
