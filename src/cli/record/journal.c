/* SPDX-License-Identifier: MIT */
/* journal.c -- the batch journal DIR/journal.jsonl: one JSON object per line
 * (a record of fit_record.h), one line per finished fit (and per failed material, published Error and
 * written renders), appended with one write() and fsync'd before the batch
 * goes on.  Records are keyed by the material's identity (absolute path, size,
 * a 64-bit FNV-1a hash of its bytes taken over 8-byte words) and the settings (version, scale, cutoff,
 * starts) with the model; the batch reuses a record only when all of it
 * matches.  A kill in the middle of a write leaves a last line without its
 * newline: loading ignores it and opening cuts it off. */
#define _XOPEN_SOURCE 700
#include "batch.h"
#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ------------------------------------------------------------------ settings */

void bj_settings_make(bj_settings *s, const brdffit_sample_options *so, const brdffit_fit_options *fo)
{
    memset(s, 0, sizeof *s);
    snprintf(s->version, sizeof s->version, "%s", brdffit_version());
    snprintf(s->scale, sizeof s->scale, "%s", brdffit_scale_name(so->scale));
    s->cutoff_deg = so->cutoff_deg;
    s->starts = fo->starts;
    snprintf(s->metric, sizeof s->metric, "%s", brdffit_metric_get_name((brdffit_metric)fo->metric));
}

int bj_settings_equal(const bj_settings *a, const bj_settings *b)
{
    return strcmp(a->version, b->version) == 0 && strcmp(a->scale, b->scale) == 0 &&
           a->cutoff_deg == b->cutoff_deg && a->starts == b->starts &&
           strcmp(a->metric, b->metric) == 0;
}

const char *bj_settings_diff(const bj_settings *journal, const bj_settings *run, char *buf,
                             size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
#define ADD(...)                                                                      \
    do {                                                                              \
        int w_ = snprintf(buf + used, len - used, "%s", used ? ", " : "");            \
        if (w_ > 0 && (size_t)w_ < len - used)                                        \
            used += (size_t)w_;                                                       \
        w_ = snprintf(buf + used, len - used, __VA_ARGS__);                           \
        if (w_ > 0 && (size_t)w_ < len - used)                                        \
            used += (size_t)w_;                                                       \
    } while (0)
    if (strcmp(journal->version, run->version) != 0)
        ADD("program version %s (this run: %s)", journal->version, run->version);
    if (strcmp(journal->scale, run->scale) != 0)
        ADD("scale %s (this run: %s)", journal->scale, run->scale);
    if (journal->cutoff_deg != run->cutoff_deg)
        ADD("cutoff %g deg (this run: %g)", journal->cutoff_deg, run->cutoff_deg);
    if (journal->starts != run->starts)
        ADD("starts %d (this run: %d; 0 = each model's default)", journal->starts, run->starts);
    if (strcmp(journal->metric, run->metric) != 0)
        ADD("metric %s (this run: %s)", journal->metric, run->metric);
#undef ADD
    return buf;
}

/* ------------------------------------------------------------------ identity */

#define FNV_OFFSET 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

/* FNV-1a 64 taken over 8-byte little-endian words (the tail bytes one by one):
 * eight times fewer multiplications than byte-wise FNV-1a; a change detector,
 * not a cryptographic hash.  n is a multiple of 8 except for the last call. */
static uint64_t hash_words(uint64_t h, const unsigned char *p, size_t n)
{
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t w = 0;
        for (int b = 7; b >= 0; b--)
            w = (w << 8) | p[i + (size_t)b];
        h ^= w;
        h *= FNV_PRIME;
    }
    for (; i < n; i++) {
        h ^= p[i];
        h *= FNV_PRIME;
    }
    return h;
}

