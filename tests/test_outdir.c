/* SPDX-License-Identifier: MIT */
/* test_outdir.c -- what the program writes stays inside its output directory:
 * links planted at every name batch, render, plot and report write (the
 * files, the temporaries' old fixed names, a material's directory, the
 * journal) are never followed; a material name from a journal that is not
 * one path component is refused by report, naming the file and line; one
 * batch per directory at a time (the lock), report against a batch; modes
 * from the umask; a dangling --out link said to be one; names with tabs and
 * line breaks escaped in the TSV files. */
#define _DEFAULT_SOURCE
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "fit_record.h"
#include "outdir.h"

#include <check.h>
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#define DEMO "synthetic-alum-bronze-ct"
#define FAST "--model ward --starts 1"

static const char *tmpdir(char *buf, size_t len)
{
    const char *t = getenv("TMPDIR");
    snprintf(buf, len, "%s/brdffit-outdir-XXXXXX", t && *t ? t : "/tmp");
    ck_assert_ptr_nonnull(mkdtemp(buf));
    return buf;
}

#define expect_exit(r, want, what)                                                          \
    ck_assert_msg((r).status == (want), "%s: exit %d, expected %d\nstdout:\n%s\nstderr:\n%s", \
                  (what), (r).status, (want), (r).out, (r).err)

/* A file "victim" in dir with known bytes, its path in buf. */
static const char *victim(const char *dir, char *buf, size_t len)
{
    snprintf(buf, len, "%s/victim", dir);
    ck_assert_int_eq(tu_write_bytes(buf, "victim\n", 7), 0);
    return buf;
}

static void victim_intact(const char *path)
{
    char *v = tu_slurp(path);
    ck_assert_ptr_nonnull(v);
    ck_assert_msg(strcmp(v, "victim\n") == 0, "%s was written through a link: %.80s", path, v);
    free(v);
}

static void plant(const char *target, const char *dir, const char *name)
{
    char link[2048];
    snprintf(link, sizeof link, "%s/%s", dir, name);
    ck_assert_msg(symlink(target, link) == 0, "symlink %s", link);
}

/* ------------------------------------------------------------------ names, TSV text */

START_TEST(names_and_tsv_text)
{
    ck_assert_ptr_null(od_name_problem("alum-bronze"));
    ck_assert_ptr_null(od_name_problem("tab\there\nnewline"));
    ck_assert_ptr_nonnull(od_name_problem(""));
    ck_assert_ptr_nonnull(od_name_problem("."));
    ck_assert_ptr_nonnull(od_name_problem(".."));
    ck_assert_ptr_nonnull(od_name_problem("../../escaped"));
    ck_assert_ptr_nonnull(od_name_problem("a/b"));
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    const char *in[] = { "a\tb", "a\nb", "a\rb", "a b", "a\\tb", "-", "", NULL };
    for (int i = 0; in[i]; i++) {
        fr_write_tsv_text(f, in[i]);
        putc('|', f);
    }
    fr_write_tsv_text(f, NULL);
    fclose(f);
    /* every text distinct, none with a tab or line break */
    ck_assert_str_eq(buf, "a\\tb|a\\nb|a\\rb|a b|a\\\\tb|\\-|-|-");
    free(buf);
}
END_TEST

/* ------------------------------------------------------------------ links planted */

static const char *const top_names[] = { "index.html", "fits.tsv", "headline.svg", NULL };
static const char *const material_names[] = {
    "index.html", "params.tsv", "params.json", "reference.exr", "reference.png", "ward.exr",
    "ward.png", "ward-diff.png", "renders.json", "plot-measured.svg", "plot-ward.svg", NULL
};

/* A batch of the demo into OUT = dir/NAME, where prepare(OUT) planted links. */
static tu_run_out demo_batch(const char *out)
{
    char args[2048];
    snprintf(args, sizeof args, "batch --demo --out '%s' " FAST, out);
    return tu_run_cli("", args);
}

/* The names the temporaries had (NAME.tmp) linked to the victim: every file
 * is written, the victim is not.  Temporaries a killed run left (regular
 * files .NAME.XXXXXXXXXXXX.tmp) are removed; other files stay. */
