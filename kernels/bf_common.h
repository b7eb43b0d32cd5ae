/* SPDX-License-Identifier: MIT */
/*
 * bf_common.h -- the portability layer of the model maths.
 *
 * The files in kernels/ are written once, in the common subset of C99 and
 * OpenCL C, and compiled twice: into the C library (the files in src/lib include them)
 * and into the OpenCL fitting kernel (the library passes them, concatenated
 * in the order of the Makefile's KERNEL_SOURCES, to clCreateProgramWithSource;
 * in the kernel they do not include each other).  Nothing in them is
 * repeated anywhere else.
 *
 *   BF_REAL    the type of one "lane" of samples: double on the host, a
 *              vector of BF_WIDTH doubles in the kernel (-DBF_WIDTH=4|8).
 *   BF_SEL(a, b, c)   c ? b : a, lane by lane (OpenCL select()).
 *   BF_ANY(c)         true when c holds in some lane.
 *   BF_LAST(v), BF_FIRST(v)   the last and the first lane of v, as a double.
 *   BF_NLANES         the lanes of a BF_REAL (1 on the host, BF_WIDTH in the kernel).
 *   BF_IOTA           a BF_REAL whose lane i is i (0.0 on the host).
 *   BF_HSUM(v)        the sum of v's lanes, in a fixed order, as a double.
 *   bf_max_where(v, c, none)  the largest lane of v where c > 0 (none if no lane).
 *   BF_LOADC(p), BF_LOADP(p), BF_STORE(v, p)
 *                     BF_NLANES consecutive doubles from a constant table, from
 *                     private memory, and into private (or global) memory.
 *   BF_LOADG(p)       BF_NLANES consecutive doubles from global memory.
 *   BF_GATHERG(p, v)  the doubles p[(int)v] lane by lane from global memory
 *                     (v holds whole numbers >= 0), made in registers: a
 *                     vector loaded from private lanes stored one by one
 *                     waits for those stores (bf_he_bin_gather).
 *   BF_GATHERC(p, v)  the same from a constant table (bf_he_dlog).
 *   BF_GLOBAL         the address space of buffers a pass writes and reads
 *                     (__global in the kernel, nothing on the host).
 *   BF_FN, BF_FN_INLINE  how the functions are declared; BF_FN_INLINE is
 *                     always inlined into the kernel, so that its callers'
 *                     constants (the model, nk, np) fold into it.
 *   BF_UNROLL3(v, ...)   the statements ... three times, each in a block of
 *                     its own with the constant v = 0, 1, 2: a loop over the
 *                     channels or a pass's coordinates (np <= BF_MAX_NP = 3,
 *                     bf_layout.h) written out, so that every index it makes
 *                     is a constant (bf_accumulate, bf_pass.h).
 *
 * Code that uses BF_REAL is branch-free per lane: data-dependent choices go
 * through BF_SEL, loops that depend on the data run while BF_ANY(...).
 * Scalar parameters are plain double in both languages.
 */
#ifndef BF_COMMON_H
#define BF_COMMON_H

#define BF_UNROLL3(v, ...)                                                      \
    { const int v = 0; __VA_ARGS__ }                                            \
    { const int v = 1; __VA_ARGS__ }                                            \
    { const int v = 2; __VA_ARGS__ }