int bj_identify(const char *path, bj_identity *id, brdffit_error *err)
{
    memset(id, 0, sizeof *id);
    char abs[PATH_MAX];
    if (!realpath(path, abs)) {
        err->status = BRDFFIT_E_FILE_OPEN;
        snprintf(err->message, sizeof err->message, "%.1000s: cannot open: %s", path,
                 strerror(errno));
        return -1;
    }
    snprintf(id->path, sizeof id->path, "%s", abs);
    FILE *f = cli_fopen_regular(path, err); /* a FIFO is refused, never waited on */
    if (!f)
        return -1;
    /* this call's own buffer: the prefetch thread and the main thread identify
     * files at the same time; a multiple of 8 bytes, as hash_words reads */
    enum { CHUNK = 1 << 16 };
    unsigned char *buf = malloc(CHUNK);
    if (!buf) {
        fclose(f);
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "%.1000s: out of memory to read it", path);
        return -1;
    }
    uint64_t h = FNV_OFFSET;
    long long size = 0;
    size_t got;
    while ((got = fread(buf, 1, CHUNK, f)) > 0) {
        h = hash_words(h, buf, got);
        size += (long long)got;
    }
    free(buf);
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        err->status = BRDFFIT_E_FILE_READ;
        snprintf(err->message, sizeof err->message, "%.1000s: read error after %lld bytes",
                 path, size);
        return -1;
    }
    id->size = size;
    snprintf(id->hash, sizeof id->hash, "%016llx", (unsigned long long)h);
    return 0;
}

void bj_identify_bytes(const char *label, const void *data, size_t len, bj_identity *id)
{
    memset(id, 0, sizeof *id);
    snprintf(id->path, sizeof id->path, "%s", label);
    id->size = (long long)len;
    snprintf(id->hash, sizeof id->hash, "%016llx",
             (unsigned long long)hash_words(FNV_OFFSET, data, len));
}

int bj_identity_equal(const bj_identity *a, const bj_identity *b)
{
    return strcmp(a->path, b->path) == 0 && a->size == b->size && strcmp(a->hash, b->hash) == 0;
}

/* ------------------------------------------------------------------ records */

int bj_records_push(bj_records *rs, const fit_record *r)
{
    if (rs->n == rs->cap) {
        int cap = rs->cap ? rs->cap * 2 : 64;
        fit_record *g = realloc(rs->r, (size_t)cap * sizeof *g);
        if (!g)
            return -1;
        rs->r = g;
        rs->cap = cap;
    }
    rs->r[rs->n++] = *r;
    return 0;
}

void bj_records_free(bj_records *rs)
{
    free(rs->r);
    rs->r = NULL;
    rs->n = rs->cap = 0;
}

/* ------------------------------------------------------------------ the file */

static int io_fail(brdffit_error *err, const char *what, const char *path, int e)
{
    err->status = BRDFFIT_E_FILE_WRITE;
    snprintf(err->message, sizeof err->message, "cannot %s %.1800s: %s", what, path, strerror(e));
    return -1;
}

int bj_journal_open(bj_journal *j, const out_dir *dir, int *torn, brdffit_error *err)
{
    *torn = 0;
    j->fd = -1;
    if (out_join(j->path, sizeof j->path, dir->path, "journal.jsonl") != 0)
        return io_fail(err, "open", dir->path, ENAMETOOLONG);
    int fd = od_open_append(dir, "journal.jsonl", err);
    if (fd < 0)
        return -1;
    /* cut a torn last line off: find the last newline */
    off_t size = lseek(fd, 0, SEEK_END);
    if (size > 0) {
        char buf[4096];
        off_t keep = 0, pos = size;
        while (pos > 0) {
            off_t from = pos > (off_t)sizeof buf ? pos - (off_t)sizeof buf : 0;
            ssize_t got = pread(fd, buf, (size_t)(pos - from), from);
            if (got != pos - from) {
                int e = got < 0 ? errno : EIO;
                close(fd);
                return io_fail(err, "read", j->path, e);
            }
            off_t k = got;
            while (k > 0 && buf[k - 1] != '\n')
                k--;
            if (k > 0) {
                keep = from + k;
                break;
            }
            pos = from;
        }
        if (keep < size) {
            *torn = 1;
            if (ftruncate(fd, keep) != 0 || fsync(fd) != 0) {
                int e = errno;
                close(fd);
                return io_fail(err, "repair", j->path, e);
            }
        }
    }
    j->fd = fd;
    return od_sync(dir, err);
}

