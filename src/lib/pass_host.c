/* SPDX-License-Identifier: MIT */
/* pass_host.c -- bf_host_loop: a data pass as a plain C loop, the same maths
 * as the kernel (kernels/bf_pass.h) one sample at a time. */
#include "pass.h"
#include "samples.h"

#include "bf_pass.h"

static int has_rows(const brdffit_samples *samples, const bf_pass_bins *bins)
{
    return bins && bins->table && samples->n > 0;
}

void bf_host_begin(const brdffit_samples *samples, const bf_pass_bins *bins, brdffit_model model,
                   int np, const bf_pass_par *pp, struct bf_pass_state *ps)
{
    bf_pass_state_clear(ps);
    if (has_rows(samples, bins)) {
        double floor[3];
        bf_lobe_row_floor((int)model, pp->p[0], pp->lam, floor);
        bf_lobe_rows((int)model, bins->table, (int)bins->hd[0], (int)bins->hd[samples->n - 1],
                     pp->p, np, pp->lam, floor, bins->rows, bins->nrows, &ps->lobe);
    }
}

void bf_host_sample(const brdffit_samples *samples, const bf_pass_bins *bins, size_t i,
                    brdffit_model model, int nk, int np, const bf_pass_par *pp, double *mom,
                    struct bf_pass_state *ps)
{
    const size_t npad = samples->npad;
    const double *f = samples->data;
    bf_geom g = { f[BF_F_IX * npad + i], f[BF_F_IY * npad + i], f[BF_F_IZ * npad + i],
                  f[BF_F_OX * npad + i], f[BF_F_OY * npad + i], f[BF_F_OZ * npad + i],
                  f[BF_F_NH * npad + i], f[BF_F_VH * npad + i] };
    double rho[3] = { f[BF_F_R * npad + i], f[BF_F_G * npad + i], f[BF_F_B * npad + i] };
    if (ps && has_rows(samples, bins))
        bf_lobe_bins(&ps->lobe, bins->hd[i]);
    bf_accumulate((int)model, nk, np, pp, &g, rho, f[BF_F_A2 * npad + i], mom, ps);
}

void bf_host_loop(const brdffit_samples *samples, const bf_pass_bins *bins, brdffit_model model,
                  int nk, int np, const bf_pass_par *pp, double *mom)
{
    int nmom = bf_nmom(nk, np);
    for (int m = 0; m < nmom; m++)
        mom[m] = 0.0;
    bf_pass_state state;
    bf_host_begin(samples, bins, model, np, pp, &state);
    const int rows = has_rows(samples, bins);
    if (rows)
        bf_pass_whole_bins(nk, np, pp, &state, (int)bins->hd[0], (int)bins->hd[samples->n - 1], 0,
                           (long)samples->n, mom);
    for (size_t i = 0; i < samples->n; i++) {
        double keep = 1.0; /* one lane: all of it summed with its bin, or none */
        long skip;
        if (rows && bf_pass_bins_skip(&state, bins->hd[i], (long)i, &keep, &skip)) {
            i += (size_t)skip; /* the bin summed whole */
            continue;
        }
        bf_host_sample(samples, bins, i, model, nk, np, pp, mom, &state);
    }
    bf_accumulate_end(nk, np, pp, mom, &state);
}