START_TEST(old_temporary_names_linked)
{
    char dir[512], v[1024], out[1024], mdir[1200];
    tmpdir(dir, sizeof dir);
    victim(dir, v, sizeof v);
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(mdir, sizeof mdir, "%s/" DEMO, out);
    ck_assert_int_eq(mkdir(out, 0777), 0);
    ck_assert_int_eq(mkdir(mdir, 0777), 0);
    char name[300];
    for (int i = 0; top_names[i]; i++) {
        snprintf(name, sizeof name, "%s.tmp", top_names[i]);
        plant(v, out, name);
    }
    for (int i = 0; material_names[i]; i++) {
        snprintf(name, sizeof name, "%s.tmp", material_names[i]);
        plant(v, mdir, name);
    }
    char left[2][1400], kept[1400];
    snprintf(left[0], sizeof left[0], "%s/.index.html.aB3dE5gH7jK9.tmp", out);
    snprintf(left[1], sizeof left[1], "%s/.ward.png.Zz0Yy1Xx2Ww3.tmp", mdir);
    snprintf(kept, sizeof kept, "%s/.notes.tmp", out);
    for (int k = 0; k < 2; k++)
        ck_assert_int_eq(tu_write_bytes(left[k], "x", 1), 0);
    ck_assert_int_eq(tu_write_bytes(kept, "x", 1), 0);
    tu_run_out r = demo_batch(out);
    expect_exit(r, 0, "batch with links at NAME.tmp");
    tu_run_free(&r);
    victim_intact(v);
    for (int k = 0; k < 2; k++)
        ck_assert_msg(access(left[k], F_OK) != 0, "%s is left", left[k]);
    ck_assert_int_eq(access(kept, F_OK), 0);
    tu_remove_tree(dir);
}
END_TEST

/* A link at each name a batch writes, one run each: the run stops saying so,
 * the victim is untouched, the link stays a link. */
START_TEST(links_at_every_batch_name)
{
    char dir[512], v[1024], out[1024], mdir[1200], link[1400];
    tmpdir(dir, sizeof dir);
    victim(dir, v, sizeof v);
    for (int pass = 0; pass < 2; pass++) {
        const char *const *names = pass ? material_names : top_names;
        for (int i = 0; names[i]; i++) {
            snprintf(out, sizeof out, "%s/out-%d-%d", dir, pass, i);
            snprintf(mdir, sizeof mdir, "%s/" DEMO, out);
            ck_assert_int_eq(mkdir(out, 0777), 0);
            ck_assert_int_eq(mkdir(mdir, 0777), 0);
            plant(v, pass ? mdir : out, names[i]);
            tu_run_out r = demo_batch(out);
            expect_exit(r, 1, names[i]);
            ck_assert_msg(strstr(r.err, names[i]) && strstr(r.err, "symbolic link (not followed)"),
                          "%s: %s", names[i], r.err);
            tu_run_free(&r);
            victim_intact(v);
            snprintf(link, sizeof link, "%s/%s", pass ? mdir : out, names[i]);
            struct stat st;
            ck_assert_int_eq(lstat(link, &st), 0);
            ck_assert(S_ISLNK(st.st_mode));
        }
    }
    tu_remove_tree(dir);
}
END_TEST

/* The journal linked elsewhere (it would be appended to), and a material's
 * directory linked elsewhere (its 11 files would land there). */
START_TEST(linked_journal_and_material_directory)
{
    char dir[512], v[1024], out[1024], elsewhere[1024];
    tmpdir(dir, sizeof dir);
    victim(dir, v, sizeof v);
    snprintf(out, sizeof out, "%s/out1", dir);
    ck_assert_int_eq(mkdir(out, 0777), 0);
    plant(v, out, "journal.jsonl");
    tu_run_out r = demo_batch(out);
    expect_exit(r, 1, "batch with a linked journal");
    ck_assert_msg(strstr(r.err, "journal.jsonl: it is a symbolic link (not followed)"), "%s", r.err);
    tu_run_free(&r);
    victim_intact(v);

    snprintf(out, sizeof out, "%s/out2", dir);
    snprintf(elsewhere, sizeof elsewhere, "%s/elsewhere", dir);
    ck_assert_int_eq(mkdir(out, 0777), 0);
    ck_assert_int_eq(mkdir(elsewhere, 0777), 0);
    plant(elsewhere, out, DEMO);
    r = demo_batch(out);
    expect_exit(r, 1, "batch with a linked material directory");
    ck_assert_msg(strstr(r.err, DEMO ": it is a symbolic link (not followed)"), "%s", r.err);
    tu_run_free(&r);
    DIR *d = opendir(elsewhere);
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d)) != NULL)
        n += e->d_name[0] != '.';
    closedir(d);
    ck_assert_msg(n == 0, "%d files landed in the linked directory", n);
    tu_remove_tree(dir);
}
END_TEST

