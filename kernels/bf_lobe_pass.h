/* SPDX-License-Identifier: MIT */
/*
 * bf_lobe_pass.h -- the lobes in a data pass (bf_pass.h): each model's
 * forward differences (bf_lobe_fd), the state a lobe carries from vector to
 * vector, and He's bin rows (bf_he_pass.h).  bf_lobe.h (the lobes' values)
 * does not include this; the library's pass and the kernel do.
 */
#ifndef BF_LOBE_PASS_H
#define BF_LOBE_PASS_H

#ifndef __OPENCL_VERSION__
#include "bf_lobe.h"
#include "bf_he_pass.h"
#endif

/* What a lobe may carry from one vector of samples to the next within a
 * data pass, which walks the samples in table order: each lobe that keeps
 * something has its member (He: the memos of its series and the pass's bin
 * rows, bf_he_fd); the other lobes keep nothing.  A pass zeroes it
 * (bf_lobe_state_clear) at the start of each run of samples, hands it the
 * rows (bf_lobe_rows) and then each vector's bins (bf_lobe_bins), and hands
 * it to bf_lobe_fd vector after vector. */
typedef struct bf_lobe_state {
    bf_he_memo he;
} bf_lobe_state;

BF_FN void bf_lobe_state_clear(bf_lobe_state *st)
{
    bf_he_memo_clear(&st->he);
}

/* He's forward differences with its member of the state (NULL: no memo). */
BF_FN void bf_lobe_fd_he(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                         BF_REAL *K0, BF_REAL (*Kj)[3], bf_lobe_state *st)
{
    bf_he_fd(g, p, np, lam, K0, Kj, st ? &st->he : (bf_he_memo *)0);
}

/* sum_i dK[i] (q[i] - p[i]): the first-order change of a lobe from p to q. */
BF_FN BF_REAL bf_dk_step(const BF_REAL *dK, const double *p, const double *q)
{
    return (dK[0] * (q[0] - p[0]) + dK[1] * (q[1] - p[1])) + dK[2] * (q[2] - p[2]);
}

/* K0 = k0 and the neighbours K(p[0]) + dK . (p[1 + j] - p[0]) of a lobe
 * with partials dK, the same in every channel (BF_FD_GRAD, BF_FD_SCHLICK). */
BF_FN void bf_lobe_fd_partials(BF_REAL k0, const BF_REAL *dK, const double (*p)[3], int np,
                               BF_REAL *K0, BF_REAL (*Kj)[3])
{
    K0[0] = K0[1] = K0[2] = k0;
    for (int j = 0; j < np; j++)
        Kj[j][0] = Kj[j][1] = Kj[j][2] = k0 + bf_dk_step(dK, p[0], p[1 + j]);
}

/* The value and partials of a lobe whose fd is BF_FD_GRAD (bf_<model>_vdk)
 * or BF_FD_SCHLICK (K = F(F0, V.H) R(p[1]): F0's partial from Schlick's
 * factor, p[1]'s from bf_<model>_rest_vdk).  The value is bit for bit
 * bf_lobe's. */
#define BF_VDK_BF_FD_POINTWISE(name)
#define BF_VDK_BF_FD_OWN(name)
#define BF_VDK_BF_FD_GRAD(name) return bf_##name##_vdk(g, p, dK);
#define BF_VDK_BF_FD_SCHLICK(name)                              \
    {                                                           \
        BF_REAL dr = BF_R(0.0);                                 \
        BF_REAL r0 = bf_##name##_rest_vdk(g, p[1], &dr);        \
        BF_REAL f0 = bf_schlick(p[0], g->vh);                   \
        dK[0] = (1.0 - bf_schlick(0.0, g->vh)) * r0;            \
        dK[1] = f0 * dr;                                        \
        return f0 * r0;                                         \
    }

/* A lobe's value K(p) and its partials dK[i] = dK / dp_i, for the lobes
 * that have them (bf_lobe_fd_kind BF_FD_KIND_PARTIALS); dK is 0 where a
 * lobe has fewer parameters, and K and dK are 0 for the other lobes. */
