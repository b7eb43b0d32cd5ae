/* SPDX-License-Identifier: MIT */
/*
 * bf_layout.h -- what the host and the kernel exchange in a data pass, and
 * nothing of the model maths: the fields of a prepared sample set, the point
 * of a pass (bf_pass_par) and the layout of the moments a pass returns.
 * Written once for the C library and the OpenCL kernel (see bf_common.h).
 *
 * The moments (see bf_pass.h for what they are), for nk = 1 lobe (or 3 for a
 * chromatic model) and np lobe coordinates (0 for a value-only pass):
 *   BF_MOM_A                     A = sum a^2
 *   per lobe k, at bf_mom_lobe(k, np), a block of bf_kblk(np):
 *     BF_MK_SK, BF_MK_SKK          sum a^2 K, sum a^2 K^2
 *     bf_mk_sg(j)                  sum a^2 G_j
 *     bf_mk_skg(np, j)             sum a^2 K G_j
 *     bf_mk_sgg(np, j, l), j <= l  sum a^2 G_j G_l
 *   per channel c, at bf_mom_chan(c, nk, np), a block of 3 + np:
 *     BF_MC_SE, BF_MC_SKE, BF_MC_SEE   sum a^2 e, a^2 K e, a^2 e^2
 *     bf_mc_sge(j)                 sum a^2 G_j e
 * The offsets inside a block are relative to the block's start.
 * (The bin table a He pass also reads is He's own: BF_B_* in bf_he_rows.h.)
 */
#ifndef BF_LAYOUT_H
#define BF_LAYOUT_H

#ifndef __OPENCL_VERSION__
#include "bf_common.h"
#endif

/* Fields of a prepared sample set: field f of sample i is data[f * npad + i]. */
enum {
    BF_F_IX, BF_F_IY, BF_F_IZ, /* wi (toward the light), unit */
    BF_F_OX, BF_F_OY, BF_F_OZ, /* wo (toward the viewer), unit */
    BF_F_NH, BF_F_VH,          /* N.H and V.H, as bf_geom_derive gives them */
    BF_F_R, BF_F_G, BF_F_B,    /* measured value x channel scale */
    BF_F_A2,                   /* w cos^2(theta_i) / (3 sum w): the metric's weight */
    BF_NFIELDS
};

/* Lobe coordinates a pass differentiates in, at most (bf_accumulate's
 * loops over them are written out three times: BF_UNROLL3). */
#define BF_MAX_NP 3
#if BF_MAX_NP != 3
#error "bf_accumulate (bf_pass.h) unrolls its loops over the coordinates to BF_MAX_NP = 3"
#endif

/* The point of a pass.  Only doubles: the same bytes in C and OpenCL C
 * (the kernel reads it as BF_PASS_PAR_DOUBLES doubles). */
typedef struct bf_pass_par {
    double d[3], s[3];            /* diffuse albedo and rho_s per channel     */
    double lam[3];                /* wavelengths (He)                         */
    double inv_h[BF_MAX_NP];      /* 1 / h_j                                  */
    double p[1 + BF_MAX_NP][3];   /* p[0]: lobe params; p[1+j]: at u + h_j e_j */
    double row_floor[3];          /* the bin rows' floor per channel at p[0]
                                   * (bf_lobe_row_floor; He): the pass driver
                                   * fills it for the kernel, once a pass     */
} bf_pass_par;
#define BF_PASS_PAR_DOUBLES (3 + 3 + 3 + BF_MAX_NP + 3 * (1 + BF_MAX_NP) + 3)

/* Offset of A; offsets inside a lobe block and inside a channel block. */
enum { BF_MOM_A = 0 };
enum { BF_MK_SK = 0, BF_MK_SKK = 1 };
enum { BF_MC_SE = 0, BF_MC_SKE = 1, BF_MC_SEE = 2 };

/* Block sizes and the moment count, as constant expressions. */
#define BF_KBLK(np) (2 + 2 * (np) + (np) * ((np) + 1) / 2)
#define BF_CBLK(np) (3 + (np))
#define BF_NMOM(nk, np) (1 + (nk) * BF_KBLK(np) + 3 * BF_CBLK(np))
#define BF_NMOM_MAX 61 /* BF_NMOM(3, BF_MAX_NP) */

#ifndef __OPENCL_VERSION__
_Static_assert(sizeof(bf_pass_par) == BF_PASS_PAR_DOUBLES * sizeof(double),
               "bf_pass_par must be BF_PASS_PAR_DOUBLES doubles, no padding");
_Static_assert(BF_NMOM_MAX == BF_NMOM(3, BF_MAX_NP), "BF_NMOM_MAX is the largest moment count");
#endif

BF_FN int bf_kblk(int np)
{
    return BF_KBLK(np);
}

BF_FN int bf_nmom(int nk, int np)
{
    return BF_NMOM(nk, np);
}

/* A (the sum of the weights a^2). */
BF_FN int bf_mom_A(void)
{
    return 0;
}

/* Offset of lobe k's block. */
BF_FN int bf_mom_lobe(int k, int np)
{
    return 1 + k * BF_KBLK(np);
}

/* Offset of channel c's block. */
BF_FN int bf_mom_chan(int c, int nk, int np)
{
    return 1 + nk * BF_KBLK(np) + c * BF_CBLK(np);
}

/* Inside a lobe block: SG_j, SKG_j, SGG_jl (j <= l < np). */
BF_FN int bf_mk_sg(int j)
{
    return 2 + j;
}

BF_FN int bf_mk_skg(int np, int j)
{
    return 2 + np + j;
}

BF_FN int bf_mk_sgg(int np, int j, int l)
{
    /* the pairs (j, l), j <= l, row by row: row j starts after
     * np + (np - 1) + ... + (np - j + 1) = j np - j (j - 1) / 2 pairs */
    return 2 + 2 * np + j * np - j * (j - 1) / 2 + (l - j);
}

/* Inside a channel block: SGE_j. */
BF_FN int bf_mc_sge(int j)
{
    return 3 + j;
}

#endif /* BF_LAYOUT_H */
