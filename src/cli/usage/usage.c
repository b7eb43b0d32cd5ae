/* SPDX-License-Identifier: MIT */
/* usage.c -- the help text: the short list of commands (`brdffit --help`),
 * one command's usage and options (`brdffit help fit`), and the text the
 * manual page (man.c) shares with them. */
#include "cli.h"

#include <string.h>

/* The column where a description starts. */
#define TEXT_COLUMN 32

const char *cli_description(void)
{
    static char text[256];
    snprintf(text, sizeof text,
             "Fit the analytic BRDF models of Ngan, Durand & Matusik (EGSR 2005) to MERL\n"
             "measured reflectance tables (.binary), with the library's \"%s\" Error.",
             brdffit_metric_name());
    return text;
}

const char cli_exit_status[] =
    "0 success; 1 a file could not be read or a fit failed (the other\n"
    "files and models are still fitted); 2 a usage error; batch: 128 + the signal\n"
    "number when SIGINT or SIGTERM stopped it (what was done is kept).";

const cli_help_item cli_environment[] = {
    { "POCL_CACHE_DIR", "where PoCL caches the compiled kernels (set to a user\n"
                        "cache, ~/.cache/brdffit/pocl, when unset)" },
    { "BRDFFIT_DEVICE", "the OpenCL device when --device is not given" },
};
const int cli_nenvironment = (int)(sizeof cli_environment / sizeof cli_environment[0]);

/* "  TERM" then the lines of text at TEXT_COLUMN (the first on the next line
 * when the term reaches the column). */
static void item_text(FILE *f, const char *term, const char *text)
{
    int w = fprintf(f, "  %s", term);
    const char *line = text;
    for (;;) {
        size_t n = strcspn(line, "\n");
        if (w >= TEXT_COLUMN) {
            fputc('\n', f);
            w = 0;
        }
        fprintf(f, "%*s%.*s\n", TEXT_COLUMN - w, "", (int)n, line);
        w = 0;
        if (line[n] == '\0')
            break;
        line += n + 1;
    }
}

/* Lines separated by '\n', each indented. */
static void indented(FILE *f, const char *indent, const char *text)
{
    for (const char *line = text;;) {
        size_t n = strcspn(line, "\n");
        fprintf(f, "%s%.*s\n", indent, (int)n, line);
        if (line[n] == '\0')
            break;
        line += n + 1;
    }
}

void cli_block_text(FILE *f, const cli_help_block *b)
{
    fprintf(f, "%s:\n", b->title);
    if (b->note) {
        fputs("  (", f);
        for (const char *c = b->note; *c; c++) {
            fputc(*c, f);
            if (*c == '\n')
                fputs("   ", f);
        }
        fputs(")\n", f);
    }
    for (int i = 0; i < b->nitems; i++)
        item_text(f, b->items[i].term, b->items[i].text);
}

void cli_usage(FILE *f, const cli_command *commands, int n)
{
    fputs("Usage: brdffit COMMAND [ARGUMENTS]\n\n", f);
    fprintf(f, "%s\n\nCommands:\n", cli_description());
    for (int i = 0; i < n; i++)
        fprintf(f, "  %-9s %s\n", commands[i].name, commands[i].brief);
    fputs("\n"
          "Run 'brdffit help COMMAND' (or 'brdffit COMMAND --help') for its options,\n"
          "'brdffit --version' for the version; the manual page: man brdffit.\n"
          "\n"
          "Exit status: ",
          f);
    fprintf(f, "%s\n", cli_exit_status);
}

void cli_command_usage(FILE *f, const cli_command *c)
{
    fprintf(f, "Usage: brdffit %s%s%s\n\n", c->name, c->synopsis[0] ? " " : "", c->synopsis);
    indented(f, "  ", c->summary);
    for (int k = 0; k < CLI_MAX_BLOCKS && c->blocks[k]; k++) {
        fputc('\n', f);
        cli_block_text(f, c->blocks[k]());
    }
}
