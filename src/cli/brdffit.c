/* SPDX-License-Identifier: MIT */
/* brdffit.c -- the brdffit program: the table of subcommands, `help`, main.
 * Exit status 0 success, 1 a file or fit failed, 2 a usage error.
 * A new subcommand is one entry in commands[] (and its cmd_NAME.c). */
#include "cli.h"

#include <errno.h>
#include <string.h>

static const cli_command commands[] = {
    { "fit", cmd_fit, "FILE.binary... [OPTIONS]",
      "fit the models to MERL tables; print their parameters and Error",
      "fit the models to each table and print the fitted\nparameters (paper units) and their Error",
      { cli_options_help } },
    { "demo", cmd_demo, "[OPTIONS]", "fit every model to a built-in synthetic material",
      "fit every model to a built-in synthetic material\n"
      "(Cook-Torrance at published alum-bronze values; no files)",
      { cli_options_help } },
    { "models", cmd_models, "", "list the models, their lobe parameters and bounds",
      "list the models, their lobe parameters and bounds", { NULL } },
    { "eval", cmd_eval, "MODEL d_r d_g d_b s_r s_g s_b p0 [p1 [p2 [p3]]] --wi X Y Z --wo X Y Z",
      "print a model's BRDF value for two directions",
      "print f(wi, wo) per channel (1/sr, no cosine factor)", { cli_eval_help } },
    { "batch", cmd_batch, "INPUT... --out DIR [OPTIONS]",
      "fit every material of tables, directories, lists; write a report",
      "fit the models to every material (INPUT: a table, a directory\n"
      "of *.binary, @LIST) and write the report into DIR: pages,\n"
      "renders, plots, the Error matrix; journaled, resumable",
      { cli_batch_help, cli_options_help } },
    { "report", cmd_report, "DIR... --out DIR",
      "merge the journals of batch shards into one report",
      "merge the journals of batch directories (shards) into one report", { cli_report_help } },
    { "render", cmd_render, "TABLE --out DIR [--model LIST|all] [--fits FILE] [OPTIONS]",
      "render a table and its fitted models on a sphere (EXR, PNG)",
      "render the measured table and each fitted model on a sphere\n"
      "(EXR + PNG), difference images and image errors",
      { cli_draw_help, cli_render_help, cli_options_help } },
    { "plot", cmd_plot, "TABLE --out DIR [--model LIST|all] [--fits FILE] [--theta-i LIST]",
      "incidence-plane plots (SVG) of a table and its fitted models",
      "incidence-plane plots (SVG, cube root) of the measured table\n"
      "and each fitted model",
      { cli_draw_help, cli_plot_help, cli_options_help } },
    { "score", cmd_score, "TABLE --model M --params d_r,...,p0[,p1,p2,p3] | --fits FILE",
      "print the Error of given parameters on a table",
      "print the Error of given parameters on a table", { cli_score_help, cli_options_help } },
    { "export", cmd_export, "FITS... --out DIR [--format gltf|mitsuba]",
      "write fits as .gltf files or Mitsuba 3 scenes (a sphere each)",
      "write each fit of model gltf or gltf-ext as a glTF 2.0 file:\n"
      "the material on a sphere, DIR/MATERIAL-MODEL.gltf; with --format\n"
      "mitsuba each fit of any model as a Mitsuba 3 scene of render's\n"
      "sphere, DIR/MATERIAL-MODEL.xml",
      { cli_export_help } },
};
static const int ncommands = (int)(sizeof commands / sizeof commands[0]);

static const cli_command *find_command(const char *name)
{
    for (int i = 0; i < ncommands; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

/* `brdffit help [COMMAND | --man]`. */
static int help(int argc, char **argv)
{
    if (argc == 0 || strcmp(argv[0], "help") == 0 || cli_is_help(argv[0])) {
        cli_usage(stdout, commands, ncommands);
        return CLI_OK;
    }
    if (argc > 1)
        return cli_usage_error("help takes one command (got '%s' after '%s')", argv[1], argv[0]);
    if (strcmp(argv[0], "--man") == 0) {
        cli_man(stdout, commands, ncommands);
        return CLI_OK;
    }
    const cli_command *cmd = find_command(argv[0]);
    if (!cmd) {
        char names[256] = "";
        for (int i = 0; i < ncommands; i++)
            snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "",
                     commands[i].name);
        return cli_usage_error("help: no command '%s' (commands: %s)", argv[0], names);
    }
    cli_command_usage(stdout, cmd);
    return CLI_OK;
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
        rc = help(argc - 2, argv + 2);
    } else if (strcmp(name, "--version") == 0 || strcmp(name, "version") == 0) {
        printf("brdffit %s\n", brdffit_version());
        rc = CLI_OK;
    } else if (cmd) {
        cli_set_command(cmd->name);
        rc = cmd->run(argc - 2, argv + 2);
    } else {
        cli_error("unknown command '%s'", name);
        putc('\n', stderr);
        cli_usage(stderr, commands, ncommands);
        return CLI_USAGE;
    }
    if (rc == CLI_HELP) {
        cli_command_usage(stdout, cmd);
        rc = CLI_OK;
    }
    /* output that could not be written (a full disk, a closed pipe) is a failure */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "brdffit: error writing the output: %s\n", strerror(errno));
        return rc == CLI_OK ? CLI_FAILED : rc;
    }
    return rc;
}
