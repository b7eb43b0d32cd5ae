/* SPDX-License-Identifier: MIT */
/* eval_c.c -- the C side of the Python eval benchmark (eval_numpy.py): time
 * brdffit_eval_batch over the direction pairs in a file, through the same
 * shared library the Python package loads.
 *
 * Usage: bench_eval_c FILE REPS MODEL d_r d_g d_b s_r s_g s_b p0 [p1 [p2]]
 * FILE: uint64 n, then wi (3n doubles), then wo (3n doubles), native order.
 * Prints the fastest of REPS calls in milliseconds; the output buffer is
 * allocated and touched once, before the timed calls. */
#define _POSIX_C_SOURCE 200809L
#include "brdffit.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    if (argc < 11) {
        fprintf(stderr, "usage: %s FILE REPS MODEL d_r d_g d_b s_r s_g s_b p0 [p1 [p2]]\n", argv[0]);
        return 2;
    }
    int reps = atoi(argv[2]);
    brdffit_model model;
    if (reps < 1 || brdffit_model_from_name(argv[3], &model, NULL) != BRDFFIT_OK) {
        fprintf(stderr, "bench_eval_c: bad REPS or MODEL\n");
        return 2;
    }
    brdffit_params p;
    memset(&p, 0, sizeof p);
    for (int c = 0; c < 3; c++) {
        p.d[c] = atof(argv[4 + c]);
        p.s[c] = atof(argv[7 + c]);
    }
    for (int k = 10; k < argc && k - 10 < BRDFFIT_MAX_LOBE_PARAMS; k++)
        p.p[k - 10] = atof(argv[k]);

    FILE *f = fopen(argv[1], "rb");
    uint64_t n = 0;
    if (!f || fread(&n, sizeof n, 1, f) != 1 || n == 0 || n > (1u << 28)) {
        fprintf(stderr, "bench_eval_c: cannot read %s\n", argv[1]);
        return 1;
    }
    double *wi = malloc(3 * n * sizeof *wi), *wo = malloc(3 * n * sizeof *wo);
    double *rgb = calloc(3 * n, sizeof *rgb);
    if (!wi || !wo || !rgb || fread(wi, sizeof *wi, 3 * n, f) != 3 * n ||
        fread(wo, sizeof *wo, 3 * n, f) != 3 * n) {
        fprintf(stderr, "bench_eval_c: cannot read %s\n", argv[1]);
        return 1;
    }
    fclose(f);
    double best = 1e300;
    for (int r = 0; r < reps; r++) {
        double t0 = now();
        brdffit_status st = brdffit_eval_batch(model, &p, (size_t)n, wi, wo, rgb, NULL);
        double t = now() - t0;
        if (st != BRDFFIT_OK) {
            fprintf(stderr, "bench_eval_c: %s\n", brdffit_strerror(st));
            return 1;
        }
        if (t < best)
            best = t;
    }
    printf("%.3f\n", best * 1e3);
    free(wi);
    free(wo);
    free(rgb);
    return 0;
}
