/* SPDX-License-Identifier: MIT */
/* test_messages.c -- the program's messages for inputs of the wrong kind
 * (a list given to batch without '@', a directory or a text file given to
 * fit), model names in any case, and the note on a terminal while a model's
 * kernels are compiled (on a pseudo-terminal; never on a pipe or a file). */
#define _DEFAULT_SOURCE
#include "cli.h"
#include "testutil.h"

#include <check.h>
#include <errno.h>
#include <fcntl.h>
#include <pty.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define expect_status TU_EXPECT_STATUS

#define expect_in(text, want) ck_assert_msg(strstr((text), (want)) != NULL, "no '%s' in:\n%s", (want), (text))

/* A text file listing one (missing) table, its path in buf. */
static const char *list_file(char *buf, size_t len)
{
    ck_assert_ptr_nonnull(tu_tmpfile(buf, len));
    const char text[] = "/data/merl/alum-bronze.binary\n";
    ck_assert_int_eq(tu_write_bytes(buf, text, sizeof text - 1), 0);
    return buf;
}

START_TEST(batch_list_without_at)
{
    char list[512], args[2048], want[1200], out[] = "/tmp/brdffit-messages-XXXXXX";
    list_file(list, sizeof list);
    ck_assert_ptr_nonnull(mkdtemp(out));
    snprintf(args, sizeof args, "batch '%s' --out '%s/report'", list, out);
    tu_run_out r = tu_run_cli("", args);
    expect_status(r, 2, args);
    snprintf(want, sizeof want, "%s is a text file, not a MERL table: did you mean @%s ", list, list);
    expect_in(r.err, want);
    tu_run_free(&r);
    unlink(list);
    rmdir(out);
}
END_TEST

START_TEST(fit_directory_suggests_batch)
{
    char dir[] = "/tmp/brdffit-messages-XXXXXX", args[600], want[1200];
    ck_assert_ptr_nonnull(mkdtemp(dir));
    snprintf(args, sizeof args, "fit '%s'", dir);
    tu_run_out r = tu_run_cli("", args);
    expect_status(r, 1, args);
    snprintf(want, sizeof want, "brdffit batch %s --out DIR", dir);
    expect_in(r.err, want);
    tu_run_free(&r);
    rmdir(dir);
}
END_TEST

/* fit on a text file: the library's message names it as not a table and shows
 * its first bytes; the program then suggests batch @FILE. */
START_TEST(fit_text_file_is_not_a_table)
{
    char list[512], args[600], want[1200];
    list_file(list, sizeof list);
    snprintf(args, sizeof args, "fit '%s'", list);
    tu_run_out r = tu_run_cli("", args);
    expect_status(r, 1, args);
    snprintf(want, sizeof want, "%s: not a MERL table: it begins with \"/data/merl/a\"", list);
    expect_in(r.err, want);
    snprintf(want, sizeof want, "brdffit batch @%s --out DIR", list);
    expect_in(r.err, want);
    ck_assert_msg(strstr(r.err, "dims") == NULL, "%s", r.err);
    tu_run_free(&r);
    unlink(list);
}
END_TEST

/* --model and eval take names in any case, as the library's lookup does. */
START_TEST(model_names_in_any_case)
{
    const char *dirs = "--wi 0 0.6 0.8 --wo 0.3 0 0.9539392";
    char a[256], b[256];
    snprintf(a, sizeof a, "eval GGX 0.1 0.1 0.1 0.5 0.5 0.5 0.04 0.2 %s", dirs);
    snprintf(b, sizeof b, "eval ggx 0.1 0.1 0.1 0.5 0.5 0.5 0.04 0.2 %s", dirs);
    tu_run_out ra = tu_run_cli("", a), rb = tu_run_cli("", b);
    expect_status(ra, 0, a);
    expect_status(rb, 0, b);
    ck_assert_str_eq(ra.out, rb.out);
    tu_run_free(&ra);
    tu_run_free(&rb);
    /* names accepted: the run gets as far as the (missing) file */
    static const char *const ok[] = { "--model Cook-Torrance", "--model Ward,HE", "--model ALL",
                                      "--model=Ashikhmin_Shirley,ggx" };
    for (size_t k = 0; k < sizeof ok / sizeof ok[0]; k++) {
        snprintf(a, sizeof a, "fit %s /nonexistent/x.binary", ok[k]);
        tu_run_out r = tu_run_cli("", a);
        expect_status(r, 1, a);
        expect_in(r.err, "cannot open");
        tu_run_free(&r);
    }
    tu_run_out r = tu_run_cli("", "fit --model Phong /nonexistent/x.binary");
    expect_status(r, 2, "--model Phong");
    expect_in(r.err, "unknown model 'Phong'");
    tu_run_free(&r);
}
END_TEST

/* ------------------------------------------------------------------ the kernel note */

/* An OpenCL context, or NULL (with a note) when there is no device. */
static brdffit_context *opencl_context(void)
{
    brdffit_context *ctx = NULL;
    brdffit_error err;
    if (tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) != BRDFFIT_OK) {
        fprintf(stderr, "note: no OpenCL device (%s): the kernel note is not checked\n", err.message);
        return NULL;
    }
    return ctx;
}

