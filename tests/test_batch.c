/* SPDX-License-Identifier: MIT */
/* test_batch.c -- `brdffit batch`, `report` and `score` ($BRDFFIT_CLI): every
 * file of the report written, its HTML checked by a strict parser written
 * here and every link followed, resume after SIGKILL at several points equal
 * to a clean run, shards merged by `report` equal to one run, failure rows,
 * signals, an unwritable or full --out, changed settings and files, the
 * progress line, `score` against the batch's own numbers. */
#define _DEFAULT_SOURCE
#include "testutil.h"
#include "batch.h"
#include "cli.h"

#include <check.h>
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* The models and settings the tests fit: quick ones, so that a batch of three
 * tables takes seconds. */
#define FAST "--model ward,blinn-phong --starts 1"

static const char *cli(void)
{
    const char *p = getenv("BRDFFIT_CLI");
    return p && *p ? p : "./build/brdffit";
}

static char *slurp(const char *path)
{
    return tu_slurp(path);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

typedef tu_run_out run_out;

/* Run `sh -c "PREFIX brdffit ARGS"` (env settings or ulimit in prefix). */
static run_out run_with(const char *prefix, const char *args)
{
    return tu_run_cli(prefix, args);
}

static run_out run(const char *args)
{
    return run_with("", args);
}

static void run_free(run_out *r)
{
    tu_run_free(r);
}

#define expect_status(r, want, what)                                                         \
    ck_assert_msg((r).status == (want), "%s: exit %d, expected %d\nstdout:\n%s\nstderr:\n%s", \
                  (what), (r).status, (want), (r).out, (r).err)

/* ------------------------------------------------------------------ inputs */

static const char *const names[3] = { "blue-rubber", "alum-bronze", "chrome" };

/* A fresh temporary directory into buf. */
static const char *tmpdir(char *buf, size_t len)
{
    const char *t = getenv("TMPDIR");
    snprintf(buf, len, "%s/brdffit-batch-XXXXXX", t && *t ? t : "/tmp");
    ck_assert_ptr_nonnull(mkdtemp(buf));
    return buf;
}

/* A test's temporary directory removed at its end (a failed test stops
 * before: its directory stays, to be looked at).  Each test's reports take
 * 4-41 MB; left behind, they would grow TMPDIR by ~140 MB a `make test`. */
static void tmpdir_remove(const char *dir)
{
    ck_assert_msg(tu_remove_tree(dir) == 0, "could not remove %s", dir);
}

/* DIR/in with the three tables (symbolic links) and, when bad, a truncated one. */
static void make_inputs(const char *dir, int bad)
{
    char in[1024], link[1200], path[1024];
    snprintf(in, sizeof in, "%s/in", dir);
    ck_assert_int_eq(mkdir(in, 0755), 0);
    for (int i = 0; i < 3; i++) {
        ck_assert_msg(tu_merl_table(names[i], path, sizeof path) != NULL, "merl-table %s", names[i]);
        snprintf(link, sizeof link, "%s/%s.binary", in, names[i]);
        ck_assert_int_eq(symlink(path, link), 0);
    }
    if (bad) {
        snprintf(link, sizeof link, "%s/broken.binary", in);
        static const unsigned char head[12] = { 90, 0, 0, 0, 90, 0, 0, 0, 180, 0, 0, 0 };
        ck_assert_int_eq(tu_write_bytes(link, head, sizeof head), 0);
    }
}

/* fits.tsv without its comment line, the seconds column and the energy
 * columns (albedo_*, which a journal of an earlier version does not have):
 * what must be equal between runs ("timings aside"). */
static char *fits_sans_timing(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/fits.tsv", dir);
    char *s = slurp(path);
    ck_assert_msg(s != NULL, "no %s", path);
    char *out = malloc(strlen(s) + 1);
    ck_assert_ptr_nonnull(out);
    size_t n = 0;
    int seconds_col = -1, albedo_col = -1;
    for (char *line = s; *line;) {
        char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        if (line[0] != '#') {
            int col = 0;
            for (size_t i = 0; i < len; i++) {
                if (seconds_col < 0 && strncmp(line + i, "seconds\t", 8) == 0 && (i == 0 || line[i - 1] == '\t'))
                    seconds_col = col;
                if (albedo_col < 0 && strncmp(line + i, "\talbedo_", 8) == 0)
                    albedo_col = col + 1;
                if ((col != seconds_col || seconds_col < 0) && (albedo_col < 0 || col < albedo_col))
                    out[n++] = line[i];
                if (line[i] == '\t')
                    col++;
            }
            out[n++] = '\n';
        }
        line += len + (end ? 1 : 0);
    }
    out[n] = '\0';
    free(s);
    ck_assert_int_ge(seconds_col, 0);
    return out;
}

static int count_lines(const char *s, const char *needle)
{
    int n = 0;
    for (const char *p = s; (p = strstr(p, needle)) != NULL; p++)
        n++;
    return n;
}

/* ------------------------------------------------------------------ a strict HTML checker */

/* What a page links to (href and src values). */
typedef struct links {
    char v[512][512];
    int n;
} links;

static int is_void(const char *name)
{
    static const char *const v[] = { "meta", "img", "br", "hr", "link", "input", "col", "wbr" };
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        if (strcmp(name, v[i]) == 0)
            return 1;
    return 0;
}

/* An entity at p ("&amp;" ...): its length, or 0 when it is not one HTML knows here. */
static int entity_len(const char *p)
{
    static const char *const named[] = { "&amp;", "&lt;", "&gt;", "&quot;", "&apos;", "&#39;", "&#34;" };
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
        if (strncmp(p, named[i], strlen(named[i])) == 0)
            return (int)strlen(named[i]);
    if (p[1] == '#') {
        int k = 2;
        while (isdigit((unsigned char)p[k]))
            k++;
        return k > 2 && p[k] == ';' ? k + 1 : 0;
    }
    return 0;
}

/* Check the text between tags: no '<', entities known. */
static int check_text(const char *s, const char *end, char *why)
{
    for (const char *p = s; p < end; p++)
        if (*p == '&' && !entity_len(p)) {
            snprintf(why, 256, "bare '&' at '%.20s'", p);
            return -1;
        }
    return 0;
}

/* One start tag at p (after '<'): its name, its attributes (links collected). */
static const char *start_tag(const char *p, char *name, links *L, char *why)
{
    int n = 0;
    while (isalnum((unsigned char)*p) && n < 31)
        name[n++] = (char)tolower((unsigned char)*p++);
    name[n] = '\0';
    if (n == 0) {
        snprintf(why, 256, "bad tag at '%.20s'", p);
        return NULL;
    }
    for (;;) {
        while (*p == ' ' || *p == '\n' || *p == '\t')
            p++;
        if (*p == '>')
            return p + 1;
        char an[64];
        int k = 0;
        while ((isalnum((unsigned char)*p) || *p == '-') && k < 63)
            an[k++] = *p++;
        an[k] = '\0';
        if (k == 0 || p[0] != '=' || p[1] != '"') {
            snprintf(why, 256, "attribute not name=\"value\" in <%s> at '%.20s'", name, p);
            return NULL;
        }
        p += 2;
        const char *v = p;
        while (*p && *p != '"' && *p != '<')
            p++;
        if (*p != '"') {
            snprintf(why, 256, "unterminated attribute %s in <%s>", an, name);
            return NULL;
        }
        if (check_text(v, p, why) != 0)
            return NULL;
        if ((strcmp(an, "href") == 0 || strcmp(an, "src") == 0) && L->n < 512)
            snprintf(L->v[L->n++], sizeof L->v[0], "%.*s", (int)(p - v), v);
        p++;
    }
}

/* 0 when the page is well-formed HTML as written here (doctype, balanced
 * elements, void elements unclosed, quoted attributes, known entities). */
static int html_check(const char *path, links *L, char *why)
{
    char *doc = slurp(path);
    L->n = 0;
    if (!doc) {
        snprintf(why, 256, "cannot read");
        return -1;
    }
    char stack[64][32];
    int depth = 0, rc = -1, elements = 0;
    const char *p = doc;
    if (strncmp(p, "<!DOCTYPE html>", 15) != 0) {
        snprintf(why, 256, "no <!DOCTYPE html> first");
        goto done;
    }
    p += 15;
    while (*p) {
        const char *lt = strchr(p, '<');
        const char *end = lt ? lt : p + strlen(p);
        if (check_text(p, end, why) != 0)
            goto done;
        if (!lt)
            break;
        if (lt[1] == '/') {
            char name[32];
            int n = 0;
            const char *q = lt + 2;
            while (isalnum((unsigned char)*q) && n < 31)
                name[n++] = (char)tolower((unsigned char)*q++);
            name[n] = '\0';
            if (*q != '>' || depth == 0 || strcmp(stack[depth - 1], name) != 0) {
                snprintf(why, 256, "</%s> does not close <%s>", name, depth ? stack[depth - 1] : "");
                goto done;
            }
            depth--;
            p = q + 1;
            continue;
        }
        char name[32];
        const char *q = start_tag(lt + 1, name, L, why);
        if (!q)
            goto done;
        elements++;
        if (depth == 0 && (strcmp(name, "html") != 0 || elements != 1)) {
            snprintf(why, 256, "<%s> outside <html>", name);
            goto done;
        }
        p = q;
        if (is_void(name))
            continue;
        if (strcmp(name, "style") == 0 || strcmp(name, "script") == 0) {
            const char *close = strstr(p, strcmp(name, "style") == 0 ? "</style>" : "</script>");
            if (!close) {
                snprintf(why, 256, "<%s> not closed", name);
                goto done;
            }
            p = close + strlen(name) + 3;
            continue;
        }
        if (depth == 64) {
            snprintf(why, 256, "nested too deep");
            goto done;
        }
        snprintf(stack[depth++], 32, "%s", name);
    }
    if (depth != 0) {
        snprintf(why, 256, "<%s> not closed at the end", stack[depth - 1]);
        goto done;
    }
    rc = 0;
done:
    free(doc);
    return rc;
}

static void url_decode(const char *in, char *out, size_t len)
{
    size_t n = 0;
    for (const char *p = in; *p && n + 1 < len; p++) {
        if (p[0] == '%' && isxdigit((unsigned char)p[1]) && isxdigit((unsigned char)p[2])) {
            char h[3] = { p[1], p[2], 0 };
            out[n++] = (char)strtol(h, NULL, 16);
            p += 2;
        } else {
            out[n++] = *p;
        }
    }
    out[n] = '\0';
}

/* The page at dir/page parses; every link is relative and its file exists.
 * Returns how many links it has. */
static int check_page(const char *dir, const char *page)
{
    char path[2048], why[256] = "";
    static links L;
    snprintf(path, sizeof path, "%s/%s", dir, page);
    ck_assert_msg(html_check(path, &L, why) == 0, "%s: %s", path, why);
    char pdir[2048];
    snprintf(pdir, sizeof pdir, "%s", path);
    *strrchr(pdir, '/') = '\0';
    for (int i = 0; i < L.n; i++) {
        const char *h = L.v[i];
        ck_assert_msg(!strstr(h, "://") && h[0] != '/' && strncmp(h, "data:", 5) != 0,
                      "%s links outside the report: %s", path, h);
        char rel[1024], target[4096];
        url_decode(h, rel, sizeof rel);
        snprintf(target, sizeof target, "%s/%s", pdir, rel);
        ck_assert_msg(exists(target), "%s links to %s, which does not exist", path, target);
    }
    return L.n;
}

START_TEST(html_checker_self_test)
{
    char dir[512], p[1024], why[256];
    static links L;
    tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/a.html", dir);
    const char *good = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><style>td{x:1}</style>"
                       "</head><body><p>a &amp; b<img src=\"x%20y.png\"></p></body></html>\n";
    ck_assert_int_eq(tu_write_bytes(p, good, strlen(good)), 0);
    ck_assert_msg(html_check(p, &L, why) == 0, "%s", why);
    ck_assert_int_eq(L.n, 1);
    ck_assert_str_eq(L.v[0], "x%20y.png");
    static const char *const bad[] = {
        "<html><body></body></html>",                                    /* no doctype */
        "<!DOCTYPE html><html><body><p></body></html>",                  /* unclosed p */
        "<!DOCTYPE html><html><body>a & b</body></html>",                /* bare & */
        "<!DOCTYPE html><html><body><a href=x>y</a></body></html>",      /* unquoted */
        "<!DOCTYPE html><html><body></body></html><p></p>",              /* after html */
        "<!DOCTYPE html><html><body><b><i></b></i></body></html>",       /* crossed */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ck_assert_int_eq(tu_write_bytes(p, bad[i], strlen(bad[i])), 0);
        ck_assert_msg(html_check(p, &L, why) != 0, "accepted: %s", bad[i]);
    }
    unlink(p);
    rmdir(dir);
}
END_TEST

/* ------------------------------------------------------------------ the report */

static void check_material_files(const char *out, const char *name)
{
    static const char *const files[] = { "index.html", "params.tsv", "params.json" };
    char path[2048];
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/%s/%s", out, name, files[i]);
        ck_assert_msg(exists(path), "missing %s", path);
    }
    snprintf(path, sizeof path, "%s/%s/params.json", out, name);
    char *j = slurp(path);
    ck_assert_msg(tu_json_object_line(j), "%s is not valid JSON:\n%s", path, j);
    free(j);
    snprintf(path, sizeof path, "%s/index.html", name);
    ck_assert_int_ge(check_page(out, path), 3);
}

