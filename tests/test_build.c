/* SPDX-License-Identifier: MIT */
/* test_build.c -- the Makefile's header dependencies (-MMD -MP): a change to
 * a header rebuilds the objects that include it, and only those.  Asked of
 * make itself with `make -n -W HEADER` (what would run were HEADER new),
 * in the build directory of the binaries under test; an object that `make -n`
 * would rebuild anyway (a source edited since the build) proves nothing
 * either way and is not asserted on. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The build directory: that of $BRDFFIT_CLI (make test sets it), else "build". */
static void build_dir(char *buf, size_t len)
{
    const char *cli = getenv("BRDFFIT_CLI");
    snprintf(buf, len, "%s", cli && *cli ? cli : "build/brdffit");
    char *slash = strrchr(buf, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(buf, len, "build");
}

/* What `make -n [-W header]` would run (its output) into out. */
static void would_run(const char *header, const char *goal, char *out, size_t len)
{
    char dir[512], cmd[2048], what[600] = "";
    build_dir(dir, sizeof dir);
    if (header)
        snprintf(what, sizeof what, "-W '%s'", header);
    snprintf(cmd, sizeof cmd, "make -s -n %s BUILD='%s' '%s/%s' 2>&1", what, dir, dir, goal);
    FILE *p = popen(cmd, "r");
    ck_assert_ptr_nonnull(p);
    size_t n = fread(out, 1, len - 1, p);
    out[n] = '\0';
    pclose(p);
}

static int compiles(const char *out, const char *source)
{
    char pat[256];
    snprintf(pat, sizeof pat, "-c -o ");
    for (const char *q = out; (q = strstr(q, pat)) != NULL; q++) {
        const char *eol = strchr(q, '\n');
        size_t n = eol ? (size_t)(eol - q) : strlen(q);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line - 1 ? n : sizeof line - 1), q);
        if (strstr(line, source))
            return 1;
    }
    return 0;
}

static char out[1 << 16], base[1 << 16];

/* The start of the output, for a message. */
static const char *head(const char *text)
{
    static char buf[1200];
    snprintf(buf, sizeof buf, "%.1100s", text);
    return buf;
}

#define REBUILDS(src) ck_assert_msg(compiles(out, src), "%s not rebuilt; make -n said:\n%s", src, head(out))
#define KEEPS(src)                                                                              \
    ck_assert_msg(compiles(base, src) || !compiles(out, src), "%s rebuilt; make -n said:\n%s", \
                  src, head(out))

START_TEST(header_change_rebuilds_its_includers)
{
    would_run(NULL, "libbrdffit.a", base, sizeof base);

    /* the He model: the evaluators and the pass, which include it */
    would_run("kernels/bf_he_model.h", "libbrdffit.a", out, sizeof out);
    REBUILDS("src/lib/models.c");
    REBUILDS("src/lib/render.c");
    REBUILDS("src/lib/pass_host.c");
    KEEPS("src/lib/status.c");
    KEEPS("src/lib/fit/problem.c");
    KEEPS("src/lib/merl_file.c");

    /* He's pass machinery: the pass, not the evaluators (which do not include it) */
    would_run("kernels/bf_he_rows.h", "libbrdffit.a", out, sizeof out);
    REBUILDS("src/lib/pass_host.c");
    KEEPS("src/lib/models.c");
    KEEPS("src/lib/render.c");
    KEEPS("src/lib/status.c");

    /* the grid header: the table files, not the pass */
    would_run("src/lib/grid.h", "libbrdffit.a", out, sizeof out);
    REBUILDS("src/lib/grid.c");
    REBUILDS("src/lib/merl_file.c");
    REBUILDS("src/lib/lookup.c");
    KEEPS("src/lib/pass.c");
    KEEPS("src/lib/context.c");

    /* the fit's own header: the fit's files, in their subfolder, and no other */
    would_run("src/lib/fit/fit_internal.h", "libbrdffit.a", out, sizeof out);
    REBUILDS("src/lib/fit/map.c");
    REBUILDS("src/lib/fit/problem.c");
    REBUILDS("src/lib/fit/screen.c");
    REBUILDS("src/lib/fit/refine.c");
    REBUILDS("src/lib/fit/api.c");
    KEEPS("src/lib/linear.c");
    KEEPS("src/lib/refine_select.c");

    /* the public header: everything of the library */
    would_run("include/brdffit.h", "libbrdffit.a", out, sizeof out);
    REBUILDS("src/lib/status.c");
    REBUILDS("src/lib/pass.c");
}
END_TEST

/* Occurrences of the bytes of text in the file at path; -1 when it cannot be read. */
static long count_in_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t n = strlen(text), have = 0, cap = 1 << 16;
    char *buf = malloc(cap + n);
    long count = 0;
    size_t got;
    while (buf && (got = fread(buf + have, 1, cap, f)) > 0) {
        size_t end = have + got;
        for (size_t i = 0; i + n <= end; i++)
            if (memcmp(buf + i, text, n) == 0)
                count++;
        /* keep the last n - 1 bytes: a match across two reads */
        have = end < n - 1 ? end : n - 1;
        memmove(buf, buf + end - have, have);
    }
    free(buf);
    fclose(f);
    return count;
}

/* Fault injection (BRDFFIT_FAULT, src/cli/record/fault.c) is in the tests' build of
 * the program and not in the one that is installed: the installed program
 * has not the variable's name; the faults build has it. */
START_TEST(fault_injection_only_in_the_test_build)
{
    long shipped = count_in_file(tu_cli(), "BRDFFIT_FAULT");
    long faults = count_in_file(tu_cli_faults(), "BRDFFIT_FAULT");
    ck_assert_msg(shipped == 0, "%s: BRDFFIT_FAULT %ld times (-1: unreadable)", tu_cli(), shipped);
    ck_assert_msg(faults > 0, "%s: BRDFFIT_FAULT %ld times (-1: unreadable)", tu_cli_faults(),
                  faults);
}
END_TEST

Suite *build_suite(void)
{
    Suite *s = suite_create("build");
    TCase *tc = tcase_create("build");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, header_change_rebuilds_its_includers);
    tcase_add_test(tc, fault_injection_only_in_the_test_build);
    suite_add_tcase(s, tc);
    return s;
}
