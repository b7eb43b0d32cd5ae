/* SPDX-License-Identifier: MIT */
/* man.c -- the manual page brdffit(1) (`brdffit help --man`; the build
 * writes it to build/brdffit.1), made from the same text as the help: the
 * description, the commands and their blocks of options, the exit statuses
 * and the environment (usage.c), in man(7) macros.  Text is escaped for
 * roff: a backslash as \e, every '-' as \- (options and model names are
 * typed as shown), quotes as ASCII quotes, a line that would begin with a
 * control character with \& before it. */
#include "cli.h"

#include <ctype.h>
#include <string.h>

/* One character of text, escaped. */
static void roff_char(FILE *f, char c)
{
    if (c == '\\')
        fputs("\\e", f);
    else if (c == '-')
        fputs("\\-", f);
    else if (c == '`')
        fputs("\\(ga", f);
    else if (c == '\'')
        fputs("\\(aq", f);
    else
        fputc(c, f);
}

/* Text lines separated by '\n', each a roff text line (empty ones left out). */
static void roff_lines(FILE *f, const char *text)
{
    int line_start = 1;
    for (const char *c = text; *c; c++) {
        if (*c == '\n') {
            if (!line_start)
                fputc('\n', f);
            line_start = 1;
            continue;
        }
        if (line_start && *c == '.')
            fputs("\\&", f);
        roff_char(f, *c);
        line_start = 0;
    }
    if (!line_start)
        fputc('\n', f);
}

/* A term on one line: its options ("--model", "-1" is not one) in bold. */
static void roff_term(FILE *f, const char *term)
{
    for (const char *c = term; *c;) {
        int word_start = c == term || strchr(" [|,", c[-1]) != NULL;
        if (word_start && c[0] == '-' && (c[1] == '-' || isalpha((unsigned char)c[1]))) {
            fputs("\\fB", f);
            while (*c == '-' || isalnum((unsigned char)*c))
                roff_char(f, *c++);
            fputs("\\fR", f);
        } else {
            roff_char(f, *c++);
        }
    }
    fputc('\n', f);
}

static void roff_block(FILE *f, const cli_help_block *b)
{
    fputs(".SS ", f);
    roff_term(f, b->title);
    if (b->note) {
        char note[512];
        snprintf(note, sizeof note, "(%s)", b->note);
        fputs(".PP\n", f);
        roff_lines(f, note);
    }
    for (int i = 0; i < b->nitems; i++) {
        fputs(".TP\n", f);
        roff_term(f, b->items[i].term);
        roff_lines(f, b->items[i].text);
    }
}

/* Every block of options once, in the order the commands first name them. */
static void roff_blocks(FILE *f, const cli_command *commands, int n)
{
    const cli_help_block *done[64];
    int ndone = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < CLI_MAX_BLOCKS && commands[i].blocks[k]; k++) {
            const cli_help_block *b = commands[i].blocks[k]();
            int seen = 0;
            for (int j = 0; j < ndone; j++)
                seen |= done[j] == b;
            if (seen || ndone == (int)(sizeof done / sizeof done[0]))
                continue;
            done[ndone++] = b;
            roff_block(f, b);
        }
}

static void roff_commands(FILE *f, const cli_command *commands, int n)
{
    fputs(".SH COMMANDS\n", f);
    for (int i = 0; i < n; i++) {
        fprintf(f, ".TP\n\\fB%s\\fR ", commands[i].name);
        roff_term(f, commands[i].synopsis);
        roff_lines(f, commands[i].summary);
    }
}

void cli_man(FILE *f, const cli_command *commands, int n)
{
    fprintf(f,
            ".\\\" brdffit(1), written by `brdffit help --man` from the program's help text\n"
            ".TH BRDFFIT 1 \"\" \"brdffit %s\" \"User Commands\"\n"
            ".nh\n" /* no hyphenation: options and names stay whole */
            ".ad l\n"
            ".SH NAME\n"
            "brdffit \\- fit analytic BRDF models to MERL measured reflectance tables\n"
            ".SH SYNOPSIS\n"
            "\\fBbrdffit\\fR \\fICOMMAND\\fR [\\fIARGUMENTS\\fR]\n"
            ".br\n"
            "\\fBbrdffit help\\fR [\\fICOMMAND\\fR]\n"
            ".br\n"
            "\\fBbrdffit \\-\\-help\\fR | \\fB\\-\\-version\\fR\n"
            ".SH DESCRIPTION\n",
            brdffit_version());
    roff_lines(f, cli_description());
    fputs(".PP\n", f);
    roff_lines(f, "`brdffit help COMMAND` (or `brdffit COMMAND --help`) prints the usage and\n"
                  "options of one command.");
    roff_commands(f, commands, n);
    fputs(".SH OPTIONS\n", f);
    roff_blocks(f, commands, n);
    fputs(".SH \"EXIT STATUS\"\n", f);
    roff_lines(f, cli_exit_status);
    fputs(".SH ENVIRONMENT\n", f);
    for (int i = 0; i < cli_nenvironment; i++) {
        fputs(".TP\n", f);
        fprintf(f, "\\fB%s\\fR\n", cli_environment[i].term);
        roff_lines(f, cli_environment[i].text);
    }
}