/* The pages of the batch of batch_writes_every_file in out: the index (the
 * matrix marks one best per fitted material, failure rows say why, the
 * settings are there, the published Error is shown), a material's page (the
 * renders, differences, plots and EXR files of each model) and its
 * params.tsv. */
static void check_batch_pages(const char *out)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/index.html", out);
    char *idx = slurp(path);
    ck_assert_int_eq(count_lines(idx, "class=\"best\""), 3);
    ck_assert_int_eq(count_lines(idx, "not fitted: "), 2);
    ck_assert_msg(strstr(idx, "ngan-l2") && strstr(idx, ">flat<") &&
                      strstr(idx, brdffit_version()) && strstr(idx, "median Error") &&
                      strstr(idx, "headline.svg"),
                  "%s", idx);
    ck_assert_msg(strstr(idx, "published Error ") && strstr(idx, "\xc2\xa0\xc3\x97"),
                  "no published Error and ratio in the matrix");
    ck_assert_msg(strstr(idx, "median ratio to published"), "no median ratio in the Models table");
    ck_assert_msg(strstr(idx, "computed here: the published parameters scored on the tables given"),
                  "the settings do not say where the published Errors come from");
    free(idx);
    snprintf(path, sizeof path, "%s/chrome/index.html", out);
    char *page = slurp(path);
    static const char *const linked[] = {
        "src=\"reference.png\"", "src=\"ward.png\"", "src=\"ward-diff.png\"",
        "src=\"blinn-phong.png\"", "src=\"plot-measured.svg\"", "src=\"plot-ward.svg\"",
        "src=\"plot-blinn-phong.svg\"", "href=\"reference.exr\"", "href=\"ward.exr\"",
        "src=\"ward-flip.png\"", "src=\"diff-scale.svg\"", "src=\"flip-scale.svg\"",
        "Blue: the model is darker than the reference", "Its mean over the image is the image error",
    };
    for (size_t i = 0; i < sizeof linked / sizeof linked[0]; i++)
        ck_assert_msg(strstr(page, linked[i]), "chrome's page has no %s", linked[i]);
    ck_assert_msg(strstr(page, "Ward: "), "no caption with the Error");
    free(page);
    snprintf(path, sizeof path, "%s/blue-rubber/params.tsv", out);
    char *pt = slurp(path);
    ck_assert_msg(strstr(pt, "\nblue-rubber\tward\t") && strstr(pt, "\nblue-rubber\tblinn-phong\t"),
                  "%s", pt);
    free(pt);
}