/* render and plot: a link at each of their names and at the old NAME.tmp. */
START_TEST(links_in_render_and_plot)
{
    char dir[512], v[1024], out[1024], args[2048], name[300];
    tmpdir(dir, sizeof dir);
    victim(dir, v, sizeof v);
    static const char *const names[] = { "reference.exr", "reference.png", "ward.exr", "ward.png",
                                         "ward-diff.png", "renders.json", "plot-measured.svg",
                                         "plot-ward.svg", NULL };
    for (int i = 0; names[i]; i++) {
        const char *cmd = strncmp(names[i], "plot", 4) == 0 ? "plot" : "render";
        const char *size = cmd[0] == 'p' ? "--points 20" : "--size 16";
        snprintf(out, sizeof out, "%s/tmp-%d", dir, i);
        ck_assert_int_eq(mkdir(out, 0777), 0);
        snprintf(name, sizeof name, "%s.tmp", names[i]);
        plant(v, out, name);
        snprintf(args, sizeof args, "%s '%s' --out '%s' %s --cutoff 20 " FAST, cmd,
                 tu_table_fixture(), out, size);
        tu_run_out r = tu_run_cli("", args);
        expect_exit(r, 0, args);
        tu_run_free(&r);
        victim_intact(v);
        snprintf(out, sizeof out, "%s/final-%d", dir, i);
        ck_assert_int_eq(mkdir(out, 0777), 0);
        plant(v, out, names[i]);
        snprintf(args, sizeof args, "%s '%s' --out '%s' %s --cutoff 20 " FAST, cmd,
                 tu_table_fixture(), out, size);
        r = tu_run_cli("", args);
        expect_exit(r, 1, args);
        ck_assert_msg(strstr(r.err, names[i]) && strstr(r.err, "symbolic link (not followed)"),
                      "%s: %s", names[i], r.err);
        tu_run_free(&r);
        victim_intact(v);
    }
    tu_remove_tree(dir);
}
END_TEST

/* report: links in its --out (a page, a material's directory) are not followed. */
START_TEST(links_in_report_out)
{
    char dir[512], v[1024], shard[1024], out[1024], elsewhere[1024], args[4096];
    tmpdir(dir, sizeof dir);
    victim(dir, v, sizeof v);
    snprintf(shard, sizeof shard, "%s/shard", dir);
    tu_run_out r = demo_batch(shard);
    expect_exit(r, 0, "batch");
    tu_run_free(&r);
    snprintf(out, sizeof out, "%s/report", dir);
    ck_assert_int_eq(mkdir(out, 0777), 0);
    plant(v, out, "index.html.tmp");
    plant(v, out, "fits.tsv");
    snprintf(args, sizeof args, "report '%s' --out '%s'", shard, out);
    r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "fits.tsv: it is a symbolic link (not followed)"), "%s", r.err);
    tu_run_free(&r);
    victim_intact(v);
    snprintf(out, sizeof out, "%s/report2", dir);
    snprintf(elsewhere, sizeof elsewhere, "%s/elsewhere", dir);
    ck_assert_int_eq(mkdir(out, 0777), 0);
    ck_assert_int_eq(mkdir(elsewhere, 0777), 0);
    plant(elsewhere, out, DEMO);
    snprintf(args, sizeof args, "report '%s' --out '%s'", shard, out);
    r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "symbolic link (not followed)"), "%s", r.err);
    tu_run_free(&r);
    ck_assert_int_eq(rmdir(elsewhere), 0); /* empty */
    tu_remove_tree(dir);
}
END_TEST

/* ------------------------------------------------------------------ names from journals */

/* A journal record whose material is not one path component: the journal's
 * check ignores it naming the journal and line, and report writes nothing
 * outside --out (cmd_report.c checks the names it merges again). */
