/* SPDX-License-Identifier: MIT */
/* test_help.c -- the program's help: the short list of commands, each
 * command's own usage (`brdffit help CMD` = `brdffit CMD --help`), and the
 * manual page made from the same text (`brdffit help --man`, build/brdffit.1):
 * every command and option of the help in it, escaped for roff, rendered by
 * groff without a warning. */
#define _DEFAULT_SOURCE
#include "cli.h"
#include "testutil.h"

#include <check.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const all_commands[] = { "fit",    "demo",   "models", "eval",  "batch",
                                            "report", "render", "plot",   "score", "export" };
#define NCOMMANDS ((int)(sizeof all_commands / sizeof all_commands[0]))

#define expect_status TU_EXPECT_STATUS

static tu_run_out run_ok(const char *args)
{
    tu_run_out r = tu_run_cli("", args);
    expect_status(r, 0, args);
    return r;
}

/* "\n  NAME " in the list of commands. */
static int lists_command(const char *text, const char *name)
{
    char want[64];
    snprintf(want, sizeof want, "\n  %s ", name);
    return strstr(text, want) != NULL;
}

START_TEST(overview_lists_the_commands)
{
    tu_run_out a = run_ok("--help"), b = run_ok("help");
    ck_assert_str_eq(a.out, b.out);
    for (int i = 0; i < NCOMMANDS; i++)
        ck_assert_msg(lists_command(a.out, all_commands[i]), "no %s in:\n%s", all_commands[i], a.out);
    ck_assert_msg(strstr(a.out, "'brdffit help COMMAND'") != NULL, "%s", a.out);
    ck_assert_msg(tu_count_lines(a.out) <= 24, "%d lines:\n%s", tu_count_lines(a.out), a.out);
    ck_assert_msg(strstr(a.out, "--cutoff") == NULL, "the list of commands has options:\n%s", a.out);
    tu_run_free(&a);
    tu_run_free(&b);
}
END_TEST

/* `help NAME` and `NAME --help` print the same: that command's usage. */
START_TEST(each_command_has_its_help)
{
    const char *name = all_commands[_i];
    char args[128], want[128];
    snprintf(args, sizeof args, "help %s", name);
    tu_run_out a = run_ok(args);
    snprintf(args, sizeof args, "%s --help", name);
    tu_run_out b = run_ok(args);
    ck_assert_str_eq(a.out, b.out);
    snprintf(want, sizeof want, "Usage: brdffit %s", name);
    ck_assert_msg(strncmp(a.out, want, strlen(want)) == 0, "%s", a.out);
    ck_assert_msg(strstr(a.out, "Commands:") == NULL, "help %s lists the commands:\n%s", name, a.out);
    tu_run_free(&a);
    tu_run_free(&b);
}
END_TEST

/* Each command's help has its own options and not another's. */
START_TEST(help_shows_the_commands_options)
{
    static const struct { const char *name, *has, *lacks; } cases[] = {
        { "fit", "--cutoff", "--shard" },   { "batch", "--shard", "--theta-i" },
        { "batch", "--cutoff", "--size" },  { "render", "--size", "--theta-i" },
        { "plot", "--theta-i", "--size" },  { "score", "--params", "--shard" },
        { "eval", "--wi", "--cutoff" },     { "report", "--out", "--cutoff" },
        { "export", "--format", "--cutoff" },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char args[64];
        snprintf(args, sizeof args, "help %s", cases[k].name);
        tu_run_out r = run_ok(args);
        ck_assert_msg(strstr(r.out, cases[k].has) != NULL, "%s: no %s", args, cases[k].has);
        ck_assert_msg(strstr(r.out, cases[k].lacks) == NULL, "%s: has %s", args, cases[k].lacks);
        tu_run_free(&r);
    }
}
END_TEST

START_TEST(help_of_no_command)
{
    tu_run_out r = tu_run_cli("", "help xyz");
    expect_status(r, 2, "help xyz");
    ck_assert_msg(strstr(r.err, "no command 'xyz'") && strstr(r.err, "fit, demo"), "%s", r.err);
    ck_assert_str_eq(r.out, "");
    tu_run_free(&r);
    r = tu_run_cli("", "help fit demo");
    expect_status(r, 2, "help fit demo");
    tu_run_free(&r);
}
END_TEST

/* A usage error points to its command's help. */
START_TEST(usage_error_points_to_its_help)
{
    tu_run_out r = tu_run_cli("", "fit --frobnicate x.binary");
    expect_status(r, 2, "fit --frobnicate");
    ck_assert_msg(strstr(r.err, "Try 'brdffit fit --help'") != NULL, "%s", r.err);
    tu_run_free(&r);
}
END_TEST

/* ------------------------------------------------------------------ the manual page */

/* Every "--option" of text is in man, as roff writes it ("\-\-option"). */
static void expect_options_in(const char *man, const char *text, const char *what)
{
    for (const char *p = strstr(text, "--"); p; p = strstr(p + 2, "--")) {
        if (p > text && (p[-1] == '-' || (p[-1] >= 'a' && p[-1] <= 'z')))
            continue;
        size_t n = strspn(p + 2, "abcdefghijklmnopqrstuvwxyz0123456789-");
        if (n == 0)
            continue;
        char want[128] = "\\-\\-";
        for (size_t i = 0; i < n && strlen(want) + 3 < sizeof want; i++)
            strcat(want, p[2 + i] == '-' ? "\\-" : (char[]){ p[2 + i], '\0' });
        ck_assert_msg(strstr(man, want) != NULL, "%s: %.*s is not in the manual page as %s", what,
                      (int)n + 2, p, want);
    }
}