START_TEST(batch_writes_every_file)
{
    char dir[512], args[8192], list[1024], pub[1024], out[1024];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 1);
    snprintf(list, sizeof list, "%s/list", dir);
    char body[1200];
    snprintf(body, sizeof body, "# a comment\n%s/nope.binary\n\n", dir);
    ck_assert_int_eq(tu_write_bytes(list, body, strlen(body)), 0);
    tu_shared("data/ngan2005-fits.tsv", pub, sizeof pub);
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(args, sizeof args, "batch '%s/in' @'%s' --out '%s' " FAST " --scale flat --published '%s'",
             dir, list, out, pub);
    run_out r = run(args);
    expect_status(r, 1, args); /* two tables failed; the others are fitted */
    char want[1200];
    snprintf(want, sizeof want, "%s/index.html\n", out);
    ck_assert_str_eq(r.out, want);
    ck_assert_msg(strstr(r.err, "broken.binary") && strstr(r.err, "truncated"), "%s", r.err);
    ck_assert_msg(strstr(r.err, "nope.binary"), "%s", r.err);

    static const char *const top[] = { "index.html", "fits.tsv", "headline.svg", "journal.jsonl" };
    char path[2048];
    for (int i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/%s", out, top[i]);
        ck_assert_msg(exists(path), "missing %s", path);
    }
    for (int i = 0; i < 3; i++)
        check_material_files(out, names[i]);
    check_material_files(out, "broken");
    check_material_files(out, "nope");
    ck_assert_int_ge(check_page(out, "index.html"), 3 + 2 + 2);

    /* every journal line is one JSON object */
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *jl = slurp(path);
    int nrec = 0;
    for (char *line = strtok(jl, "\n"); line; line = strtok(NULL, "\n"), nrec++)
        ck_assert_msg(tu_json_object_line(line), "journal line %d is not a JSON object: %s", nrec + 1, line);
    free(jl);
    ck_assert_int_ge(nrec, 3 * 2 + 2);

    /* the headline figure: well-formed SVG, one marker per fit and per legend entry */
    tu_xml_doc svg;
    snprintf(path, sizeof path, "%s/headline.svg", out);
    ck_assert_msg(tu_xml_load(path, &svg) == 0, "%s is not well-formed XML", path);
    ck_assert_int_eq(tu_xml_count(&svg, "circle"), 3 * 2 + 2);
    ck_assert_int_ge(tu_xml_count(&svg, "polyline"), 2);
    tu_xml_free(&svg);

    /* fits.tsv: 3 x 2 fits and two failure rows saying why */
    char *fits = fits_sans_timing(out);
    ck_assert_int_eq(count_lines(fits, "\n"), 1 + 3 * 2 + 2);
    ck_assert_msg(strstr(fits, "broken\t-\t") && strstr(fits, "truncated"), "%s", fits);
    ck_assert_msg(strstr(fits, "nope\t-\t") && strstr(fits, "cannot open"), "%s", fits);
    free(fits);

    check_batch_pages(out);
    run_free(&r);
    tmpdir_remove(dir);
}
END_TEST

/* ------------------------------------------------------------------ resume, shards */

/* A clean run of the three tables into DIR/NAME; returns fits.tsv sans timing. */
static char *clean_run(const char *dir, const char *name, const char *extra)
{
    char args[4096];
    snprintf(args, sizeof args, "batch '%s/in' --out '%s/%s' " FAST " %s", dir, dir, name, extra);
    run_out r = run(args);
    expect_status(r, 0, args);
    run_free(&r);
    char out[1024];
    snprintf(out, sizeof out, "%s/%s", dir, name);
    return fits_sans_timing(out);
}

static int journal_count(const char *out, const char *kind)
{
    char path[1024], needle[64];
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    snprintf(needle, sizeof needle, "{\"kind\":\"%s\"", kind);
    char *j = slurp(path);
    int n = j ? count_lines(j, needle) : -1;
    free(j);
    return n;
}