START_TEST(report_refuses_bad_journal_names)
{
    char dir[512], shard[1024], out[1024], jpath[1200], args[4096], esc[1024];
    tmpdir(dir, sizeof dir);
    snprintf(shard, sizeof shard, "%s/a/b/shard", dir);
    snprintf(args, sizeof args, "mkdir -p '%s/a/b' && true", dir);
    ck_assert_int_eq(system(args), 0);
    snprintf(args, sizeof args, "batch --demo --out '%s' " FAST " --no-render --no-plot", shard);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 0, args);
    tu_run_free(&r);
    snprintf(jpath, sizeof jpath, "%s/journal.jsonl", shard);
    char *j = tu_slurp(jpath);
    ck_assert_ptr_nonnull(j);
    int lines = tu_count_lines(j);
    static const char *const bad[] = { "../../escaped", "..", "", "x/y", NULL };
    for (int k = 0; bad[k]; k++) {
        /* the journal's first line again, its material renamed */
        char *line = strndup(j, (size_t)(strchr(j, '\n') - j));
        char *m = strstr(line, "\"material\":\"" DEMO "\"");
        ck_assert_ptr_nonnull(m);
        char rec[8192];
        snprintf(rec, sizeof rec, "%.*s\"material\":\"%s\"%s\n", (int)(m - line), line, bad[k],
                 m + strlen("\"material\":\"" DEMO "\""));
        free(line);
        FILE *f = fopen(jpath, "w");
        fputs(j, f);
        fputs(rec, f);
        fclose(f);
        snprintf(out, sizeof out, "%s/a/b/report-%d", dir, k);
        snprintf(args, sizeof args, "report '%s' --out '%s'", shard, out);
        r = tu_run_cli("", args);
        /* the journal's check refuses the record (its line said), the rest is merged */
        expect_exit(r, 0, args);
        char want[2048];
        snprintf(want, sizeof want, "%s: line %d: the material name is empty or not a file name: "
                 "ignored", jpath, lines + 1);
        ck_assert_msg(strstr(r.err, want), "expected '%s' in:\n%s", want, r.err);
        tu_run_free(&r);
        snprintf(esc, sizeof esc, "%s/escaped", dir);
        ck_assert_msg(access(esc, F_OK) != 0, "report wrote %s", esc);
        snprintf(esc, sizeof esc, "%s/a/escaped", dir);
        ck_assert_msg(access(esc, F_OK) != 0, "report wrote %s", esc);
    }
    free(j);
    tu_remove_tree(dir);
}
END_TEST

/* ------------------------------------------------------------------ the lock */

static int count_substr(const char *s, const char *what)
{
    int n = 0;
    for (const char *p = s; (p = strstr(p, what)) != NULL; p++)
        n++;
    return n;
}

/* Two batches into one directory at once: one says the other is writing it
 * and fails; the journal holds each fit once. */
START_TEST(two_batches_at_once)
{
    char dir[512], out[1024], args[4096], jpath[1200];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/out", dir);
    /* the second starts while the first runs (its fits take seconds) */
    snprintf(args, sizeof args,
             "batch --demo --out '%s' --model ward,cook-torrance --no-render --no-plot -q & "
             "sleep 0.2; '%s' batch --demo --out '%s' --model ward,cook-torrance --no-render "
             "--no-plot -q; echo second=$? >&2; wait $!; echo first=$? >&2; }",
             out, tu_cli(), out);
    tu_run_out r = tu_run_cli("{", args); /* { brdffit ARGS; } >out 2>err */
    ck_assert_msg(strstr(r.err, "second=1") && strstr(r.err, "first=0"), "%s", r.err);
    char want[1200];
    snprintf(want, sizeof want, "is writing %s", out);
    ck_assert_msg(strstr(r.err, "brdffit: another brdffit batch (pid ") && strstr(r.err, want),
                  "%s", r.err);
    tu_run_free(&r);
    snprintf(jpath, sizeof jpath, "%s/journal.jsonl", out);
    char *j = tu_slurp(jpath);
    ck_assert_ptr_nonnull(j);
    ck_assert_int_eq(count_substr(j, "\"kind\":\"fit\""), 2);
    ck_assert_int_eq(count_substr(j, "\"model\":\"ward\""), 1);
    free(j);
    tu_remove_tree(dir);
}
END_TEST