#ifdef __OPENCL_VERSION__
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#  ifndef BF_WIDTH
#    define BF_WIDTH 8
#  endif
#  if BF_WIDTH == 4
#    define BF_REAL double4
#    define BF_LAST(v) ((v).s3)
#    define BF_FIRST(v) ((v).s0)
#    define BF_IOTA ((double4)(0.0, 1.0, 2.0, 3.0))
#    define BF_LOADC(p) vload4(0, (p))
#    define BF_LOADP(p) vload4(0, (p))
#    define BF_STORE(v, p) vstore4((v), 0, (p))
#    define BF_LOADG(p) vload4(0, (p))
#    define BF_HSUM(v) (((v).s0 + (v).s1) + ((v).s2 + (v).s3))
#    define BF_GATHERG(p, v) bf_gatherg4((p), convert_int4(v))
inline double4 bf_gatherg4(__global const double *p, int4 i)
{
    return (double4)(p[i.s0], p[i.s1], p[i.s2], p[i.s3]);
}
#    define BF_GATHERC(p, v) bf_gatherc4((p), convert_int4(v))
inline double4 bf_gatherc4(__constant const double *p, int4 i)
{
    return (double4)(p[i.s0], p[i.s1], p[i.s2], p[i.s3]);
}
#  elif BF_WIDTH == 8
#    define BF_REAL double8
#    define BF_LAST(v) ((v).s7)
#    define BF_FIRST(v) ((v).s0)
#    define BF_IOTA ((double8)(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0))
#    define BF_LOADC(p) vload8(0, (p))
#    define BF_LOADP(p) vload8(0, (p))
#    define BF_STORE(v, p) vstore8((v), 0, (p))
#    define BF_LOADG(p) vload8(0, (p))
#    define BF_HSUM(v) ((((v).s0 + (v).s1) + ((v).s2 + (v).s3)) + (((v).s4 + (v).s5) + ((v).s6 + (v).s7)))
#    define BF_GATHERG(p, v) bf_gatherg8((p), convert_int8(v))
inline double8 bf_gatherg8(__global const double *p, int8 i)
{
    return (double8)(p[i.s0], p[i.s1], p[i.s2], p[i.s3], p[i.s4], p[i.s5], p[i.s6], p[i.s7]);
}
#    define BF_GATHERC(p, v) bf_gatherc8((p), convert_int8(v))
inline double8 bf_gatherc8(__constant const double *p, int8 i)
{
    return (double8)(p[i.s0], p[i.s1], p[i.s2], p[i.s3], p[i.s4], p[i.s5], p[i.s6], p[i.s7]);
}
#  else
#    error "BF_WIDTH must be 4 or 8"
#  endif
#  define BF_NLANES BF_WIDTH
#  define BF_GLOBAL __global
#  define BF_FN inline
#  define BF_FN_INLINE inline __attribute__((always_inline))
#  define BF_SEL(a, b, c) select((a), (b), (c))
/* BF_ANY from the lanes' bytes: OpenCL's any() tests each lane's sign bit,
 * which PoCL 3.1 made a reduction of the 64-bit lanes (a mask turned into
 * a vector, halved three times with an OR, moved to a register), while the
 * lanes of a comparison are 0 or -1, so narrowing them to 8 bits and testing
 * the 64 bits together says the same in three instructions.  Every BF_ANY
 * takes a comparison or a logical operation of comparisons.  He, where
 * BF_ANY guards every branch: a rough full pass 6-12% faster, a stride-subset
 * pass 2-10%, every sum the same to the bit. */
#  if BF_WIDTH == 8
#    define BF_ANY(c) (as_ulong(convert_char8(c)) != 0)
#  else
#    define BF_ANY(c) (as_uint(convert_char4(c)) != 0)
#  endif
#else
#  include <math.h>
#  define BF_REAL double
#  define BF_FN static inline
#  define BF_FN_INLINE static inline
#  define BF_SEL(a, b, c) ((c) ? (b) : (a))
#  define BF_ANY(c) (c)
#  define BF_LAST(v) (v)
#  define BF_FIRST(v) (v)
#  define BF_NLANES 1
#  define BF_IOTA 0.0
#  define BF_LOADC(p) (*(p))
#  define BF_LOADP(p) (*(p))
#  define BF_STORE(v, p) (*(p) = (v))
#  define BF_LOADG(p) (*(p))
#  define BF_GATHERG(p, v) ((p)[(int)(v)])
#  define BF_GATHERC(p, v) ((p)[(int)(v)])
#  define BF_GLOBAL
#  define BF_HSUM(v) (v)
#endif

#define BF_PI 3.14159265358979323846
#define BF_SQRT_PI 1.77245385090551602730
/* Smallest positive normal double: keeps logs and divisions finite. */
#define BF_TINY 2.2250738585072014e-308

#define BF_R(x) ((BF_REAL)(x))

BF_FN double bf_max_where(BF_REAL v, BF_REAL c, double none)
{
    double vv[BF_NLANES], cc[BF_NLANES], m = none;
    BF_STORE(v, vv);
    BF_STORE(c, cc);
    for (int i = 0; i < BF_NLANES; i++)
        if (cc[i] > 0.0 && !(vv[i] <= m))
            m = vv[i];
    return m;
}

/* 1 / a and 1 / b from one division (a division of 8 doubles holds the
 * divider ~16-24 cycles, a multiply half a cycle); a b must be a normal
 * double, which each caller says why it is. */
BF_FN void bf_rcp2(BF_REAL a, BF_REAL b, BF_REAL *ra, BF_REAL *rb)
{
    BF_REAL inv = 1.0 / (a * b);
    *ra = b * inv;
    *rb = a * inv;
}

#endif /* BF_COMMON_H */