/* No fit is journaled twice: every (material, model) at most once. */
static void no_duplicate_fits(const char *out)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = slurp(path);
    ck_assert_ptr_nonnull(j);
    for (int i = 0; i < 3; i++) {
        static const char *const models[2] = { "ward", "blinn-phong" };
        for (int k = 0; k < 2; k++) {
            char key[256];
            snprintf(key, sizeof key, "\"material\":\"%s\"", names[i]);
            int n = 0;
            for (char *line = j; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
                char *end = strchr(line, '\n');
                char save = end ? *end : 0;
                if (end)
                    *end = '\0';
                char mk[64];
                snprintf(mk, sizeof mk, "\"model\":\"%s\"", models[k]);
                if (strstr(line, "{\"kind\":\"fit\"") && strstr(line, key) && strstr(line, mk))
                    n++;
                if (end)
                    *end = save;
            }
            ck_assert_msg(n == 1, "%s %s journaled %d times", names[i], models[k], n);
        }
    }
    free(j);
}

START_TEST(resume_after_sigkill_equals_clean_run)
{
    char dir[512], args[4096], out[1024];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    char *clean = clean_run(dir, "clean", "");
    snprintf(out, sizeof out, "%s/killed", dir);
    snprintf(args, sizeof args, "batch '%s/in' --out '%s' " FAST, dir, out);

    /* 1: killed right after its second record was synced */
    run_out r = tu_run_cli_faults("BRDFFIT_FAULT=record:2", args);
    expect_status(r, 128 + SIGKILL, "killed after record 2");
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 2);
    /* 2: killed after a material's renders and plots were written, before their record */
    r = tu_run_cli_faults("BRDFFIT_FAULT=asset:1", args);
    expect_status(r, 128 + SIGKILL, "killed after the renders");
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "assets"), 0);
    /* 3: killed in the middle of writing its second record: a torn last line */
    r = tu_run_cli_faults("BRDFFIT_FAULT=torn:2", args);
    expect_status(r, 128 + SIGKILL, "killed mid-record");
    run_free(&r);
    char path[1200];
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = slurp(path);
    ck_assert_msg(j[0] && j[strlen(j) - 1] != '\n', "no torn last line:\n%s", j);
    free(j);
    /* 4: killed while writing the pages of the report */
    r = tu_run_cli_faults("BRDFFIT_FAULT=page:2", args);
    expect_status(r, 128 + SIGKILL, "killed in the report");
    ck_assert_msg(strstr(r.err, "cut short"), "the torn line is not reported:\n%s", r.err);
    run_free(&r);
    /* then the same command to the end */
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "done (journaled)"), "nothing was resumed:\n%s", r.err);
    run_free(&r);

    char *resumed = fits_sans_timing(out);
    ck_assert_str_eq(resumed, clean);
    ck_assert_int_eq(journal_count(out, "fit"), 3 * 2);
    ck_assert_int_eq(journal_count(out, "assets"), 3);
    no_duplicate_fits(out);
    check_page(out, "index.html");
    for (int i = 0; i < 3; i++)
        check_material_files(out, names[i]);
    free(resumed);
    free(clean);
    tmpdir_remove(dir);
}
END_TEST

START_TEST(shards_merged_by_report_equal_one_run)
{
    char dir[512], args[8192];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    char *clean = clean_run(dir, "clean", "");
    /* shard 1 (two materials) without reading the second ahead: the same fits */
    char *s1 = clean_run(dir, "s1", "--shard 1/2 --no-read-ahead");
    char *s2 = clean_run(dir, "s2", "--shard=2/2");
    /* sorted: alum-bronze, blue-rubber, chrome: shard 1 has the 1st and 3rd */
    ck_assert_msg(strstr(s1, "alum-bronze\t") && strstr(s1, "chrome\t") && !strstr(s1, "blue-rubber\t"), "%s", s1);
    ck_assert_msg(strstr(s2, "blue-rubber\t") && !strstr(s2, "chrome\t") && !strstr(s2, "alum-bronze\t"), "%s", s2);
    snprintf(args, sizeof args, "report '%s/s1' '%s/s2' --out '%s/merged'", dir, dir, dir);
    run_out r = run(args);
    expect_status(r, 0, args);
    run_free(&r);
    char merged_dir[1024];
    snprintf(merged_dir, sizeof merged_dir, "%s/merged", dir);
    char *merged = fits_sans_timing(merged_dir);
    ck_assert_str_eq(merged, clean);
    check_page(merged_dir, "index.html");
    for (int i = 0; i < 3; i++)
        check_material_files(merged_dir, names[i]);

    /* shards made with other settings are not merged: the difference is said */
    char *s3 = clean_run(dir, "s3", "--shard 2/2 --cutoff 70");
    snprintf(args, sizeof args, "report '%s/s1' '%s/s3' --out '%s/bad'", dir, dir, dir);
    r = run(args);
    expect_status(r, 1, args);
    ck_assert_msg(strstr(r.err, "cutoff 70"), "%s", r.err);
    run_free(&r);
    free(s3);
    free(merged);
    free(s1);
    free(s2);
    free(clean);
    tmpdir_remove(dir);
}
END_TEST

/* ------------------------------------------------------------------ signals, output errors */

START_TEST(sigterm_keeps_what_is_done)
{
    char dir[512], out[1024], jpath[1200];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(jpath, sizeof jpath, "%s/journal.jsonl", out);
    char in[1024];
    snprintf(in, sizeof in, "%s/in", dir);
    pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        int devnull = open("/dev/null", O_WRONLY);
        dup2(devnull, 1);
        dup2(devnull, 2);
        execl(cli(), cli(), "batch", in, "--out", out, "--model", "ward,blinn-phong",
              "--starts", "1", (char *)NULL);
        _exit(127);
    }
    /* wait for the first journaled fit, then SIGTERM */
    int seen = 0;
    for (int t = 0; t < 1200 && !seen; t++) {
        char *j = slurp(jpath);
        seen = j && strstr(j, "\n") != NULL;
        free(j);
        if (!seen)
            usleep(100000);
    }
    ck_assert_msg(seen, "no journal record within 120 s");
    kill(pid, SIGTERM);
    int st = 0;
    ck_assert_int_eq(waitpid(pid, &st, 0), pid);
    ck_assert_msg(WIFEXITED(st) && WEXITSTATUS(st) == 128 + SIGTERM,
                  "exit %d (signalled %d): expected %d", WIFEXITED(st) ? WEXITSTATUS(st) : -1,
                  WIFSIGNALED(st) ? WTERMSIG(st) : 0, 128 + SIGTERM);
    char *j = slurp(jpath);
    ck_assert_msg(j[strlen(j) - 1] == '\n', "the journal ends in a torn line");
    int before = journal_count(out, "fit");
    ck_assert_int_ge(before, 1);
    ck_assert_int_lt(before, 6);
    free(j);
    check_page(out, "index.html"); /* the index of what was done */
    char args[4096];
    snprintf(args, sizeof args, "batch '%s' --out '%s' " FAST, in, out);
    run_out r = run(args);
    expect_status(r, 0, args);
    run_free(&r);
    if (journal_count(out, "fit") != 6) {
        j = slurp(jpath);
        fprintf(stderr, "journal:\n%s\n", j);
        free(j);
    }
    ck_assert_int_eq(journal_count(out, "fit"), 6);
    no_duplicate_fits(out);
    tmpdir_remove(dir);
}
END_TEST