BF_FN_INLINE BF_REAL bf_lobe_vdk(int model, const bf_geom *g, const double *p, BF_REAL *dK)
{
    dK[0] = dK[1] = dK[2] = BF_R(0.0);
    switch (model) {
#define BF_LOBE_VDK_CASE(id, name, fd) \
    case id: { BF_VDK_##fd(name) } break;
        BF_MODEL_LOBES(BF_LOBE_VDK_CASE)
#undef BF_LOBE_VDK_CASE
    default: break;
    }
    return BF_R(0.0);
}

/* The kinds of forward differences a BF_MODEL_LOBES entry names. */
#define BF_FD_POINTWISE(name)                                   \
    bf_lobe_##name(g, p[0], lam, K0);                           \
    for (int j = 0; j < np; j++)                                \
        bf_lobe_##name(g, p[1 + j], lam, Kj[j]);
#define BF_FD_GRAD(name)                                        \
    if (np == 0)                                                \
        bf_lobe_##name(g, p[0], lam, K0);                       \
    else {                                                      \
        BF_REAL dk[3];                                          \
        BF_REAL k0 = bf_lobe_vdk(model, g, p[0], dk);           \
        bf_lobe_fd_partials(k0, dk, p, np, K0, Kj);             \
    }
#define BF_FD_SCHLICK(name) BF_FD_GRAD(name)
#define BF_FD_OWN(name) bf_lobe_fd_##name(g, p, np, lam, K0, Kj, st);

/* K at p[0] and at the np forward-difference neighbours p[1..np] of a data
 * pass (see bf_pass.h): K0[c] = K(p[0]) as bf_lobe gives it, bit for bit,
 * Kj[j][c] ~ K(p[1 + j]).  A BF_FD_POINTWISE lobe is evaluated at each
 * point; a BF_FD_GRAD lobe gives K(p[0]) plus its partials
 * (bf_<model>_vdk, bf_models.h) times p[1 + j] - p[0], and a BF_FD_SCHLICK
 * one (K = F(F0, V.H) R(p[1])) the same from Schlick's partial in F0 and
 * its rest's in p[1] (bf_<model>_rest_vdk): a full pass then costs a value
 * pass and a few products a sample instead of 1 + np lobes.  He
 * (BF_FD_OWN) sums its series once and carries it to the neighbours to first
 * order in its log, and with a state (NULL: none) reuses the previous
 * vector's series where g and a are unchanged, and with the pass's bin rows
 * (bf_lobe_rows) takes a flat vector's whole value from them (bf_he_fd; K0
 * is then bf_he_pass_value's to ~1e-12, and the model's bf_he to ~1e-12). */
BF_FN_INLINE void bf_lobe_fd(int model, const bf_geom *g, const double (*p)[3], int np,
                             const double *lam, BF_REAL *K0, BF_REAL (*Kj)[3], bf_lobe_state *st)
{
    (void)st;
    switch (model) {
#define BF_LOBE_FD_CASE(id, name, fd) \
    case id: { fd(name) } return;
    BF_MODEL_LOBES(BF_LOBE_FD_CASE)
#undef BF_LOBE_FD_CASE
    default: break;
    }
    K0[0] = K0[1] = K0[2] = BF_R(0.0);
    for (int j = 0; j < np; j++)
        Kj[j][0] = Kj[j][1] = Kj[j][2] = BF_R(0.0);
}

/* The factored form of a vector: where a lobe's K at every point p[j] of a
 * pass is F[j][c] q, with q per lane and the factors F fixed over a run of
 * vectors (He's bin rows: F = bk, q = 1 / (cos ti cos to)), a pass can sum
 * the run's moments from a few sums of q (bf_fold in bf_pass.h).
 * bf_lobe_fd_factored returns 1 and sets *q for such a vector, leaving K0
 * and Kj unset; its factors are bf_lobe_factor(st, j, c), unchanged while
 * bf_lobe_factor_gen(st) is.  Otherwise it is bf_lobe_fd and returns 0.
 * Only BF_FD_OWN lobes factor (bf_lobe_fdf_<name>). */
BF_FN int bf_lobe_fdf_he(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                         BF_REAL *K0, BF_REAL (*Kj)[3], bf_lobe_state *st, BF_REAL *q)
{
    return bf_he_fd_factored(g, p, np, lam, K0, Kj, &st->he, q);
}

#define BF_FDF_BF_FD_POINTWISE(name)
#define BF_FDF_BF_FD_GRAD(name)
#define BF_FDF_BF_FD_SCHLICK(name)
#define BF_FDF_BF_FD_OWN(name) return bf_lobe_fdf_##name(g, p, np, lam, K0, Kj, st, q);

BF_FN_INLINE int bf_lobe_fd_factored(int model, const bf_geom *g, const double (*p)[3],
                                     int np, const double *lam, BF_REAL *K0, BF_REAL (*Kj)[3],
                                     bf_lobe_state *st, BF_REAL *q)
{
    if (st) {
        switch (model) {
#define BF_LOBE_FDF_CASE(id, name, fd) \
    case id: { BF_FDF_##fd(name) } break;
            BF_MODEL_LOBES(BF_LOBE_FDF_CASE)
#undef BF_LOBE_FDF_CASE
        default: break;
        }
    }
    bf_lobe_fd(model, g, p, np, lam, K0, Kj, st);
    return 0;
}

/* The bin rows of a pass (He: bf_he_bin_rows), for the lobes that have them
 * (BF_FD_OWN): made for the bins h0 .. h1 of the bin table `bins` (bf_he_rows.h)
 * into rows (nrows per field) and handed to st, which then serves a vector
 * whose lanes are flat from them, given the vector's bins (bf_lobe_bins). */
BF_FN void bf_lobe_rows_he(BF_GLOBAL const double *bins, int h0, int h1, const double (*p)[3],
                           int np, const double *lam, const double *floor, BF_GLOBAL double *rows,
                           int nrows, bf_lobe_state *st)
{
    bf_he_bin_rows(bins, h0, h1, p, np, lam, floor, rows, nrows);
    st->he.rows = rows;
    st->he.nrows = nrows;
    st->he.bins = bins;
    st->he.cot_sure = bf_he_cot_sure(p[0][0], p[0][1]);
}

#define BF_ROWS_BF_FD_POINTWISE(name)
#define BF_ROWS_BF_FD_GRAD(name)
#define BF_ROWS_BF_FD_SCHLICK(name)
#define BF_ROWS_BF_FD_OWN(name) bf_lobe_rows_##name(bins, h0, h1, p, np, lam, floor, rows, nrows, st);

/* floor: bf_lobe_row_floor's at p[0]. */
BF_FN void bf_lobe_rows(int model, BF_GLOBAL const double *bins, int h0, int h1,
                        const double (*p)[3], int np, const double *lam, const double *floor,
                        BF_GLOBAL double *rows, int nrows, bf_lobe_state *st)
{
    switch (model) {
#define BF_LOBE_ROWS_CASE(id, name, fd) \
    case id: { BF_ROWS_##fd(name) } break;
        BF_MODEL_LOBES(BF_LOBE_ROWS_CASE)
#undef BF_LOBE_ROWS_CASE
    default: break;
    }
}

/* The floor of the bin rows at lobe parameters p0 (He: bf_he_row_floors)
 * into floor[3], once a pass; 0 for a lobe without rows. */
#define BF_FLOOR_BF_FD_POINTWISE(name)
#define BF_FLOOR_BF_FD_GRAD(name)
#define BF_FLOOR_BF_FD_SCHLICK(name)
#define BF_FLOOR_BF_FD_OWN(name) bf_##name##_row_floors(p0, lam, floor);

BF_FN void bf_lobe_row_floor(int model, const double *p0, const double *lam, double *floor)
{
    floor[0] = floor[1] = floor[2] = 0.0;
    switch (model) {
#define BF_LOBE_FLOOR_CASE(id, name, fd) \
    case id: { BF_FLOOR_##fd(name) } break;
        BF_MODEL_LOBES(BF_LOBE_FLOOR_CASE)
#undef BF_LOBE_FLOOR_CASE
    default: break;
    }
}

/* The bins hd of the lanes of the next vector (for the rows). */
BF_FN void bf_lobe_bins(bf_lobe_state *st, BF_REAL hd)
{
    st->he.vhd = hd;
}

/* 1 in the lanes (bins vhd) whose bin a pass sums whole from the bin
 * table's sums (He: bf_he_bin_whole; bf_pass_whole_bins in bf_pass.h); 0
 * for a lobe without rows. */
BF_FN BF_REAL bf_lobe_bin_whole(const bf_lobe_state *st, BF_REAL vhd)
{
    return bf_he_bin_whole(&st->he, vhd);
}

/* The bin table of the pass's rows (NULL: none). */
BF_FN BF_GLOBAL const double *bf_lobe_bin_table(const bf_lobe_state *st)
{
    return st->he.bins;
}

/* Field 3 j + c of the pass's rows (K cos ti cos to at p[j], channel c) of
 * the bins h .. h + BF_NLANES - 1. */
BF_FN BF_REAL bf_lobe_bin_row(const bf_lobe_state *st, int j, int c, int h)
{
    return BF_LOADG(st->he.rows + (3 * j + c) * st->he.nrows + h);
}

BF_FN double bf_lobe_factor_gen(const bf_lobe_state *st)
{
    return st->he.bgen;
}

BF_FN double bf_lobe_factor(const bf_lobe_state *st, int j, int c)
{
    return st->he.bk[j][c];
}

/* How a model's lobe takes a data pass's forward differences (the fd of its
 * BF_MODEL_LOBES entry): BF_FD_KIND_POINTWISE (the lobe's values at each
 * point, bit for bit), BF_FD_KIND_PARTIALS (BF_FD_GRAD, BF_FD_SCHLICK: its
 * value and partials) or BF_FD_KIND_OWN (BF_FD_OWN: He, with bin rows). */
enum { BF_FD_KIND_POINTWISE, BF_FD_KIND_PARTIALS, BF_FD_KIND_OWN };
BF_FN int bf_lobe_fd_kind(int model)
{
#define BF_FD_KIND_BF_FD_POINTWISE BF_FD_KIND_POINTWISE
#define BF_FD_KIND_BF_FD_GRAD BF_FD_KIND_PARTIALS
#define BF_FD_KIND_BF_FD_SCHLICK BF_FD_KIND_PARTIALS
#define BF_FD_KIND_BF_FD_OWN BF_FD_KIND_OWN
#define BF_LOBE_KIND_CASE(id, name, fd) \
    if (model == id) return BF_FD_KIND_##fd;
    BF_MODEL_LOBES(BF_LOBE_KIND_CASE)
#undef BF_LOBE_KIND_CASE
    return BF_FD_KIND_POINTWISE;
}

/* 1 when a model's lobe has forward differences of its own (BF_FD_OWN: it
 * has bin rows). */
BF_FN int bf_lobe_has_own_fd(int model)
{
    return bf_lobe_fd_kind(model) == BF_FD_KIND_OWN;
}

#endif /* BF_LOBE_PASS_H */
