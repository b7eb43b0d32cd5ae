/* SPDX-License-Identifier: MIT */
/* cmd_report.c -- `brdffit report DIR... --out OUT`: the journals of several
 * batch directories (the shards of one job) merged into one report: the same
 * pages, index, fits.tsv and headline figure as `batch` writes, with the
 * renders and plots copied from the shard that made them. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

const cli_help_block *cli_report_help(void)
{
    static const cli_help_item items[] = {
        { "DIR...", "the --out directories of `brdffit batch` runs (shards)" },
        { "--out DIR", "where the merged report goes" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK("Arguments of report", NULL, items);
    return &block;
}

static int by_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* The settings of the report: those of each journal's last record, which must agree. */
static int pick_settings(const bj_records *rs, char **dirs, int ndirs, bj_settings *out)
{
    int have = 0, from = -1;
    for (int d = 0; d < ndirs; d++) {
        const fit_record *last = NULL;
        for (int i = 0; i < rs->n; i++)
            if (rs->r[i].origin == d)
                last = &rs->r[i];
        if (!last) {
            cli_error("%s: no journal records (not a batch directory?)", dirs[d]);
            return -1;
        }
        if (!have) {
            *out = last->settings;
            have = 1;
            from = d;
        } else if (!bj_settings_equal(out, &last->settings)) {
            char diff[512];
            bj_settings_diff(&last->settings, out, diff, sizeof diff);
            cli_error("%s was made with other settings than %s: %s "
                      "(\"this run\" = %s); not merged",
                      dirs[d], dirs[from], diff, dirs[from]);
            return -1;
        }
    }
    return 0;
}

static int build(rp_report *rep, const bj_records *rs, char **dirs, int ndirs)
{
    /* the models: every model fitted with these settings, in registry order */
    brdffit_model models[BJ_MAX_MODELS];
    int nm = 0, other = 0;
    for (int id = 0; id < BJ_MAX_MODELS; id++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)id);
        if (!mi)
            break;
        for (int i = 0; i < rs->n; i++)
            if (rs->r[i].kind == FR_FIT && strcmp(rs->r[i].model, mi->name) == 0 &&
                bj_settings_equal(&rs->r[i].settings, &rep->settings)) {
                models[nm++] = (brdffit_model)id;
                break;
            }
    }
    bj_settings s = rep->settings;
    if (rp_init(rep, models, nm, &s) != 0)
        return -1;
    /* the materials, by name */
    const char **names = malloc((size_t)(rs->n > 0 ? rs->n : 1) * sizeof *names);
    if (!names)
        return -1;
    int nn = 0;
    for (int i = 0; i < rs->n; i++) {
        const fit_record *r = &rs->r[i];
        if (!bj_settings_equal(&r->settings, &rep->settings)) {
            other++;
            continue;
        }
        if (r->kind == FR_PUBLISHED)
            rep->have_published = 1;
        if (!rep->backend[0] && r->backend[0])
            snprintf(rep->backend, sizeof rep->backend, "%s (from the journals)", r->backend);
        names[nn++] = r->material;
    }
    qsort(names, (size_t)nn, sizeof *names, by_str);
    int rc = 0;
    for (int i = 0; i < nn && rc == 0; i++)
        if (i == 0 || strcmp(names[i], names[i - 1]) != 0)
            rc = rp_add(rep, names[i], NULL, rs, (const char *const *)dirs, ndirs);
    free(names);
    if (other)
        fprintf(stderr, "brdffit: %d journal record%s made with other settings left out\n", other,
                other == 1 ? "" : "s");
    return rc;
}

/* Every record's material must name a directory of the report: one path
 * component.  0, or -1 with the journal and line of the first that cannot. */
static int check_names(const bj_records *rs, char **dirs)
{
    for (int i = 0; i < rs->n; i++) {
        const char *bad = od_name_problem(rs->r[i].material);
        if (bad) {
            cli_error("%s/journal.jsonl line %d: the material name '%s' cannot name a directory "
                      "of the report (%s); not merged",
                      dirs[rs->r[i].origin], rs->r[i].line, rs->r[i].material, bad);
            return -1;
        }
    }
    return 0;
}