START_TEST(unwritable_or_full_out_stops_at_once)
{
    char dir[512], args[4096], file[1024];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    char *clean = clean_run(dir, "clean", ""); /* also warms PoCL's kernel cache */

    /* --out under a regular file */
    snprintf(file, sizeof file, "%s/plain", dir);
    ck_assert_int_eq(tu_write_bytes(file, "x", 1), 0);
    snprintf(args, sizeof args, "batch '%s/in' --out '%s/sub' " FAST, dir, file);
    run_out r = run(args);
    expect_status(r, 1, args);
    ck_assert_msg(strstr(r.err, "plain/sub") && strstr(r.err, "Not a directory"), "%s", r.err);
    run_free(&r);

    /* a full disk: every file limited to 2 MB (ulimit -f 4096 blocks of 512 in sh),
     * the journal already 2 MB less 3000 bytes long (records of another material):
     * the first record of the run fits, the second cannot be written */
    char out[1024], jpath[1200], cpath[1200];
    snprintf(out, sizeof out, "%s/full", dir);
    ck_assert_int_eq(mkdir(out, 0755), 0);
    snprintf(jpath, sizeof jpath, "%s/journal.jsonl", out);
    snprintf(cpath, sizeof cpath, "%s/clean/journal.jsonl", dir);
    char *cj = slurp(cpath);
    char *nl = strchr(cj, '\n');
    ck_assert_ptr_nonnull(nl);
    nl[1] = '\0';
    char *name = strstr(cj, "\"material\":\"alum-bronze\"");
    ck_assert_ptr_nonnull(name);
    memcpy(name, "\"material\":\"padding-mat\"", 25); /* same length */
    const size_t limit = 4096 * 512, pad_to = limit - 3000, len = strlen(cj);
    FILE *jf = fopen(jpath, "wb");
    ck_assert_ptr_nonnull(jf);
    size_t have = 0;
    while (have + len <= pad_to) {
        fputs(cj, jf);
        have += len;
    }
    fprintf(jf, "%*s\n", (int)(pad_to - have - 1), ""); /* a blank line: not a record */
    ck_assert_int_eq(fclose(jf), 0);
    free(cj);
    int padded = journal_count(out, "fit");
    snprintf(args, sizeof args, "batch '%s/in' --out '%s' --no-render --no-plot " FAST, dir, out);
    r = run_with("ulimit -f 4096;", args);
    expect_status(r, 1, "batch with ulimit -f 4096");
    ck_assert_msg(strstr(r.err, "journal.jsonl") && strstr(r.err, "File too large") &&
                      strstr(r.err, "stopped"),
                  "%s", r.err);
    ck_assert_msg(!strstr(r.err, "[2/3]"), "it went on after the failure:\n%s", r.err);
    run_free(&r);
    char *j = slurp(jpath);
    ck_assert_msg(j[strlen(j) - 1] == '\n', "the journal ends in a torn line");
    free(j);
    ck_assert_int_eq(journal_count(out, "fit"), padded + 1);
    r = run(args); /* room again: it goes on from the record kept */
    expect_status(r, 0, args);
    run_free(&r);
    char *after = fits_sans_timing(out);
    ck_assert_str_eq(after, clean);
    no_duplicate_fits(out);
    free(after);
    free(clean);
    tmpdir_remove(dir);
}
END_TEST

/* ------------------------------------------------------------------ settings and files that change */

static void perturb_table(const char *from, const char *to)
{
    brdffit_table *t = NULL;
    brdffit_error err;
    ck_assert_int_eq(brdffit_table_read(from, &t, &err), BRDFFIT_OK);
    double *v = brdffit_table_values(t);
    for (size_t i = 0; i < 3 * (size_t)BRDFFIT_MERL_BINS; i += 997)
        if (v[i] > 0)
            v[i] *= 1.5;
    ck_assert_int_eq(brdffit_table_write(t, to, &err), BRDFFIT_OK);
    brdffit_table_free(t);
}

START_TEST(changed_settings_and_files_are_refitted)
{
    char dir[512], args[4096], out[1024];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    free(clean_run(dir, "out", ""));
    snprintf(out, sizeof out, "%s/out", dir);
    ck_assert_int_eq(journal_count(out, "fit"), 6);

    snprintf(args, sizeof args, "batch '%s/in' --out '%s' --model ward,blinn-phong --starts 2", dir, out);
    run_out r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "other settings") && strstr(r.err, "starts 1 (this run: 2"), "%s",
                  r.err);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 12);
    char fpath[1200];
    snprintf(fpath, sizeof fpath, "%s/fits.tsv", out);
    char *fits = slurp(fpath);
    ck_assert_msg(strstr(fits, "starts 2,"), "the report is not of the new settings:\n%s", fits);
    ck_assert_int_eq(count_lines(fits, "\n"), 2 + 3 * 2);
    free(fits);

    /* chrome's table changes: only it is fitted again */
    char link[1200], path[1024];
    snprintf(link, sizeof link, "%s/in/chrome.binary", dir);
    ck_assert_msg(tu_merl_table("chrome", path, sizeof path) != NULL, "merl-table chrome");
    unlink(link);
    perturb_table(path, link);
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "chrome: the table changed"), "%s", r.err);
    ck_assert_msg(strstr(r.err, "blue-rubber: done (journaled)"), "%s", r.err);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 14);

    /* a journal written by another program version: said, and everything refitted */
    char jpath[1200], cmd[4096];
    snprintf(jpath, sizeof jpath, "%s/journal.jsonl", out);
    snprintf(cmd, sizeof cmd, "sed -i 's/\"version\":\"[^\"]*\"/\"version\":\"0.0.1-old\"/' '%s'", jpath);
    ck_assert_int_eq(system(cmd), 0);
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "program version 0.0.1-old (this run: "), "%s", r.err);
    ck_assert_msg(!strstr(r.err, "done (journaled)"), "reused a record of another version:\n%s", r.err);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 20);
    tmpdir_remove(dir);
}
END_TEST

/* ------------------------------------------------------------------ progress */