/* The lock held here: exclusive (a batch, pid named in the file) stops a
 * batch and a report of the directory; shared (a report) stops a batch. */
START_TEST(lock_held_refuses)
{
    char dir[512], out[1024], lpath[1200], args[4096], want[2048];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/out", dir);
    tu_run_out r = demo_batch(out);
    expect_exit(r, 0, "batch");
    tu_run_free(&r);
    snprintf(lpath, sizeof lpath, "%s/.brdffit-lock", out);
    int fd = open(lpath, O_RDWR);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(flock(fd, LOCK_EX), 0);
    ck_assert_int_eq(ftruncate(fd, 0), 0);
    ck_assert_int_eq(pwrite(fd, "batch 4242\n", 11, 0), 11);
    snprintf(want, sizeof want, "brdffit: another brdffit batch (pid 4242) is writing %s", out);
    r = demo_batch(out);
    expect_exit(r, 1, "batch, the lock held");
    ck_assert_msg(strstr(r.err, want), "%s", r.err);
    tu_run_free(&r);
    snprintf(args, sizeof args, "report '%s' --out '%s/merged'", out, dir);
    r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, want), "%s", r.err);
    tu_run_free(&r);
    ck_assert_int_eq(flock(fd, LOCK_SH), 0); /* a report reads it */
    r = demo_batch(out);
    expect_exit(r, 1, "batch, a report reading");
    snprintf(want, sizeof want, "a brdffit report is reading %s", out);
    ck_assert_msg(strstr(r.err, want), "%s", r.err);
    tu_run_free(&r);
    r = tu_run_cli("", args); /* reports share it */
    expect_exit(r, 0, args);
    tu_run_free(&r);
    close(fd);
    r = demo_batch(out);
    expect_exit(r, 0, "batch, the lock free");
    tu_run_free(&r);
    tu_remove_tree(dir);
}
END_TEST

/* ------------------------------------------------------------------ modes */

/* Every file 0666 and directory 0777 less the umask, under dir. */
static void check_modes(const char *path, mode_t mask)
{
    struct stat st;
    ck_assert_int_eq(lstat(path, &st), 0);
    mode_t want = (S_ISDIR(st.st_mode) ? 0777 : 0666) & ~mask;
    ck_assert_msg((st.st_mode & 07777) == want, "%s: mode %o, expected %o", path,
                  (unsigned)(st.st_mode & 07777), (unsigned)want);
    if (!S_ISDIR(st.st_mode))
        return;
    DIR *d = opendir(path);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char sub[2048];
        snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
        check_modes(sub, mask);
    }
    closedir(d);
}

START_TEST(modes_follow_the_umask)
{
    static const mode_t masks[] = { 022, 077 };
    char dir[512], out[1024], args[4096], um[32];
    tmpdir(dir, sizeof dir);
    for (int k = 0; k < 2; k++) {
        snprintf(um, sizeof um, "umask %03o;", (unsigned)masks[k]);
        snprintf(out, sizeof out, "%s/batch-%03o", dir, (unsigned)masks[k]);
        snprintf(args, sizeof args, "batch --demo --out '%s' " FAST, out);
        tu_run_out r = tu_run_cli(um, args);
        expect_exit(r, 0, args);
        tu_run_free(&r);
        char merged[1100];
        snprintf(merged, sizeof merged, "%s/report-%03o", dir, (unsigned)masks[k]);
        snprintf(args, sizeof args, "report '%s' --out '%s'", out, merged);
        r = tu_run_cli(um, args);
        expect_exit(r, 0, args);
        tu_run_free(&r);
        check_modes(out, masks[k]);
        check_modes(merged, masks[k]);
        snprintf(out, sizeof out, "%s/render-%03o", dir, (unsigned)masks[k]);
        snprintf(args, sizeof args, "render '%s' --out '%s' --size 16 --cutoff 20 " FAST,
                 tu_table_fixture(), out);
        r = tu_run_cli(um, args);
        expect_exit(r, 0, args);
        tu_run_free(&r);
        check_modes(out, masks[k]);
    }
    tu_remove_tree(dir);
}
END_TEST

/* ------------------------------------------------------------------ --out itself */

