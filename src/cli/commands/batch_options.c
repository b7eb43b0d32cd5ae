/* SPDX-License-Identifier: MIT */
/* batch_options.c -- the options of `brdffit batch` and their help block. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <stdlib.h>
#include <string.h>

static int parse_shard(const char *v, int *k, int *n)
{
    const char *slash = strchr(v, '/');
    char a[32];
    if (!slash || (size_t)(slash - v) >= sizeof a)
        return -1;
    memcpy(a, v, (size_t)(slash - v));
    a[slash - v] = '\0';
    if (cli_parse_int(slash + 1, 1, 1000000, n) != 0 || cli_parse_int(a, 1, *n, k) != 0)
        return -1;
    return 0;
}

/* The batch's own options are taken out; the rest go to cli_parse_options. */
int batch_parse_options(int argc, char **argv, batch_options *b)
{
    memset(b, 0, sizeof *b);
    b->shard_k = b->shard_n = 1;
    char **rest = malloc((size_t)(argc + 1) * sizeof *rest);
    if (!rest) {
        fputs("brdffit: out of memory\n", stderr);
        return CLI_FAILED;
    }
    int nrest = 0, rc = CLI_OK;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        const char *a = argv[i];
        const char **dst = NULL;
        if (strcmp(a, "--") == 0) {
            while (i < argc)
                rest[nrest++] = argv[i++];
            break;
        }
        if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0)
            b->quiet = 1;
        else if (strcmp(a, "--no-render") == 0)
            b->no_render = 1;
        else if (strcmp(a, "--no-plot") == 0)
            b->no_plot = 1;
        else if (strcmp(a, "--demo") == 0)
            b->demo = 1;
        else if (strcmp(a, "--allow-scale-mismatch") == 0)
            b->allow_scale_mismatch = 1;
        else if (strcmp(a, "--json") == 0)
            rc = cli_usage_error("batch writes its JSON into --out DIR; --json is for fit");
        else if (strncmp(a, "--out", 5) == 0 && (a[5] == '\0' || a[5] == '='))
            dst = &b->out;
        else if (strncmp(a, "--published", 11) == 0 && (a[11] == '\0' || a[11] == '='))
            dst = &b->published;
        else if (strncmp(a, "--shard", 7) == 0 && (a[7] == '\0' || a[7] == '=')) {
            const char *v = a[7] == '=' ? a + 8 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || parse_shard(v, &b->shard_k, &b->shard_n) != 0)
                rc = cli_usage_error("--shard '%s': expected K/N with 1 <= K <= N", v ? v : "");
        } else
            rest[nrest++] = argv[i];
        if (dst) {
            const char *eq = strchr(a, '=');
            const char *v = eq ? eq + 1 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || !*v)
                rc = cli_usage_error("%.*s needs a value", (int)strcspn(a, "="), a);
            else
                *dst = v;
        }
    }
    if (rc == CLI_OK) {
        rc = cli_parse_options(nrest, rest, &b->common);
        if (rc == CLI_OK && !b->out)
            rc = cli_usage_error("batch needs --out DIR");
        else if (rc == CLI_OK && b->common.nfiles == 0 && !b->demo)
            rc = cli_usage_error("batch needs INPUT: a table, a directory of *.binary or @LIST");
    }
    free(rest);
    return rc;
}

const cli_help_block *cli_batch_help(void)
{
    static const cli_help_item items[] = {
        { "--out DIR", "the report: DIR/index.html, DIR/<material>/, fits.tsv,\n"
                       "journal.jsonl (re-run the same command to resume)" },
        { "--published FITS.tsv", "also the Error of published parameters (the format\n"
                                  "of ngan2005-fits.tsv) on each table, and the ratio;\n"
                                  "a file stating '# scale: S' needs --scale S" },
        { "--allow-scale-mismatch", "compare with a --published file of another scale\n"
                                    "(said on every page of the report)" },
        { "--shard K/N", "only every N-th material of the sorted list, from the\n"
                         "K-th (merge the shards with `brdffit report`)" },
        { "--no-render, --no-plot", "leave out the renders / the incidence-plane plots" },
        { "--demo", "add the embedded synthetic material" },
        { "--quiet", "no progress on stderr (a live line on a terminal,\n"
                     "else one line per material)" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK(
        "Options of batch",
        "and the options of fit but --json; INPUT is a MERL table,\n"
        "a directory of *.binary, or @LIST: a text file naming one table a line",
        items);
    return &block;
}