START_TEST(progress_lines)
{
    char dir[512], args[4096];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    snprintf(args, sizeof args, "batch '%s/in' --out '%s/a' --model ward --starts 1", dir, dir);
    run_out r = run(args); /* stderr is a file: one plain line per material */
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "[1/3] alum-bronze: done") && strstr(r.err, "[3/3] chrome: done"),
                  "%s", r.err);
    ck_assert_msg(!strchr(r.err, '\r') && !strchr(r.err, '\033'), "terminal codes in a file:\n%s", r.err);
    run_free(&r);
    snprintf(args, sizeof args, "batch '%s/in' --out '%s/b' --model ward --starts 1 --quiet", dir, dir);
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(!strstr(r.err, "[1/3]"), "--quiet printed progress:\n%s", r.err);
    run_free(&r);

    /* on a terminal (script(1) gives the program a pseudo-terminal): the live line */
    char cmd[8192], log[1200];
    snprintf(log, sizeof log, "%s/tty.log", dir);
    snprintf(cmd, sizeof cmd,
             "script -qec \"'%s' batch '%s/in' --out '%s/c' --model ward --starts 1\" '%s' "
             ">/dev/null 2>&1 </dev/null",
             cli(), dir, dir, log);
    int rc = system(cmd);
    ck_assert_msg(rc != -1 && WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "%s: %d", cmd, rc);
    char *t = slurp(log);
    ck_assert_ptr_nonnull(t);
    ck_assert_msg(strstr(t, "\r\033[K[1/3] alum-bronze ward") && strstr(t, "ETA") &&
                      strstr(t, "elapsed") && strstr(t, "fits 0/3"),
                  "no live line:\n%s", t);
    free(t);
    tmpdir_remove(dir);
}
END_TEST

/* ------------------------------------------------------------------ score, demo */

/* The field of column `column` (named in the header line) of the fits.tsv
 * row of material and model, into buf. */
static const char *fits_field(const char *out, const char *material, const char *model,
                              const char *column, char *buf, size_t len)
{
    char path[1200], line[8192];
    snprintf(path, sizeof path, "%s/fits.tsv", out);
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    char *fld[40];
    int n, col = -1;
    const char *found = NULL;
    if ((n = tu_tsv_next(f, line, sizeof line, fld, 40)) > 0)
        for (int i = 0; i < n; i++)
            if (strcmp(fld[i], column) == 0)
                col = i;
    ck_assert_msg(col >= 2, "no column %s in the header of %s", column, path);
    while ((n = tu_tsv_next(f, line, sizeof line, fld, 40)) > 0)
        if (n > col && strcmp(fld[0], material) == 0 && strcmp(fld[1], model) == 0) {
            snprintf(buf, len, "%s", fld[col]);
            found = buf;
            break;
        }
    fclose(f);
    ck_assert_msg(found != NULL, "no %s %s row in %s", material, model, path);
    return found;
}

/* The Error `score` prints for model (its line "model  error"). */
static double score_error(const char *output, const char *model)
{
    char key[64];
    snprintf(key, sizeof key, "\n%s ", model);
    const char *p = strstr(output, key);
    ck_assert_msg(p != NULL, "no %s line in:\n%s", model, output);
    return strtod(p + strlen(key), NULL);
}

START_TEST(score_agrees_with_the_batch)
{
    char dir[512], args[8192], pub[1024], out[1024], table[1024];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    tu_shared("data/ngan2005-fits.tsv", pub, sizeof pub);
    char extra[1200];
    snprintf(extra, sizeof extra, "--scale flat --published '%s'", pub);
    free(clean_run(dir, "out", extra));
    snprintf(out, sizeof out, "%s/out", dir);
    ck_assert_ptr_nonnull(tu_merl_table("blue-rubber", table, sizeof table));

    /* the fitted parameters (10 digits) score the fitted Error */
    static const char *const cols[7] = { "d_r", "d_g", "d_b", "s_r", "s_g", "s_b", "p0" };
    char p[12][64], params[1024] = "";
    for (int c = 0; c < 7; c++) {
        fits_field(out, "blue-rubber", "ward", cols[c], p[c], sizeof p[c]);
        strcat(params, c ? "," : "");
        strcat(params, p[c]);
    }
    char e_fit[64], e_pub[64];
    fits_field(out, "blue-rubber", "ward", "error", e_fit, sizeof e_fit);
    fits_field(out, "blue-rubber", "ward", "published_error", e_pub, sizeof e_pub);
    snprintf(args, sizeof args, "score '%s' --scale flat --model ward --params %s", table, params);
    run_out r = run(args);
    expect_status(r, 0, args);
    double e = score_error(r.out, "ward");
    ck_assert_msg(tu_reldiff(e, strtod(e_fit, NULL)) < 1e-7, "score %.10g, batch %s", e, e_fit);
    run_free(&r);

    /* the published parameters: the batch's published Error */
    snprintf(args, sizeof args, "score '%s' --scale flat --fits '%s' --model ward,blinn-phong",
             table, pub);
    r = run(args);
    expect_status(r, 0, args);
    e = score_error(r.out, "ward");
    ck_assert_msg(tu_reldiff(e, strtod(e_pub, NULL)) < 1e-9, "score %.10g, batch %s", e, e_pub);
    (void)score_error(r.out, "blinn-phong"); /* both rows of blue-rubber are scored */
    run_free(&r);

    /* usage errors */
    snprintf(args, sizeof args, "score '%s' --model ward --params 1,2,3", table);
    r = run(args);
    expect_status(r, 2, args);
    ck_assert_msg(strstr(r.err, "7 comma-separated numbers"), "%s", r.err);
    run_free(&r);
    snprintf(args, sizeof args, "score '%s' --params 1,2,3,4,5,6,7", table);
    r = run(args);
    expect_status(r, 2, args);
    run_free(&r);
    tmpdir_remove(dir);
}
END_TEST

/* A published-fits file stating another scale than --scale is refused,
 * naming both, and nothing is written; with --allow-scale-mismatch the
 * comparison is made and said on every page. */
START_TEST(published_scale_mismatch)
{
    char dir[512], args[8192], pub[1024], out[1024], path[2048];
    tmpdir(dir, sizeof dir);
    make_inputs(dir, 0);
    tu_shared("data/ngan2005-fits.tsv", pub, sizeof pub); /* "# scale: flat" */
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(args, sizeof args, "batch '%s/in' --out '%s' " FAST " --no-render --no-plot "
             "--published '%s'", dir, out, pub);
    run_out r = run(args);
    expect_status(r, 2, args);
    ck_assert_msg(strstr(r.err, "states '# scale: flat'") && strstr(r.err, "--scale standard") &&
                      strstr(r.err, "pass --scale flat") && strstr(r.err, "--allow-scale-mismatch"),
                  "%s", r.err);
    run_free(&r);
    snprintf(path, sizeof path, "%s/index.html", out);
    ck_assert_msg(!exists(path), "a refused batch wrote %s", path);

    strcat(args, " --allow-scale-mismatch");
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "warning: --published") && strstr(r.err, "not fitted to"), "%s", r.err);
    run_free(&r);
    check_page(out, "index.html");
    for (int i = -1; i < 3; i++) {
        if (i < 0)
            snprintf(path, sizeof path, "%s/index.html", out);
        else
            snprintf(path, sizeof path, "%s/%s/index.html", out, names[i]);
        char *page = slurp(path);
        ck_assert_msg(page && strstr(page, "class=\"warn\">Warning: ") &&
                          strstr(page, "states &#39;# scale: flat&#39;") &&
                          strstr(page, "not fitted to"),
                      "%s has no warning of the scale mismatch", path);
        free(page);
    }
    tmpdir_remove(dir);
}
END_TEST

