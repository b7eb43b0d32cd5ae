/* SPDX-License-Identifier: MIT */
/* make_seeds.c -- the seed corpora of the fuzz targets, written by `make fuzz`:
 *   make_seeds DIR   writes the files of DIR/table (fuzz_table.c), DIR/options
 *                    (fuzz_options.c) and DIR/journal (fuzz_journal.c); existing
 *                    files are overwritten.
 * Table seeds in the patch mode (first byte odd) start from a valid table;
 * the others are whole (short) files. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *dir;

static void put(const char *sub, const char *name, const void *data, size_t len)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s/%s", dir, sub, name);
    FILE *f = fopen(path, "wb");
    if (!f || (len && fwrite(data, 1, len, f) != len) || fclose(f) != 0) {
        fprintf(stderr, "make_seeds: cannot write %s\n", path);
        exit(1);
    }
}

static size_t le32(unsigned char *b, int32_t v)
{
    uint32_t u = (uint32_t)v;
    for (int i = 0; i < 4; i++)
        b[i] = (unsigned char)(u >> (8 * i));
    return 4;
}

static size_t le64(unsigned char *b, double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    for (int i = 0; i < 8; i++)
        b[i] = (unsigned char)(u >> (8 * i));
    return 8;
}

/* mode byte, length change, header dims, then the first samples */
static size_t table_seed(unsigned char *b, int patch, int delta, int32_t d0, int32_t d1, int32_t d2,
                         const double *first, int nfirst)
{
    size_t n = 0;
    b[n++] = patch ? 1 : 0; /* bit 1 (make a sample set) left to the fuzzer */
    if (patch)
        b[n++] = (unsigned char)(int8_t)delta;
    n += le32(b + n, d0);
    n += le32(b + n, d1);
    n += le32(b + n, d2);
    for (int i = 0; i < nfirst; i++)
        n += le64(b + n, first[i]);
    return n;
}

static void table_seeds(void)
{
    unsigned char b[256];
    const double plain[4] = { 0.01, 0.02, -1.0, 0.5 };
    const double nan_first[2] = { 0.01, NAN };
    const double inf_first[2] = { INFINITY, 0.0 };
    const double huge_first[2] = { 0.01, 1e300 };
    const double big_first[2] = { 1e100, 0.01 };
    put("table", "whole-empty", b, table_seed(b, 0, 0, 0, 0, 0, NULL, 0) - 12);
    put("table", "whole-header-only", b, table_seed(b, 0, 0, 90, 90, 180, NULL, 0));
    put("table", "whole-short-header", b, 7);
    put("table", "whole-bad-dims", b, table_seed(b, 0, 0, 90, 90, 90, plain, 4));
    put("table", "whole-negative-dims", b, table_seed(b, 0, 0, -90, 90, 180, plain, 2));
    put("table", "patch-valid", b, table_seed(b, 1, 0, 90, 90, 180, plain, 0));
    put("table", "patch-first-samples", b, table_seed(b, 1, 0, 90, 90, 180, plain, 4));
    put("table", "patch-nan", b, table_seed(b, 1, 0, 90, 90, 180, nan_first, 2));
    put("table", "patch-inf", b, table_seed(b, 1, 0, 90, 90, 180, inf_first, 2));
    put("table", "patch-huge", b, table_seed(b, 1, 0, 90, 90, 180, huge_first, 2));
    put("table", "patch-big", b, table_seed(b, 1, 0, 90, 90, 180, big_first, 2));
    put("table", "patch-truncated", b, table_seed(b, 1, -1, 90, 90, 180, plain, 1));
    put("table", "patch-trailing", b, table_seed(b, 1, 8, 90, 90, 180, plain, 1));
    put("table", "patch-dims", b, table_seed(b, 1, 0, 180, 90, 90, NULL, 0));
    size_t n = table_seed(b, 1, 0, 90, 90, 180, plain, 4);
    b[0] = 3; /* and its sample set */
    put("table", "patch-sampled", b, n);
}

/* first byte: 0 fit/demo options, 1 eval; then NUL-separated arguments */
static void option_seed(const char *name, int eval, const char *const *args)
{
    char b[1024];
    size_t n = 0;
    b[n++] = (char)eval;
    for (int i = 0; args[i]; i++) {
        size_t l = strlen(args[i]) + 1;
        memcpy(b + n, args[i], l);
        n += l;
    }
    put("options", name, b, n);
}

