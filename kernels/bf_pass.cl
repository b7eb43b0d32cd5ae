/* SPDX-License-Identifier: MIT */
/*
 * bf_pass.cl -- the OpenCL data pass: the kernel side (src/lib/pass.c is the
 * host side that enqueues it).  The library prepends the kernel headers, in
 * the order the Makefile's KERNEL_SOURCES lists, and builds it once per model
 * and context with
 *     -DBF_MODEL=<id> -DBF_NP=<lobe coordinates> -DBF_NK=<1|3> -DBF_WIDTH=<4|8>
 * (the counts from the model registry, src/lib/registry.c).
 *
 * Each work-item walks a contiguous run of BF_WIDTH-wide sample vectors
 * (explicit vector types: PoCL does not vectorise scalar work-items that call
 * exp/log), keeps its sums in BF_REAL lanes, and writes their lane sums, in
 * double, to out[run * nmom ...].  Work-item gid takes run
 * (gid * order) mod (global size), order prime to it (bf_pass_order in
 * src/lib/pass.h says why); the host adds the runs' rows in run order.
 * Global size = number of runs (a multiple of the work-group size the host
 * picks); runs past the data write zeros.
 *
 * Two kernels: bf_kernel_full (value + forward-difference Jacobian moments,
 * np = BF_NP) and bf_kernel_value (np = 0: value moments only).
 */
#ifndef BF_MODEL
#error "build with -DBF_MODEL=<model id>"
#endif
/* BF_ROWS: 1 when the model's pass has bin rows (bf_lobe_has_own_fd: He).
 * The whole-bin code is compiled only into such a kernel: compiled in and
 * never run, it makes the others' full passes ~5% slower (Cook-Torrance),
 * with the same results to the bit. */
#ifndef BF_ROWS
#error "build with -DBF_ROWS=<1 for a model with bin rows, else 0>"
#endif

#if BF_WIDTH == 8
#define BF_VLOAD(i, p) vload8((i), (p))
#elif BF_WIDTH == 4
#define BF_VLOAD(i, p) vload4((i), (p))
#else
#error "BF_WIDTH must be 4 or 8"
#endif

/* One work-item's run of vectors, run number `run`: the body of both
 * kernels.  A model with bin rows (He: bf_lobe_rows) also gets the samples'
 * bins hd (npad doubles), the bin table and room for the rows: nrows per
 * field, run r's rows BF_NLANES r further on than the rows' start (its bins
 * begin where run r - 1's end, and a vector of rows reaches BF_NLANES - 1
 * past). */
BF_FN_INLINE void bf_kernel_pass(const int np, __global const double *data, const ulong npad,
                                 const uint vec_per_item, __constant const double *ppar,
                                 __global double *out, __global const double *hd,
                                 __global const double *bins, __global double *rows,
                                 const int nrows, const uint order)
{
    const uint run = (uint)(((ulong)get_global_id(0) * order) % get_global_size(0));
    const int nmom = bf_nmom(BF_NK, np);
    bf_pass_par pp;
    double *q = (double *)&pp;
    for (int i = 0; i < BF_PASS_PAR_DOUBLES; i++)
        q[i] = ppar[i];

    BF_REAL acc[BF_NMOM_MAX];
    for (int m = 0; m < nmom; m++)
        acc[m] = BF_R(0.0);

    bf_pass_state state;
    bf_pass_state_clear(&state);
    const ulong nvec = npad / BF_WIDTH;
    ulong v0 = (ulong)run * vec_per_item;
    ulong v1 = min(v0 + vec_per_item, nvec);
    if (nrows > 0 && v0 < v1) {
        const int h0 = (int)hd[v0 * BF_WIDTH], h1 = (int)hd[v1 * BF_WIDTH - 1];
        bf_lobe_rows(BF_MODEL, bins, h0, h1, pp.p, np, pp.lam, pp.row_floor,
                     rows + (ulong)run * BF_WIDTH, nrows, &state.lobe);
#if BF_ROWS
        bf_pass_whole_bins(BF_NK, np, &pp, &state, h0, h1, (long)(v0 * BF_WIDTH),
                           (long)(v1 * BF_WIDTH), acc);
#endif
    }
    for (ulong v = v0; v < v1; v++) {
#if BF_ROWS
        BF_REAL keep = BF_R(1.0); /* 0: a lane summed with its bin */
        if (nrows > 0) {
            const BF_REAL vhd = BF_VLOAD(v, hd);
            long skip;
            if (bf_pass_bins_skip(&state, vhd, (long)(v * BF_WIDTH), &keep, &skip)) {
                v += (ulong)skip; /* every lane summed with its bin */
                continue;
            }
            bf_lobe_bins(&state.lobe, vhd);
        }
#endif
        bf_geom g;
        g.ix = BF_VLOAD(v, data + BF_F_IX * npad);
        g.iy = BF_VLOAD(v, data + BF_F_IY * npad);
        g.iz = BF_VLOAD(v, data + BF_F_IZ * npad);
        g.ox = BF_VLOAD(v, data + BF_F_OX * npad);
        g.oy = BF_VLOAD(v, data + BF_F_OY * npad);
        g.oz = BF_VLOAD(v, data + BF_F_OZ * npad);
        g.nh = BF_VLOAD(v, data + BF_F_NH * npad);
        g.vh = BF_VLOAD(v, data + BF_F_VH * npad);
        BF_REAL rho[3];
        rho[0] = BF_VLOAD(v, data + BF_F_R * npad);
        rho[1] = BF_VLOAD(v, data + BF_F_G * npad);
        rho[2] = BF_VLOAD(v, data + BF_F_B * npad);
        BF_REAL a2 = BF_VLOAD(v, data + BF_F_A2 * npad);
#if BF_ROWS
        a2 = BF_SEL(a2, BF_R(0.0), keep == 0.0);
#else
        if (nrows > 0)
            bf_lobe_bins(&state.lobe, BF_VLOAD(v, hd));
#endif
        bf_accumulate(BF_MODEL, BF_NK, np, &pp, &g, rho, a2, acc, &state);
    }
    bf_accumulate_end(BF_NK, np, &pp, acc, &state);
    for (int m = 0; m < nmom; m++)
        out[(ulong)run * nmom + m] = BF_HSUM(acc[m]);
}

__kernel void bf_kernel_full(__global const double *data, const ulong npad, const uint vec_per_item,
                             __constant const double *ppar, __global double *out,
                             __global const double *hd, __global const double *bins,
                             __global double *rows, const int nrows, const uint order)
{
    bf_kernel_pass(BF_NP, data, npad, vec_per_item, ppar, out, hd, bins, rows, nrows, order);
}

__kernel void bf_kernel_value(__global const double *data, const ulong npad, const uint vec_per_item,
                              __constant const double *ppar, __global double *out,
                              __global const double *hd, __global const double *bins,
                              __global double *rows, const int nrows, const uint order)
{
    bf_kernel_pass(0, data, npad, vec_per_item, ppar, out, hd, bins, rows, nrows, order);
}
