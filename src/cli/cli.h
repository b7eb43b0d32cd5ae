/* SPDX-License-Identifier: MIT */
/* cli.h -- what the source files of the brdffit program share.
 *
 * The program is in rooms, one folder a job:
 *   brdffit.c     main: the table of subcommands, --help, --version
 *   commands/     one cmd_NAME.c per subcommand: fit and demo, models, eval,
 *                 batch, report, render, plot, score, export
 *   export/       the files export writes: glTF 2.0 (gltf_write.c, the
 *                 sphere gltf_mesh.c), MaterialX (mtlx_write.c), the formats
 *                 by name (format.c), the files of fits it reads (fits_read.c)
 *   usage/        the command line: strict number parsing and usage errors
 *                 (args.c), the options of fit and demo (options.c), the help
 *                 text (usage.c) and the manual page (man.c) from one table,
 *                 hints for an input of the wrong kind (hints.c), the line
 *                 shown while kernels compile (kernel_note.c)
 *   text/         text for the terminal (text.c), UTF-8 (utf8.c), JSON text
 *                 (json.c)
 *   pipeline/     the one loop that reads a table, samples it and fits it
 *                 (fit_pipeline.c), the next table read meanwhile
 *                 (prefetch.c), a material's name (material.c), the fits a
 *                 render or plot needs (material_fits.c), the embedded demo
 *                 material, published fits (published.c)
 *   record/       the fit record: its schema (fit_record.c), JSON
 *                 (fit_record_json.c) and TSV (fit_record_tsv.c),
 *                 the batch journal (journal.c, jsonread.c), the output
 *                 directory, its lock and files written whole or not at all
 *                 without following links (outdir.h: outdir.c, outfile.c),
 *                 files read only when they are regular files (infile.c),
 *                 the tests' fault points
 *                 (fault.c); batch.h is what the batch's files share
 *   report/       the paper-style table (report.c), the HTML report
 *                 (html_report.c, html_material.c, html_index.c,
 *                 html_headline.c, report_data.c), a material's files (assets.c)
 *   images/       renders and plots (draw.c, render_files.c), image files
 *                 (exr_io.c, png_io.c, tonemap.c), SVG/XML text
 *                 (svg.c, plot_svg.c)
 * Each folder's headers are included by name (the Makefile's CLI_INC).
 *
 * The library never prints or exits; this program does both. */
#ifndef BRDFFIT_CLI_H
#define BRDFFIT_CLI_H

#include "brdffit.h"

#include <stdio.h>

/* Exit statuses. */
enum { CLI_OK = 0, CLI_FAILED = 1, CLI_USAGE = 2 };
/* What a subcommand returns when --help was asked: main prints the usage. */
#define CLI_HELP (-1)

#if defined(__GNUC__)
#define CLI_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define CLI_PRINTF(a, b)
#endif

/* ---- usage.c, man.c: the help text ---- */

/* One option (or argument) in the help: term "--cutoff DEG", text its
 * description, lines separated by '\n' (the text help keeps them, the manual
 * page fills them). */
typedef struct cli_help_item {
    const char *term;
    const char *text;
} cli_help_item;

/* A block of options: "Options of batch", an optional note on what else
 * applies (lines separated by '\n'), its items. */
typedef struct cli_help_block {
    const char *title;
    const char *note;             /* NULL: none */
    const cli_help_item *items;
    int nitems;
} cli_help_block;

/* A block's initializer from a title, a note and an array of items. */
#define CLI_HELP_BLOCK(title, note, items) \
    { title, note, items, (int)(sizeof items / sizeof items[0]) }

/* Each block is made by a function (a few hold text made at run time). */
typedef const cli_help_block *(*cli_help_fn)(void);
#define CLI_MAX_BLOCKS 3

/* ---- brdffit.c ---- */

/* A subcommand: `brdffit NAME ARGS...` calls run(argc, argv) with the
 * arguments after NAME and exits with what it returns (CLI_OK, CLI_FAILED,
 * CLI_USAGE), or prints its usage and exits 0 when it returns CLI_HELP. */
typedef struct cli_command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *synopsis; /* the arguments: "FILE.binary... [OPTIONS]"            */
    const char *brief;    /* what it does, one line, for the list of commands      */
    const char *summary;  /* what it does, for its help; lines separated by '\n'   */
    cli_help_fn blocks[CLI_MAX_BLOCKS]; /* its options, in order (NULL after the last) */
} cli_command;