static void option_seeds(void)
{
    option_seed("fit-files", 0, (const char *const[]){ "a.binary", "b.binary", NULL });
    option_seed("fit-all-options", 0,
                (const char *const[]){ "--model", "ward,cook-torrance", "--scale=flat", "--cutoff",
                                       "60", "--starts", "4", "--backend", "opencl", "--device",
                                       "0:0", "--json", "--", "-file", NULL });
    option_seed("fit-model-all", 0, (const char *const[]){ "--model=all", "--model", "he", "x", NULL });
    option_seed("fit-bad-number", 0, (const char *const[]){ "--cutoff", "1e-300", "--starts", "0x10", NULL });
    option_seed("fit-help", 0, (const char *const[]){ "--help", NULL });
    option_seed("fit-missing-value", 0, (const char *const[]){ "--device", NULL });
    option_seed("eval-ward", 1,
                (const char *const[]){ "ward", "0.1", "0.1", "0.1", "0.2", "0.2", "0.2", "0.3", "--wi",
                                       "0", "0", "1", "--wo", "0.5", "0", "0.8", NULL });
    option_seed("eval-he", 1,
                (const char *const[]){ "he", "0", "0", "0", "1", "1", "1", "8", "0.3", "1.5", "--wi",
                                       "0", "0.1", "1", "--wo", "0", "0", "1", NULL });
    option_seed("eval-bad", 1, (const char *const[]){ "lafortune", "nan", "--wi", "0", NULL });
}

/* Journal lines: a fit record as brdffit batch writes it (fit_record.h), and
 * the earlier form's fit, failure and assets, which the reader still takes. */
static void journal_seeds(void)
{
    static const char *const lines[][2] = {
        { "record", "{\"kind\":\"fit\",\"material\":\"alum-bronze\",\"file\":\"/d/alum-bronze.binary\","
                    "\"size\":34992012,\"hash\":\"8143736677fba4d1\",\"settings\":{\"version\":\"0.1.0\","
                    "\"metric\":\"ngan-l2\",\"scale\":\"standard\",\"cutoff_deg\":80,\"starts\":0},"
                    "\"model\":\"he\",\"param_names\":[\"tau\",\"sigma0\",\"n\"],\"status\":\"ok\","
                    "\"status_code\":0,\"message\":\"\",\"d\":[0.08,0.05,0.02],\"s\":[0.04,0.02,0.01],"
                    "\"p\":[12.5,0.3,1.6],\"lambda_um\":[0.645,0.526,0.444],\"error\":0.0568,"
                    "\"iterations\":3,\"passes\":13,\"cminpack_info\":1,\"flags\":[],"
                    "\"at_bound\":[\"n\",\"d_b\"],\"seconds\":0.204,\"seconds_solver\":0.01,"
                    "\"seconds_passes\":0.15,\"seconds_build\":0,\"samples\":923870,"
                    "\"backend\":\"opencl\",\"backend_description\":\"OpenCL\",\"assets_key\":null,"
                    "\"assets\":null}" },
        { "fit", "{\"kind\":\"fit\",\"material\":\"alum-bronze\",\"file\":{\"path\":\"/d/alum-bronze.binary\","
                 "\"size\":34992012,\"hash\":\"8143736677fba4d1\"},\"settings\":{\"version\":\"0.1.0\","
                 "\"scale\":\"standard\",\"cutoff_deg\":80,\"starts\":0},\"model\":\"he\",\"ok\":true,"
                 "\"status\":\"ok\",\"message\":\"\",\"d\":[0.08,0.05,0.02],\"s\":[0.04,0.02,0.01],"
                 "\"p\":[12.5,0.3,1.6],\"lambda_um\":[0.645,0.526,0.444],\"error\":0.0568,"
                 "\"iterations\":3,\"passes\":13,\"cminpack_info\":1,\"seconds\":0.204,"
                 "\"samples\":923870,\"on_bound\":\"n=upper\",\"backend\":\"opencl\"}" },
        { "failure", "{\"kind\":\"failure\",\"material\":\"x\\u001b\",\"file\":{\"path\":\"x.binary\","
                     "\"size\":0,\"hash\":\"\"},\"settings\":{\"version\":\"0.1.0\",\"scale\":\"flat\","
                     "\"cutoff_deg\":80,\"starts\":0},\"model\":\"\",\"ok\":false,"
                     "\"status\":\"file is empty\",\"message\":\"x.binary: empty file\"}" },
        { "assets", "{\"kind\":\"assets\",\"material\":\"m\",\"file\":{\"path\":\"(embedded)\","
                    "\"size\":34992000,\"hash\":\"8143736677fba4d1\"},\"settings\":{\"version\":\"0.1.0\","
                    "\"scale\":\"standard\",\"cutoff_deg\":80,\"starts\":0},\"model\":\"\",\"ok\":true,"
                    "\"status\":\"ok\",\"message\":\"\",\"assets_key\":\"rf1:render=1,plot=1:ward\","
                    "\"assets\":\"image\\tward.png\\tWard: 0.0569\\n\"}" },
    };
    for (size_t i = 0; i < sizeof lines / sizeof lines[0]; i++)
        put("journal", lines[i][0], lines[i][1], strlen(lines[i][1]));
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_seeds DIR\n");
        return 2;
    }
    dir = argv[1];
    table_seeds();
    option_seeds();
    journal_seeds();
    return 0;
}