/* A dangling --out link is said to be one; a link to a directory is followed. */
START_TEST(out_links)
{
    char dir[512], out[1024], real[1024], args[4096], want[2048];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/dangling", dir);
    ck_assert_int_eq(symlink("missing-dir", out), 0);
    snprintf(want, sizeof want, "cannot create the directory %s: it is a symbolic link to "
             "missing-dir, which does not exist", out);
    tu_run_out r = demo_batch(out);
    expect_exit(r, 1, "batch --out dangling");
    ck_assert_msg(strstr(r.err, want), "%s", r.err);
    tu_run_free(&r);
    snprintf(args, sizeof args, "plot '%s' --out '%s' --cutoff 20 " FAST, tu_table_fixture(), out);
    r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, want), "%s", r.err);
    tu_run_free(&r);
    snprintf(real, sizeof real, "%s/missing-dir", dir); /* now there */
    ck_assert_int_eq(mkdir(real, 0777), 0);
    r = demo_batch(out);
    expect_exit(r, 0, "batch --out a link to a directory");
    tu_run_free(&r);
    snprintf(real, sizeof real, "%s/missing-dir/index.html", dir);
    ck_assert_int_eq(access(real, F_OK), 0);
    tu_remove_tree(dir);
}
END_TEST

/* ------------------------------------------------------------------ TSV */

/* Materials named with a tab and a line break: fits.tsv has a row each, as
 * many fields as the header, the names escaped; params.tsv's comment is one line. */
START_TEST(tsv_names_escaped)
{
    char dir[512], in[1024], out[1024], args[4096], path[2048];
    tmpdir(dir, sizeof dir);
    snprintf(in, sizeof in, "%s/in", dir);
    ck_assert_int_eq(mkdir(in, 0777), 0);
    plant(tu_table_fixture(), in, "a\tb.binary");
    plant(tu_table_fixture(), in, "a\nb.binary");
    plant(tu_table_fixture(), in, "a b.binary");
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(args, sizeof args, "batch '%s' --out '%s' --cutoff 20 --no-render --no-plot " FAST,
             in, out);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 0, args);
    tu_run_free(&r);
    snprintf(path, sizeof path, "%s/fits.tsv", out);
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    char line[16384], *fld[64];
    int n, header = 0, rows = 0, seen = 0;
    while ((n = tu_tsv_next(f, line, sizeof line, fld, 64)) > 0) {
        if (!header) {
            header = n;
            continue;
        }
        ck_assert_int_eq(n, header);
        rows++;
        seen |= (strcmp(fld[0], "a\\tb") == 0) | (strcmp(fld[0], "a\\nb") == 0) << 1 |
                (strcmp(fld[0], "a b") == 0) << 2;
    }
    fclose(f);
    ck_assert_int_eq(rows, 3);
    ck_assert_int_eq(seen, 7);
    snprintf(path, sizeof path, "%s/a\nb/params.tsv", out);
    char *p = tu_slurp(path);
    ck_assert_ptr_nonnull(p);
    ck_assert_msg(strncmp(p, "# a\\nb: metric", 14) == 0, "%.80s", p);
    ck_assert_int_eq(tu_count_lines(p), 3); /* comment, header, row */
    free(p);
    tu_remove_tree(dir);
}
END_TEST

Suite *outdir_suite(void)
{
    Suite *s = suite_create("outdir");
    TCase *tc = tcase_create("outdir");
    tcase_set_timeout(tc, 600);
    tcase_add_unchecked_fixture(tc, tu_table_fixture_make, tu_table_fixture_remove);
    tcase_add_test(tc, names_and_tsv_text);
    tcase_add_test(tc, old_temporary_names_linked);
    tcase_add_test(tc, links_at_every_batch_name);
    tcase_add_test(tc, linked_journal_and_material_directory);
    tcase_add_test(tc, links_in_render_and_plot);
    tcase_add_test(tc, links_in_report_out);
    tcase_add_test(tc, report_refuses_bad_journal_names);
    tcase_add_test(tc, two_batches_at_once);
    tcase_add_test(tc, lock_held_refuses);
    tcase_add_test(tc, modes_follow_the_umask);
    tcase_add_test(tc, out_links);
    tcase_add_test(tc, tsv_names_escaped);
    suite_add_tcase(s, tc);
    return s;
}
