/* SPDX-License-Identifier: MIT */
/* brdffit.c -- the brdffit program: the table of subcommands and main.
 * Exit status 0 success, 1 a file or fit failed, 2 a usage error.
 * A new subcommand is one line in commands[] (and its cmd_NAME.c). */
#include "cli.h"

#include <errno.h>
#include <string.h>

static const cli_command commands[] = {
    { "fit", cmd_fit, "FILE.binary... [OPTIONS]",
      "fit the models to each table and print the fitted\nparameters (paper units) and their Error" },
    { "demo", cmd_demo, "[OPTIONS]",
      "fit every model to a built-in synthetic material\n"
      "(Cook-Torrance at published alum-bronze values; no files)" },
    { "models", cmd_models, "", "list the models, their lobe parameters and bounds" },
    { "eval", cmd_eval, "MODEL d_r d_g d_b s_r s_g s_b p0 [p1 [p2]] --wi X Y Z --wo X Y Z",
      "print f(wi, wo) per channel (1/sr, no cosine factor)" },
    { "batch", cmd_batch, "INPUT... --out DIR [OPTIONS]",
      "fit the models to every material (INPUT: a table, a directory\n"
      "of *.binary, @LIST) and write the report into DIR: pages,\n"
      "renders, plots, the Error matrix; journaled, resumable" },
    { "report", cmd_report, "DIR... --out DIR",
      "merge the journals of batch directories (shards) into one report" },
    { "render", cmd_render, "TABLE --out DIR [--model LIST|all] [--fits FILE] [OPTIONS]",
      "render the measured table and each fitted model on a sphere\n"
      "(EXR + PNG), difference images and image errors" },
    { "plot", cmd_plot, "TABLE --out DIR [--model LIST|all] [--fits FILE] [--theta-i LIST]",
      "incidence-plane plots (SVG, cube root) of the measured table\n"
      "and each fitted model" },
    { "score", cmd_score, "TABLE --model M --params d_r,...,p0[,p1,p2] | --fits FILE",
      "print the Error of given parameters on a table" },
};
static const int ncommands = (int)(sizeof commands / sizeof commands[0]);

static const cli_command *find_command(const char *name)
{
    for (int i = 0; i < ncommands; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        cli_usage(stderr, commands, ncommands);
        return CLI_USAGE;
    }
    const char *name = argv[1];
    const cli_command *cmd = find_command(name);
    int rc;
    if (cli_is_help(name) || strcmp(name, "help") == 0) {
        rc = CLI_HELP;
    } else if (strcmp(name, "--version") == 0 || strcmp(name, "version") == 0) {
        printf("brdffit %s\n", brdffit_version());
        rc = CLI_OK;
    } else if (cmd) {
        rc = cmd->run(argc - 2, argv + 2);
    } else {
        cli_error("unknown command '%s'", name);
        putc('\n', stderr);
        cli_usage(stderr, commands, ncommands);
        return CLI_USAGE;
    }
    if (rc == CLI_HELP) {
        cli_usage(stdout, commands, ncommands);
        rc = CLI_OK;
    }
    /* output that could not be written (a full disk, a closed pipe) is a failure */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "brdffit: error writing the output: %s\n", strerror(errno));
        return rc == CLI_OK ? CLI_FAILED : rc;
    }
    return rc;
}