/* ---- usage.c ---- */

/* The short help: what the program does, the n commands of commands one a
 * line, where to find more. */
void cli_usage(FILE *f, const cli_command *commands, int n);
/* The help of one command: its usage line, what it does, its options. */
void cli_command_usage(FILE *f, const cli_command *c);
/* One block of options as text. */
void cli_block_text(FILE *f, const cli_help_block *b);
/* The text both the help and the manual page show. */
const char *cli_description(void);  /* what the program does, '\n'-separated lines */
extern const char cli_exit_status[];  /* the exit statuses                         */
extern const cli_help_item cli_environment[]; /* the environment variables read  */
extern const int cli_nenvironment;

/* ---- man.c ---- */

/* The manual page brdffit(1) (man(7) macros) of the n commands. */
void cli_man(FILE *f, const cli_command *commands, int n);

/* ---- cmd_*.c: the subcommands ---- */

int cmd_fit(int argc, char **argv);
int cmd_demo(int argc, char **argv);
int cmd_models(int argc, char **argv);
int cmd_eval(int argc, char **argv);
int cmd_batch(int argc, char **argv);
int cmd_report(int argc, char **argv);
int cmd_score(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_plot(int argc, char **argv);
int cmd_export(int argc, char **argv);
/* Their blocks of options (each beside the command's parser). */
const cli_help_block *cli_batch_help(void);  /* batch_options.c                  */
const cli_help_block *cli_draw_help(void);   /* cmd_render.c: render and plot    */
const cli_help_block *cli_render_help(void); /* cmd_render.c                     */
const cli_help_block *cli_plot_help(void);   /* cmd_plot.c                       */
const cli_help_block *cli_eval_help(void);   /* cmd_eval.c                       */
const cli_help_block *cli_score_help(void);  /* cmd_score.c                      */
const cli_help_block *cli_report_help(void); /* cmd_report.c                     */
const cli_help_block *cli_export_help(void); /* cmd_export.c                     */

/* ---- demo_material.c: the embedded synthetic material ---- */

const char *cli_demo_name(void);
/* Its generating model and parameters. */
const brdffit_params *cli_demo_truth(brdffit_model *model);
/* Its table, stored in the given scale. */
brdffit_status cli_demo_table(brdffit_scale scale, brdffit_table **out, brdffit_error *err);

/* ---- args.c ---- */

/* A finite double, the whole string (strtod with an end check). 0 on success. */
int cli_parse_double(const char *s, double *out);
/* A decimal int in [lo, hi], the whole string. 0 on success. */
int cli_parse_int(const char *s, int lo, int hi, int *out);
/* 1 when a is --help or -h. */
int cli_is_help(const char *a);
/* "brdffit: <message>" and a pointer to the command's --help on stderr;
 * returns CLI_USAGE. */
int cli_usage_error(const char *fmt, ...) CLI_PRINTF(1, 2);
/* The command whose help cli_usage_error points to (NULL: the program's). */
void cli_set_command(const char *name);
/* The valid model names, comma-separated, into buf. */
const char *cli_model_names(char *buf, size_t len);
/* The numbers a model's parameters are given as, in order, separated by sep
 * (' ' or ','): its colours by colour_names ("d_r", ..., "s_b", or
 * "base_color_r", ..., "specular_color_b"), then its lobe parameters by name. */
const char *cli_param_list(brdffit_model model, char sep, char *buf, size_t len);
/* The models' default numbers of starts, "8; he 7" (the common one first), into buf. */
const char *cli_default_starts(char *buf, size_t len);

/* ---- options.c ---- */

typedef struct cli_options {
    brdffit_model models[BRDFFIT_MODEL_COUNT]; /* in the order asked, no repeats */
    int nmodels;                                /* 0 until --model; then >= 1    */
    brdffit_sample_options sample;
    brdffit_fit_options fit;
    brdffit_context_options context;
    int json;
    int all_metrics;                            /* --metric all (batch: the three in turn) */
    int read_ahead;                             /* 1 (default): the next table is read
                                                 * while this one is fitted (prefetch.h);
                                                 * 0 after --no-read-ahead             */
    const char **files;                         /* the positional arguments      */
    int nfiles;
} cli_options;

/* Parse the arguments after `fit` / `demo` into o (defaults first).  Returns
 * CLI_OK, CLI_USAGE or CLI_FAILED (message printed), or CLI_HELP when --help
 * was asked.  Free with cli_options_free. */
int cli_parse_options(int argc, char **argv, cli_options *o);
void cli_options_free(cli_options *o);
/* The "Options of fit and demo" block of the help. */
const cli_help_block *cli_options_help(void);

/* ---- kernel_note.c ---- */

/* When f is a terminal, the context uses OpenCL and the model's kernels are
 * not built in it yet: "brdffit: compiling the OpenCL kernels of MODEL, once
 * per machine (cached in DIR)..." on f, without a newline; returns 1 then,
 * else 0 (nothing printed). */
int kernel_note_begin(FILE *f, const brdffit_context *ctx, brdffit_model model);
/* After the call that built them (a fit, an Error): the time ends the line
 * when the build compiled (1 s or more), else the line is erased (PoCL's
 * cache had them, or the build failed).  Nothing when shown is 0. */
void kernel_note_end(FILE *f, int shown, const brdffit_context *ctx, brdffit_model model);

/* ---- hints.c ---- */

/* 1 when path is a directory. */
int cli_is_directory(const char *path);
/* 1 when path is a regular file whose first bytes are text (no control
 * characters but tabs and line ends): a list, not a MERL table. */
int cli_is_text_file(const char *path);
/* After a table could not be read: what to run instead when path is a
 * directory or a text file (a note on stderr), else nothing. */
void cli_hint_unreadable_table(const char *path);

/* ---- infile.c ---- */

/* path opened for reading when it is a regular file (opened without blocking,
 * checked with fstat, then made blocking): its descriptor, or -1 with err set
 * ("PATH: not a regular file", "PATH: is a directory, not a file", "PATH:
 * cannot open: REASON").  A FIFO or a device is never waited on. */
int cli_open_regular(const char *path, brdffit_error *err);
/* The same as a stdio stream ("rb"), or NULL with err set. */
FILE *cli_fopen_regular(const char *path, brdffit_error *err);

/* ---- material.c ---- */

/* What a fit report is about: a material and the settings of its samples. */
typedef struct cli_material {
    const char *name;                 /* "alum-bronze"                          */
    const char *file;                 /* its path, or NULL (the demo)           */
    const char *about;                /* one extra line for the table, or NULL  */
    brdffit_sample_options sample;    /* cutoff and scale                       */
} cli_material;

/* The material's name from a path: the base name without ".binary", into buf. */
const char *cli_material_name(const char *path, char *buf, size_t len);

/* ---- report.c ---- */

/* Table mode. */
void report_header(FILE *f, const cli_material *m, const brdffit_samples *s,
                   const brdffit_context *ctx, const brdffit_fit_options *fo);
void report_row(FILE *f, const char *label, const brdffit_model_info *mi,
                const brdffit_params *p, double error, const brdffit_fit_result *r);
void report_row_failed(FILE *f, brdffit_model model, const brdffit_error *err);
void report_legend(FILE *f, const brdffit_model *models, int nmodels, brdffit_metric metric);

/* ---- json.c ---- */

/* s as a JSON string (quotes included); a byte that is not part of
 * well-formed UTF-8 is written \udcXX (XX the byte: lossless, see json.c). */
void json_string(FILE *f, const char *s);
/* x with %.17g, or null when x is not finite. */
void json_number(FILE *f, double x);
/* "[x0,x1,...]" of n numbers. */
void json_numbers(FILE *f, const double *x, int n);

/* ---- text.c ---- */

/* s for the terminal: control characters (newlines too), C1 controls and
 * bytes that are not well-formed UTF-8 written as \xHH. */
void plain_string(FILE *f, const char *s);
/* The same, but a newline stays one, followed by an indent (a build log). */
void plain_lines(FILE *f, const char *s);
/* "brdffit: MESSAGE\n" on stderr, the message through plain_string. */
void cli_error(const char *fmt, ...) CLI_PRINTF(1, 2);
/* s itself when shorter than len, else its head, "..." and its tail
 * (len - 1 bytes): a long path in a message leaves room for the reason. */
const char *cli_brief(const char *s, char *buf, size_t len);

#endif