/* What was written to the master side of a pseudo-terminal so far (the
 * writer closed), NUL-terminated, into buf. */
static size_t read_pty(int master, char *buf, size_t len)
{
    size_t got = 0;
    for (;;) {
        ssize_t n = read(master, buf + got, len - 1 - got);
        if (n > 0)
            got += (size_t)n;
        else if (n < 0 && errno == EINTR)
            continue;
        else
            break; /* EIO: the other side is closed */
        if (got == len - 1)
            break;
    }
    buf[got] = '\0';
    return got;
}

/* The note is printed to a terminal only, and only for a model not yet built. */
START_TEST(kernel_note_only_on_a_terminal)
{
    brdffit_context *ctx = opencl_context();
    if (!ctx)
        return;
    FILE *file = tmpfile();
    ck_assert_int_eq(kernel_note_begin(file, ctx, BRDFFIT_WARD), 0);
    ck_assert_int_eq(ftell(file), 0);
    fclose(file);

    int master, slave;
    ck_assert_int_eq(openpty(&master, &slave, NULL, NULL, NULL), 0);
    FILE *tty = fdopen(slave, "w");
    ck_assert_ptr_nonnull(tty);
    ck_assert_int_eq(kernel_note_begin(tty, ctx, BRDFFIT_WARD), 1);
    kernel_note_end(tty, 1, ctx, BRDFFIT_WARD); /* not built: no time, the line erased */
    ck_assert_int_eq(brdffit_context_prepare(ctx, BRDFFIT_WARD, NULL), BRDFFIT_OK);
    ck_assert_int_eq(kernel_note_begin(tty, ctx, BRDFFIT_WARD), 0); /* built: nothing */
    fclose(tty);
    char got[4096];
    read_pty(master, got, sizeof got);
    close(master);
    expect_in(got, "brdffit: compiling the OpenCL kernels of ward, once per machine (cached in ");
    const char *end = strstr(got, ")...");
    ck_assert_msg(end && strcmp(end, ")...\r\033[K") == 0, "%s", got);
    brdffit_context_free(ctx);
}
END_TEST

/* The table fitted below (a ../shared one). */
static const char *table_path(char *buf, size_t len)
{
    const char *p = tu_merl_table("blue-rubber", buf, len);
    ck_assert_msg(p != NULL, "../shared/tools/merl-table blue-rubber failed");
    return p;
}

/* `brdffit fit` with stderr on a file (as on a pipe): no note. */
START_TEST(no_kernel_note_on_a_pipe)
{
    char table[1024], args[1200];
    snprintf(args, sizeof args, "fit '%s' --model ward --starts 1", table_path(table, sizeof table));
    tu_run_out r = tu_run_cli("", args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "compiling") == NULL && strstr(r.err, "\033[") == NULL, "%s", r.err);
    tu_run_free(&r);
}
END_TEST

/* `brdffit fit` with stderr on a pseudo-terminal: the note, then its time or
 * its line erased. */
START_TEST(kernel_note_on_a_terminal)
{
    brdffit_context *ctx = opencl_context();
    if (!ctx)
        return;
    brdffit_context_free(ctx);
    char table[1024];
    table_path(table, sizeof table);
    const char *cli = getenv("BRDFFIT_CLI");
    int master, slave;
    ck_assert_int_eq(openpty(&master, &slave, NULL, NULL, NULL), 0);
    pid_t pid = fork();
    ck_assert_int_ne(pid, -1);
    if (pid == 0) {
        int null = open("/dev/null", O_RDWR);
        dup2(null, 0);
        dup2(null, 1);
        dup2(slave, 2);
        close(master);
        execl(cli && *cli ? cli : "./build/brdffit", "brdffit", "fit", table, "--model", "ward",
              "--starts", "1", (char *)NULL);
        _exit(127);
    }
    close(slave);
    char got[8192];
    read_pty(master, got, sizeof got);
    close(master);
    int status = 0;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 0, "status %d: %s", status, got);
    expect_in(got, "brdffit: compiling the OpenCL kernels of ward, once per machine (cached in ");
    const char *end = strstr(got, ")...");
    ck_assert_msg(end && (strncmp(end, ")...\r\033[K", 8) == 0 || strstr(end, " s\r\n")), "%s", got);
}
END_TEST

Suite *messages_suite(void)
{
    Suite *s = suite_create("messages");
    TCase *tc = tcase_create("messages");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, batch_list_without_at);
    tcase_add_test(tc, fit_directory_suggests_batch);
    tcase_add_test(tc, fit_text_file_is_not_a_table);
    tcase_add_test(tc, model_names_in_any_case);
    tcase_add_test(tc, kernel_note_only_on_a_terminal);
    suite_add_tcase(s, tc);
    TCase *tf = tcase_create("messages_fit");
    tcase_set_timeout(tf, 300);
    tcase_set_tags(tf, TU_NEEDS_SHARED);
    tcase_add_test(tf, no_kernel_note_on_a_pipe);
    tcase_add_test(tf, kernel_note_on_a_terminal);
    suite_add_tcase(s, tf);
    return s;
}