START_TEST(demo_batch_prints_its_index)
{
    char dir[512], args[4096], out[1024], want[1200];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/demo", dir);
    snprintf(args, sizeof args, "batch --demo --out '%s' --model cook-torrance --starts 1", out);
    run_out r = run(args);
    expect_status(r, 0, args);
    snprintf(want, sizeof want, "%s/index.html\n", out);
    ck_assert_str_eq(r.out, want);
    run_free(&r);
    check_page(out, "index.html");
    check_material_files(out, "synthetic-alum-bronze-ct");
    char e[64];
    fits_field(out, "synthetic-alum-bronze-ct", "cook-torrance", "error", e, sizeof e);
    ck_assert_msg(strtod(e, NULL) < 1e-6, "the generating model fits with Error %s", e);
    /* again: everything is in the journal */
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "done (journaled)"), "%s", r.err);
    run_free(&r);
    tmpdir_remove(dir);
}
END_TEST

/* The journal's fit record, the fit record of `demo --json` (a fit and a
 * failure) and those of params.json have the same keys: one schema
 * (docs/fit-record.md). */
START_TEST(one_record_schema_everywhere)
{
    char dir[512], args[4096], out[1024], path[1200], keys[4096], want[4096];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/demo", dir);
    snprintf(args, sizeof args, "batch --demo --out '%s' --model ward --starts 1 --no-render --no-plot",
             out);
    run_out r = run(args);
    expect_status(r, 0, args);
    run_free(&r);

    /* fit --json: a fit of the demo material, and a missing file's failure */
    r = run("demo --json --model ward --starts 1");
    expect_status(r, 0, "demo --json");
    ck_assert_msg(tu_json_object_line(strtok(r.out, "\n")), "%s", r.out);
    ck_assert_int_gt(tu_json_keys(r.out, want, sizeof want), 25);
    run_free(&r);
    r = run("fit --json --model ward /nonexistent-brdffit-dir/gone.binary");
    expect_status(r, 1, "fit --json of a missing file");
    ck_assert_int_eq(tu_json_keys(r.out, keys, sizeof keys) > 0, 1);
    ck_assert_str_eq(keys, want);
    run_free(&r);

    /* the journal: every line */
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = slurp(path);
    ck_assert_ptr_nonnull(j);
    int lines = 0;
    for (char *line = strtok(j, "\n"); line; line = strtok(NULL, "\n"), lines++) {
        ck_assert_msg(tu_json_keys(line, keys, sizeof keys) > 0, "%s", line);
        ck_assert_str_eq(keys, want);
    }
    ck_assert_int_ge(lines, 1);
    free(j);

    /* params.json: its fit record */
    snprintf(path, sizeof path, "%s/synthetic-alum-bronze-ct/params.json", out);
    char *pj = slurp(path);
    ck_assert_msg(pj && tu_json_object_line(strtok(pj, "\n")), "%s", pj ? pj : path);
    const char *fit = tu_json_element(tu_json_member(pj, "fits"), 0);
    ck_assert_msg(fit != NULL, "no fit in %s", pj);
    ck_assert_msg(tu_json_keys(fit, keys, sizeof keys) > 0, "%s", pj);
    ck_assert_str_eq(keys, want);
    free(pj);
    tmpdir_remove(dir);
}
END_TEST

/* Append a copy of the journal's first fit record that succeeded, with this
 * status text, status code and message. */
static void append_fit_as(const char *out, const char *status, int code, const char *message)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = slurp(path);
    ck_assert_ptr_nonnull(j);
    static const char ok[] = "\"status\":\"ok\",\"status_code\":0,\"message\":\"\"";
    char *fit = NULL, *at = NULL;
    for (char *line = strtok(j, "\n"); line && !at; line = strtok(NULL, "\n"))
        if (strncmp(line, "{\"kind\":\"fit\"", 13) == 0 && (at = strstr(line, ok)) != NULL)
            fit = line;
    ck_assert_msg(at != NULL, "no fit that succeeded in %s", path);
    *at = '\0';
    /* a failed fit has no Error, as the program writes it (the journal
     * ignores one that has) */
    char *rest = at + strlen(ok), *e = strstr(rest, ",\"error\":");
    ck_assert_ptr_nonnull(e);
    *e = '\0';
    char *after = e + 9 + strcspn(e + 9, ",}");
    char *albedo = strstr(after, ",\"albedo\":"); /* a failed fit has no albedo (the last members) */
    if (albedo)
        strcpy(albedo, "}");
    FILE *f = fopen(path, "a");
    ck_assert_ptr_nonnull(f);
    fprintf(f, "%s\"status\":\"%s\",\"status_code\":%d,\"message\":\"%s\"%s,\"error\":null%s\n",
            fit, status, code, message, rest, after);
    ck_assert_int_eq(fclose(f), 0);
    free(j);
}

/* Resume decides by the status code, not by the words: a failed fit whose
 * text is today's wording of a transient failure but whose code is not is
 * kept; one whose code is transient but whose words are not is fitted again. */
START_TEST(resume_decides_by_status_code)
{
    char dir[512], args[4096], out[1024];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/demo", dir);
    snprintf(args, sizeof args, "batch --demo --out '%s' --model ward --starts 1 --no-render --no-plot",
             out);
    run_out r = run(args);
    expect_status(r, 0, args);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 1);

    append_fit_as(out, brdffit_strerror(BRDFFIT_E_OPENCL), BRDFFIT_E_FIT_FAILED,
                  "OpenCL error");
    r = run(args);
    /* kept, and counted as the failure it is */
    ck_assert_msg(strstr(r.err, "failed (journaled)"), "a fit failed on the data was redone:\n%s", r.err);
    ck_assert_int_ne(r.status, 0);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 2);

    append_fit_as(out, "the device went away (reworded)", BRDFFIT_E_OPENCL, "reworded");
    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(!strstr(r.err, "(journaled)"), "a transient failure was kept:\n%s", r.err);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 4);
    tmpdir_remove(dir);
}
END_TEST

/* r as the journal line of the earlier form (before fit_record.h): "file"
 * {path, size, hash}, "ok", the "status" text, "on_bound". */