/* Read the journal of shard d (its lock shared while it is read) into rs. */
static int load_shard(char **dirs, int d, bj_records *rs)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    out_dir sd;
    od_lock lock = { -1 };
    char path[BJ_PATH_MAX];
    int bad = 0, torn = 0, before = rs->n, rc = 0;
    if (od_open(&sd, dirs[d], 0, &err) != 0 || od_lock_take(&lock, &sd, 1, "report", &err) != 0 ||
        out_join(path, sizeof path, dirs[d], "journal.jsonl") != 0 ||
        bj_journal_load(path, rs, &bad, &torn, &err) != 0) {
        cli_error("%s", err.message[0] ? err.message : dirs[d]);
        rc = -1;
    }
    od_lock_release(&lock);
    od_close(&sd);
    for (int i = before; i < rs->n; i++)
        rs->r[i].origin = d;
    if (rc == 0 && torn) /* the damaged lines were said one by one */
        cli_error("%s: a torn last line ignored", path);
    return rc;
}

/* The report's pages into out (made, locked while they are written). */
static int write_out(const rp_report *rep, const char *out)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    out_dir d;
    od_lock lock = { -1 };
    int rc = od_open(&d, out, 1, &err) != 0 || od_lock_take(&lock, &d, 0, "report", &err) != 0
                 ? CLI_FAILED : CLI_OK;
    if (rc == CLI_OK) {
        od_sweep(&d);
        rc = rp_write(rep, &d, &err) != 0 ? CLI_FAILED : CLI_OK;
    }
    if (rc != CLI_OK)
        cli_error("%s", err.message);
    else
        printf("%s/index.html\n", out);
    od_lock_release(&lock);
    od_close(&d);
    return rc;
}

int cmd_report(int argc, char **argv)
{
    const char *out = NULL;
    char **dirs = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *dirs);
    int ndirs = 0, rc = CLI_OK;
    if (!dirs)
        return CLI_FAILED;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        if (cli_is_help(argv[i]))
            rc = CLI_HELP;
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strncmp(argv[i], "--out=", 6) == 0)
            out = argv[i] + 6;
        else if (argv[i][0] == '-' && argv[i][1])
            rc = cli_usage_error("report: unknown option '%s'", argv[i]);
        else
            dirs[ndirs++] = argv[i];
    }
    if (rc == CLI_OK && (!out || !*out || ndirs == 0))
        rc = cli_usage_error("report needs batch directories and --out DIR");
    bj_records rs = { NULL, 0, 0 };
    for (int d = 0; d < ndirs && rc == CLI_OK; d++)
        if (load_shard(dirs, d, &rs) != 0)
            rc = CLI_FAILED;
    if (rc == CLI_OK && check_names(&rs, dirs) != 0)
        rc = CLI_FAILED;
    rp_report rep;
    memset(&rep, 0, sizeof rep);
    if (rc == CLI_OK && pick_settings(&rs, dirs, ndirs, &rep.settings) != 0)
        rc = CLI_FAILED;
    if (rc == CLI_OK && build(&rep, &rs, dirs, ndirs) != 0) {
        fputs("brdffit: out of memory\n", stderr);
        rc = CLI_FAILED;
    }
    if (rc == CLI_OK) {
        time_t t = time(NULL);
        struct tm tm;
        gmtime_r(&t, &tm);
        strftime(rep.started, sizeof rep.started, "%Y-%m-%dT%H:%M:%SZ", &tm);
        if (!rep.backend[0])
            snprintf(rep.backend, sizeof rep.backend, "(not recorded)");
        if (rep.have_published)
            snprintf(rep.published_path, sizeof rep.published_path, "(from the journals)");
        rc = write_out(&rep, out);
    }
    rp_free(&rep);
    bj_records_free(&rs);
    free(dirs);
    return rc;
}
