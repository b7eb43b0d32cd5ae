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
 *   BF_LAST(v)        the last lane of v, as a double.
 *
 * Code that uses BF_REAL is branch-free per lane: data-dependent choices go
 * through BF_SEL, loops that depend on the data run while BF_ANY(...).
 * Scalar parameters are plain double in both languages.
 */
#ifndef BF_COMMON_H
#define BF_COMMON_H

#ifdef __OPENCL_VERSION__
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#  ifndef BF_WIDTH
#    define BF_WIDTH 8
#  endif
#  if BF_WIDTH == 4
#    define BF_REAL double4
#    define BF_LAST(v) ((v).s3)
#  elif BF_WIDTH == 8
#    define BF_REAL double8
#    define BF_LAST(v) ((v).s7)
#  else
#    error "BF_WIDTH must be 4 or 8"
#  endif
#  define BF_FN inline
#  define BF_SEL(a, b, c) select((a), (b), (c))
#  define BF_ANY(c) any(c)
#else
#  include <math.h>
#  define BF_REAL double
#  define BF_FN static inline
#  define BF_SEL(a, b, c) ((c) ? (b) : (a))
#  define BF_ANY(c) (c)
#  define BF_LAST(v) (v)
#endif

#define BF_PI 3.14159265358979323846
#define BF_SQRT_PI 1.77245385090551602730
/* Smallest positive normal double: keeps logs and divisions finite. */
#define BF_TINY 2.2250738585072014e-308

#define BF_R(x) ((BF_REAL)(x))

#endif /* BF_COMMON_H */
