/* SPDX-License-Identifier: MIT */
/*
 * bf_exp.h -- the exponential of the lobes' hot loops (He's series terms and
 * tables, the power lobes' x^n).  In the kernel it is written out: PoCL
 * 3.1's double exp scales by 2^n in two steps and clamps both ends of the
 * whole double range, half of the work of a term of He's series.  On the
 * host (scalar) glibc's exp is faster and is used, with the same clamps.
 *
 *   bf_exp(x)       e^x for x in [-708, 709] (x is clamped to it).
 *   bf_exp_wide(x)  e^x for any x <= 709 (clamped there), subnormal results
 *                   included, and 0 below -745.2 (where exp rounds to 0).
 * Neither is given a NaN by its callers (the host's would return NaN, the
 * kernel's a clamp's value).
 *
 * The kernel's (bf_exp_poly, bf_exp_wide_poly, compiled on the host too for
 * tests/test_models.c, exp_function): Cody and Waite's reduction
 * x = n ln 2 + r, |r| <= ln 2 / 2, with ln 2 in fdlibm's two parts
 * (n ln2_hi is exact for |n| < 2^20), e^r by its Taylor polynomial of
 * degree 12 (remainder below 1.7e-16 relative), times 2^n made from its
 * exponent bits (a normal number for n >= -1022): within 5e-16 relative of
 * exp (2.3 ulp; glibc's is within 1).  Where 2^n is not normal (x below
 * about -708) the wide one takes e^r 2^(n + 256) 2^-256, which rounds once
 * into the subnormals as exp does; below -745.2 it scales by 0, as a
 * product that underflows takes the processor's slow path.  n is x / ln 2
 * rounded to nearest by adding and taking away 1.5 2^52 (|x / ln 2| < 2^51):
 * OpenCL's rint is not a vector instruction under PoCL (it cost more than
 * the polynomial).  The kernel takes the multiply-adds as fma, the host as a
 * multiply and an add (a software fma would be slower).
 */
#ifndef BF_EXP_H
#define BF_EXP_H

#ifndef __OPENCL_VERSION__
#include "bf_common.h"
#endif

#define BF_EXP_LN2_HI 6.93147180369123816490e-01
#define BF_EXP_LN2_LO 1.90821492927058770002e-10
#define BF_EXP_SHIFT 6755399441055744.0 /* 1.5 2^52 */

#ifdef __OPENCL_VERSION__
#  if BF_WIDTH == 8
#    define BF_POW2I(n) as_double8((convert_long8(n) + 1023L) << 52)
#  else
#    define BF_POW2I(n) as_double4((convert_long4(n) + 1023L) << 52)
#  endif
#  define BF_FMA(a, b, c) fma((a), (b), (c))
#else
/* 2^n for a whole n in [-1022, 1023] */
static inline double bf_pow2i(double n)
{
    union {
        double d;
        unsigned long long u;
    } v;
    v.u = (unsigned long long)((long long)n + 1023) << 52;
    return v.d;
}
#  define BF_POW2I(n) bf_pow2i(n)
#  define BF_FMA(a, b, c) ((a) * (b) + (c))
#endif

/* e^r, and n into *n, for x = n ln 2 + r (n whole, |r| <= ln 2 / 2; x in
 * [-800, 709]): e^x = e^r 2^n. */
BF_FN_INLINE BF_REAL bf_exp_reduced(BF_REAL x, BF_REAL *n)
{
    BF_REAL k = (x * 1.44269504088896340736 + BF_EXP_SHIFT) - BF_EXP_SHIFT;
    BF_REAL r = BF_FMA(k, BF_R(-BF_EXP_LN2_HI), x);
    r = BF_FMA(k, BF_R(-BF_EXP_LN2_LO), r);
    BF_REAL p = BF_R(1.0 / 479001600.0);
    p = BF_FMA(p, r, BF_R(1.0 / 39916800.0));
    p = BF_FMA(p, r, BF_R(1.0 / 3628800.0));
    p = BF_FMA(p, r, BF_R(1.0 / 362880.0));
    p = BF_FMA(p, r, BF_R(1.0 / 40320.0));
    p = BF_FMA(p, r, BF_R(1.0 / 5040.0));
    p = BF_FMA(p, r, BF_R(1.0 / 720.0));
    p = BF_FMA(p, r, BF_R(1.0 / 120.0));
    p = BF_FMA(p, r, BF_R(1.0 / 24.0));
    p = BF_FMA(p, r, BF_R(1.0 / 6.0));
    p = BF_FMA(p, r, BF_R(0.5));
    p = BF_FMA(p, r, BF_R(1.0));
    *n = k;
    return BF_FMA(p, r, BF_R(1.0));
}

BF_FN_INLINE BF_REAL bf_exp_poly(BF_REAL x)
{
    BF_REAL n;
    BF_REAL p = bf_exp_reduced(fmin(fmax(x, BF_R(-708.0)), BF_R(709.0)), &n);
    return p * BF_POW2I(n);
}

/* (Were the product to underflow there, a Lafortune value pass with most
 * lanes below -745.2 would take twice as long.) */
BF_FN_INLINE BF_REAL bf_exp_wide_poly(BF_REAL x)
{
    BF_REAL n;
    BF_REAL p = bf_exp_reduced(fmin(fmax(x, BF_R(-800.0)), BF_R(709.0)), &n);
    BF_REAL low = BF_SEL(BF_R(0.0), BF_R(1.0), n < -1022.0);
    BF_REAL scale = BF_SEL(BF_R(1.0), BF_R(8.636168555094445e-78), low > 0.0);
    return (p * BF_POW2I(n + 256.0 * low)) * BF_SEL(scale, BF_R(0.0), x < -745.2);
}

#ifdef __OPENCL_VERSION__
#  define bf_exp(x) bf_exp_poly(x)
#  define bf_exp_wide(x) bf_exp_wide_poly(x)
#else
/* The host's scalar exp is glibc's (table-driven, faster than the
 * polynomial there), with the same clamps, taken by comparisons (fmin and
 * fmax are calls on plain x86-64: two more a term made He's C evaluator 15%
 * slower), and the same 0 below -745.2 (where glibc would take its underflow
 * path: the power lobes' C evaluators 15-25% faster than with exp alone). */
static inline double bf_exp(double x)
{
    return exp(x < -708.0 ? -708.0 : x > 709.0 ? 709.0 : x);
}

static inline double bf_exp_wide(double x)
{
    return x < -745.2 ? 0.0 : exp(x > 709.0 ? 709.0 : x);
}
#endif

#endif /* BF_EXP_H */