START_TEST(man_page_has_every_command_and_option)
{
    tu_run_out man = run_ok("help --man");
    tu_run_out all = run_ok("--help");
    expect_options_in(man.out, all.out, "--help");
    for (int i = 0; i < NCOMMANDS; i++) {
        char args[64], want[64];
        snprintf(want, sizeof want, "\n.TP\n\\fB%s\\fR ", all_commands[i]);
        ck_assert_msg(strstr(man.out, want) != NULL, "the manual page has no command %s", all_commands[i]);
        snprintf(args, sizeof args, "help %s", all_commands[i]);
        tu_run_out r = run_ok(args);
        expect_options_in(man.out, r.out, args);
        tu_run_free(&r);
    }
    ck_assert(strstr(man.out, "\n.SH \"EXIT STATUS\"\n") != NULL);
    ck_assert(strstr(man.out, "\n\\fBPOCL_CACHE_DIR\\fR\n") != NULL);
    tu_run_free(&all);
    tu_run_free(&man);
}
END_TEST

/* Each line is a known macro or text; no '-' left unescaped (it would print
 * as a hyphen, not the ASCII minus an option is typed with). */
START_TEST(man_page_is_escaped)
{
    static const char *const macros[] = { ".\\\" ", ".TH ", ".SH ", ".SS ", ".TP\n",
                                          ".PP\n", ".br\n", ".nh\n", ".ad l\n" };
    tu_run_out man = run_ok("help --man");
    for (const char *line = man.out; *line; line = strchr(line, '\n') + 1) {
        size_t len = strcspn(line, "\n");
        ck_assert_msg(line[len] == '\n', "the last line has no newline");
        ck_assert_msg(len > 0, "an empty line in the manual page");
        if (line[0] == '.' || line[0] == '\'') {
            int known = 0;
            for (size_t k = 0; k < sizeof macros / sizeof macros[0]; k++)
                known |= strncmp(line, macros[k], strlen(macros[k])) == 0;
            ck_assert_msg(known, "unknown request: %.*s", (int)len, line);
            if (line[1] == '\\')
                continue;
        }
        for (size_t i = 0; i < len; i++)
            ck_assert_msg(line[i] != '-' || (i > 0 && line[i - 1] == '\\'), "an unescaped '-': %.*s",
                          (int)len, line);
    }
    tu_run_free(&man);
}
END_TEST

/* The escaping itself, on text made to need it. */
static int no_run(int argc, char **argv)
{
    (void)argc, (void)argv;
    return 0;
}

static const cli_help_block *odd_block(void)
{
    static const cli_help_item items[] = {
        { "--odd-one N", ".starts with a dot\n'starts with a quote\na \\back\\slash and `ticks`" },
    };
    static const cli_help_block block = { "Options of odd", "note -1", items, 1 };
    return &block;
}

START_TEST(man_escapes_roff)
{
    const cli_command cmd = { "odd", no_run, "X [--odd-one N]", "odd", "does odd\n.things", { odd_block } };
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    cli_man(f, &cmd, 1);
    fclose(f);
    char *man = tu_slurp(path);
    ck_assert_ptr_nonnull(man);
    static const char *const want[] = {
        "\n.TP\n\\fBodd\\fR X [\\fB\\-\\-odd\\-one\\fR N]\ndoes odd\n\\&.things\n",
        "\n.SS Options of odd\n.PP\n(note \\-1)\n",
        "\n.TP\n\\fB\\-\\-odd\\-one\\fR N\n\\&.starts with a dot\n\\(aqstarts with a quote\n"
        "a \\eback\\eslash and \\(gaticks\\(ga\n",
    };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++)
        ck_assert_msg(strstr(man, want[k]) != NULL, "no\n%s\nin\n%s", want[k], man);
    free(man);
    unlink(path);
}
END_TEST

/* groff renders it without a warning (-ww: all of them); the build's copy is
 * the program's. */
START_TEST(man_page_renders_clean)
{
    tu_run_out man = run_ok("help --man");
    const char *cli = getenv("BRDFFIT_CLI");
    char dir[512], built[600];
    snprintf(dir, sizeof dir, "%s", cli && *cli ? cli : "./build/brdffit");
    snprintf(built, sizeof built, "%s/brdffit.1", dirname(dir));
    char *file = tu_slurp(built);
    ck_assert_msg(file != NULL, "%s was not made by the build", built);
    ck_assert_msg(strcmp(file, man.out) == 0, "%s is not `brdffit help --man`", built);
    free(file);
    tu_run_free(&man);
    if (system("command -v groff >/dev/null 2>&1") != 0) {
        fputs("note: no groff: the manual page's rendering is not checked\n", stderr);
        return;
    }
    tu_run_out r = tu_run_cli("", "help --man | groff -man -Tutf8 -ww -z");
    ck_assert_msg(r.status == 0 && r.err[0] == '\0', "groff -ww: exit %d\n%s", r.status, r.err);
    tu_run_free(&r);
}
END_TEST

Suite *help_suite(void)
{
    Suite *s = suite_create("help");
    TCase *tc = tcase_create("help");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, overview_lists_the_commands);
    tcase_add_loop_test(tc, each_command_has_its_help, 0, NCOMMANDS);
    tcase_add_test(tc, help_shows_the_commands_options);
    tcase_add_test(tc, help_of_no_command);
    tcase_add_test(tc, usage_error_points_to_its_help);
    tcase_add_test(tc, man_page_has_every_command_and_option);
    tcase_add_test(tc, man_page_is_escaped);
    tcase_add_test(tc, man_escapes_roff);
    tcase_add_test(tc, man_page_renders_clean);
    suite_add_tcase(s, tc);
    return s;
}
