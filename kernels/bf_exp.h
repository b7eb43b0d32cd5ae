/* SPDX-License-Identifier: MIT */
/*
 * bf_exp.h -- the exponential of the lobes' hot loops (He's series terms and
 * tables, the power lobes' x^n), written out: PoCL 3.1's double exp scales
 * by 2^n in two steps and clamps both ends for the whole double range, half
 * of the work of a term of He's series.
 *
 *   bf_exp(x)       e^x for x in [-708, 709] (x is clamped to it): Cody and
 *                   Waite's reduction x = n ln 2 + r, |r| <= ln 2 / 2, with
 *                   ln 2 in fdlibm's two parts (n ln2_hi is exact for
 *                   |n| < 2^20), e^r by its Taylor polynomial of degree 12
 *                   (remainder below 1.7e-16 relative), times 2^n made from
 *                   its exponent bits (a normal number for n >= -1022).
 *                   Within 3 ulp of exp over the range (tests/test_exp.c;
 *                   glibc's exp is within 1).
 *   bf_exp_wide(x)  e^x for any x <= 709: as bf_exp, and where 2^n is not
 *                   normal (x below about -708) e^r 2^(n + 256) 2^-256,
 *                   which rounds once into the subnormals as exp does, and
 *                   0 below -745.2 (where exp rounds to 0).
 *
 * n is x / ln 2 rounded to nearest by adding and taking away 1.5 2^52
 * (|x / ln 2| < 2^51): OpenCL's rint is not a vector instruction under PoCL
 * (it cost more than the polynomial).  The kernel takes the multiply-adds
 * as fma; the host, compiled for plain x86-64, as a multiply and an add (a
 * software fma would be slower): the two differ by rounding alone.
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

/* e^r 2^-n for x = n ln 2 + r (n whole, |r| <= ln 2 / 2), x in [-800, 709]. */
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

BF_FN_INLINE BF_REAL bf_exp(BF_REAL x)
{
    BF_REAL n;
    BF_REAL p = bf_exp_reduced(fmin(fmax(x, BF_R(-708.0)), BF_R(709.0)), &n);
    return p * BF_POW2I(n);
}

/* Where n < -1022, 2^n as 2^(n + 256) 2^-256: one rounding, into the
 * subnormals.  Below -745.2, where e^x rounds to 0, the scale is 0: a
 * product that underflows takes the processor's slow path (a Lafortune
 * value pass with most lanes there twice as long). */
BF_FN_INLINE BF_REAL bf_exp_wide(BF_REAL x)
{
    BF_REAL n;
    BF_REAL p = bf_exp_reduced(fmin(fmax(x, BF_R(-800.0)), BF_R(709.0)), &n);
    BF_REAL low = BF_SEL(BF_R(0.0), BF_R(1.0), n < -1022.0);
    BF_REAL scale = BF_SEL(BF_R(1.0), BF_R(8.636168555094445e-78), low > 0.0);
    return (p * BF_POW2I(n + 256.0 * low)) * BF_SEL(scale, BF_R(0.0), x < -745.2);
}

#endif /* BF_EXP_H */