int bj_journal_append(bj_journal *j, const fit_record *r, brdffit_error *err)
{
    char *line = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&line, &len);
    if (!m) {
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "out of memory writing %.1800s", j->path);
        return -1;
    }
    fr_write_json(m, r);
    putc('\n', m);
    if (fclose(m) != 0 || !line) {
        free(line);
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "out of memory writing %.1800s", j->path);
        return -1;
    }
    /* one write for the whole line; a short write is completed (or fails) */
    size_t done = 0;
    if (cli_fault_hit("torn")) { /* the test of a kill in the middle of this write */
        done = len / 2;
        if (write(j->fd, line, done) == (ssize_t)done)
            (void)fsync(j->fd);
        raise(SIGKILL);
    }
    while (done < len) {
        ssize_t w = write(j->fd, line + done, len - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            int e = w < 0 ? errno : ENOSPC;
            free(line);
            /* the partial line is a torn line: cut it so the journal stays whole */
            off_t end = lseek(j->fd, 0, SEEK_END);
            if (end >= (off_t)done && ftruncate(j->fd, end - (off_t)done) == 0)
                (void)fsync(j->fd);
            return io_fail(err, "write", j->path, e);
        }
        done += (size_t)w;
    }
    free(line);
    if (fsync(j->fd) != 0)
        return io_fail(err, "write (fsync)", j->path, errno);
    return 0;
}

void bj_journal_close(bj_journal *j)
{
    if (j->fd >= 0)
        close(j->fd);
    j->fd = -1;
}

int bj_journal_load(const char *path, bj_records *rs, int *bad, int *torn, brdffit_error *err)
{
    *bad = 0;
    *torn = 0;
    FILE *f = cli_fopen_regular(path, err);
    if (!f)
        return err->status == BRDFFIT_E_FILE_OPEN && errno == ENOENT ? 0 : -1;
    char *line = NULL;
    size_t cap = 0;
    ssize_t n;
    fit_record *r = malloc(sizeof *r);
    int rc = 0;
    if (!r) {
        fclose(f);
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "out of memory reading %.1800s", path);
        return -1;
    }
    long lineno = 0;
    while ((n = getline(&line, &cap, f)) > 0) {
        lineno++;
        if (line[n - 1] != '\n') { /* the last line, without its newline: torn */
            *torn = 1;
            break;
        }
        line[n - 1] = '\0';
        char why[320];
        const char *bad_why = fr_read_json(line, r, FR_NEED_KEY) != 0
                                  ? "not a journal record"
                                  : fr_check(r, why, sizeof why);
        if (bad_why) {
            if ((*bad)++ < BJ_BAD_SHOWN)
                cli_error("%s: line %ld: %s: ignored (what it records is done again)", path,
                          lineno, bad_why);
            continue;
        }
        r->line = lineno;
        if (bj_records_push(rs, r) != 0) {
            err->status = BRDFFIT_E_NO_MEMORY;
            snprintf(err->message, sizeof err->message, "out of memory reading %.1800s", path);
            rc = -1;
            break;
        }
    }
    if (rc == 0 && ferror(f)) {
        err->status = BRDFFIT_E_FILE_READ;
        snprintf(err->message, sizeof err->message, "cannot read %.1800s: %s", path,
                 strerror(errno));
        rc = -1;
    }
    if (*bad > BJ_BAD_SHOWN)
        cli_error("%s: %d more lines that are not journal records ignored", path,
                  *bad - BJ_BAD_SHOWN);
    free(r);
    free(line);
    fclose(f);
    return rc;
}
