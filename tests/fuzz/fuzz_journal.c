/* SPDX-License-Identifier: MIT */
/* fuzz_journal.c -- libFuzzer target: the batch journal's line reader
 * (fr_read_json of src/cli/record/fit_record_json.c, over the program's JSON reader jr_parse), the input
 * being one journal line as a damaged or hostile journal.jsonl may hold.
 *
 * A line that parses must write back (fr_write_json) as a line that parses
 * to the same record: the journal's writer and reader agree on every record
 * the reader accepts, so resuming from a journal never changes what it says;
 * and the check of its values (fr_check) judges both the same.
 * `make fuzz` builds this with clang and runs it; tests/fuzz/make_seeds.c
 * writes its seed corpus (real journal lines). */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The fields a resume and the report use (fit_record minus what is not journaled). */
static int same_record(const fit_record *a, const fit_record *b)
{
    return a->kind == b->kind && strcmp(a->material, b->material) == 0 &&
           strcmp(a->id.path, b->id.path) == 0 && a->id.size == b->id.size &&
           strcmp(a->id.hash, b->id.hash) == 0 && strcmp(a->model, b->model) == 0 &&
           a->status == b->status && a->has_params == b->has_params &&
           a->has_counts == b->has_counts && a->flags == b->flags && a->at_bound == b->at_bound &&
           strcmp(a->message, b->message) == 0 && a->nparams == b->nparams &&
           memcmp(&a->params, &b->params, sizeof a->params) == 0 &&
           (a->error == b->error || (a->error != a->error && b->error != b->error)) &&
           a->iterations == b->iterations && a->passes == b->passes &&
           a->samples == b->samples && strcmp(a->assets_key, b->assets_key) == 0 &&
           strcmp(a->assets, b->assets) == 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *line = malloc(size + 1);
    fit_record *r = malloc(sizeof *r), *back = malloc(sizeof *back);
    if (!line || !r || !back)
        goto done;
    memcpy(line, data, size);
    line[size] = '\0';
    if (fr_read_json(line, r, FR_NEED_KEY) != 0)
        goto done;
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        goto done;
    fr_write_json(f, r);
    if (fclose(f) != 0)
        abort();
    if (fr_read_json(text, back, FR_NEED_KEY) != 0 || !same_record(r, back))
        abort(); /* the writer wrote what the reader does not read back */
    char why[320], why_back[320];
    if (!fr_check(r, why, sizeof why) != !fr_check(back, why_back, sizeof why_back))
        abort(); /* the check judged a record and its rewriting differently */
    free(text);
done:
    free(line);
    free(r);
    free(back);
    return 0;
}