static void write_old_form(FILE *f, const fit_record *r)
{
    static const char *const kinds[] = { "fit", "failure", "published", "assets" };
    fprintf(f, "{\"kind\":\"%s\",\"material\":", kinds[r->kind]);
    json_string(f, r->material);
    fputs(",\"file\":{\"path\":", f);
    json_string(f, r->id.path);
    fprintf(f, ",\"size\":%lld,\"hash\":", r->id.size);
    json_string(f, r->id.hash);
    fputs("},\"settings\":{\"version\":", f);
    json_string(f, r->settings.version);
    fputs(",\"scale\":", f);
    json_string(f, r->settings.scale);
    fputs(",\"cutoff_deg\":", f);
    json_number(f, r->settings.cutoff_deg);
    fprintf(f, ",\"starts\":%d},\"model\":", r->settings.starts);
    json_string(f, r->model);
    fprintf(f, ",\"ok\":%s,\"status\":", fr_ok(r) ? "true" : "false");
    json_string(f, fr_status_text(r));
    fputs(",\"message\":", f);
    json_string(f, r->message);
    if (r->kind == FR_FIT || r->kind == FR_PUBLISHED) {
        fputs(",\"d\":", f);
        json_numbers(f, r->params.d, 3);
        fputs(",\"s\":", f);
        json_numbers(f, r->params.s, 3);
        fputs(",\"p\":", f);
        json_numbers(f, r->params.p, r->nparams);
        fputs(",\"lambda_um\":", f);
        json_numbers(f, r->params.lambda_um, 3);
        fputs(",\"error\":", f);
        json_number(f, r->error);
    }
    if (r->kind == FR_FIT) {
        /* on_bound: "n=lower,d_b=0" */
        char list[128], names[256] = "";
        brdffit_model m;
        ck_assert_int_eq(brdffit_model_from_name(r->model, &m, NULL), BRDFFIT_OK);
        fr_at_bound_text(m, r->at_bound, ",", list, sizeof list);
        for (char *save = NULL, *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
            int linear = strlen(t) == 3 && (t[0] == 'd' || t[0] == 's') && t[1] == '_';
            size_t o = strlen(names);
            snprintf(names + o, sizeof names - o, "%s%s=%s", o ? "," : "", t, linear ? "0" : "lower");
        }
        fprintf(f, ",\"iterations\":%d,\"passes\":%d,\"cminpack_info\":%d,\"seconds\":",
                r->iterations, r->passes, r->cminpack_info);
        json_number(f, r->seconds);
        fprintf(f, ",\"samples\":%lld,\"on_bound\":\"%s\",\"backend\":", r->samples, names);
        json_string(f, r->backend);
    }
    if (r->kind == FR_ASSETS) {
        fputs(",\"assets_key\":", f);
        json_string(f, r->assets_key);
        fputs(",\"assets\":", f);
        json_string(f, r->assets);
    }
    fputs("}\n", f);
}

/* tsv (fits_sans_timing's) with its fit rows' Errors under each metric
 * (columns error_ngan_l2, error_log, error_cube_root) as a record without
 * them has them: "-".  A new string. */
static char *errors_blanked(const char *tsv)
{
    char *out = malloc(strlen(tsv) + 1);
    ck_assert_ptr_nonnull(out);
    size_t n = 0;
    int first = -1; /* the column of error_ngan_l2; the next two follow */
    for (const char *line = tsv; *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        int col = 0, header = first < 0;
        for (size_t i = 0; i <= len; i++) {
            if (i == len || line[i] == '\t') {
                if (header && col >= 0 && i >= 13 && strncmp(line + i - 13, "error_ngan_l2", 13) == 0)
                    first = col;
                col++;
            }
        }
        col = 0;
        for (size_t i = 0; i < len; i++) {
            int blank = !header && first >= 0 && col >= first && col < first + 3;
            if (line[i] == '\t') {
                if (blank)
                    out[n++] = '-';
                out[n++] = '\t';
                col++;
            } else if (!blank) {
                out[n++] = line[i];
            }
        }
        out[n++] = '\n';
        line += len + (end ? 1 : 0);
    }
    out[n] = '\0';
    return out;
}

/* An --out directory whose journal an earlier version wrote resumes: its
 * records are read (nothing fitted or drawn again) and the report is the same. */
START_TEST(old_form_journal_resumes)
{
    char dir[512], args[4096], out[1024], path[1200];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/demo", dir);
    snprintf(args, sizeof args, "batch --demo --out '%s' --model ward,he --starts 1 --no-render", out);
    run_out r = run(args);
    expect_status(r, 0, args);
    run_free(&r);
    char *clean = fits_sans_timing(out);

    /* the journal rewritten in the earlier form */
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = slurp(path);
    ck_assert_ptr_nonnull(j);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    int n = 0, assets = 0;
    static fit_record rec;
    for (char *line = strtok(j, "\n"); line; line = strtok(NULL, "\n"), n++) {
        ck_assert_msg(fr_read_json(line, &rec, FR_NEED_KEY) == 0, "%s", line);
        assets += rec.kind == FR_ASSETS;
        write_old_form(f, &rec);
    }
    ck_assert_int_eq(fclose(f), 0);
    free(j);
    ck_assert_int_eq(n, 3);
    ck_assert_int_eq(assets, 1);
    j = slurp(path);
    ck_assert_msg(strstr(j, "\"ok\":true") && !strstr(j, "status_code"), "%s", j);
    free(j);

    r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.err, "done (journaled)") && !strstr(r.err, "not journal records"),
                  "the earlier journal was not resumed:\n%s", r.err);
    run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 2);
    ck_assert_int_eq(journal_count(out, "assets"), 1);
    char *resumed = fits_sans_timing(out);
    char *without = errors_blanked(clean); /* the earlier form had no Errors under each metric */
    ck_assert_str_eq(resumed, without);
    free(without);
    free(resumed);
    free(clean);
    tmpdir_remove(dir);
}
END_TEST

Suite *batch_suite(void)
{
    Suite *s = suite_create("batch");
    TCase *tc = tcase_create("batch");
    tcase_set_timeout(tc, 900);
    tcase_add_test(tc, html_checker_self_test);
    tcase_add_test(tc, batch_writes_every_file);
    tcase_add_test(tc, resume_after_sigkill_equals_clean_run);
    tcase_add_test(tc, shards_merged_by_report_equal_one_run);
    tcase_add_test(tc, sigterm_keeps_what_is_done);
    tcase_add_test(tc, unwritable_or_full_out_stops_at_once);
    tcase_add_test(tc, changed_settings_and_files_are_refitted);
    tcase_add_test(tc, progress_lines);
    tcase_add_test(tc, score_agrees_with_the_batch);
    tcase_add_test(tc, published_scale_mismatch);
    tcase_add_test(tc, demo_batch_prints_its_index);
    tcase_add_test(tc, one_record_schema_everywhere);
    tcase_add_test(tc, resume_decides_by_status_code);
    tcase_add_test(tc, old_form_journal_resumes);
    suite_add_tcase(s, tc);
    return s;
}
