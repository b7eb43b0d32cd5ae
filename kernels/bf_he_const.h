/* SPDX-License-Identifier: MIT */
/* bf_he_const.h -- the constants of the He lobe's numerics, shared by its
 * parts (bf_he_model.h and bf_he_pass.h say what each part does and why
 * these values). */
#ifndef BF_HE_CONST_H
#define BF_HE_CONST_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#endif

#define BF_HE_G_LO 18.0      /* below: the series                  */
#define BF_HE_G_HI 19.0      /* above: the rough-surface limit      */
#define BF_HE_MMAX 400       /* last term of the series             */
#define BF_HE_COS_MIN 1e-100 /* floor of cos ti, cos to, cos theta_b */
#define BF_HE_LN_DEAD (-760.0) /* a lane below e^this is 0 (the rows: bf_he_row_floor) */
#define BF_HE_HEAD 40.0      /* a series starts within e^-40 of its peak term */
#define BF_HE_U_FLAT 6.0     /* u >= 6: erfc(u) and e^(-u^2) taken as 0 */
#define BF_HE_U_ROW 2.0      /* u >= 2: a pass's bin rows serve a lane whose sigma is sigma0
                              * or just below it (bf_he_near_serve) */
/* ln 18, ln 19, ln 400 (BF_HE_G_LO, BF_HE_G_HI, BF_HE_MMAX), correctly rounded:
 * written out, as the kernel compiler does not fold log() of a constant */
#define BF_HE_LN_G_LO 2.8903717578961645
#define BF_HE_LN_G_HI 2.9444389791664403
#define BF_HE_LN_MMAX 5.991464547107982

/* Tables of constants: in the kernel's constant memory, static on the host. */
#ifdef __OPENCL_VERSION__
#define BF_HE_CONSTANT __constant
#else
#define BF_HE_CONSTANT static const
#endif

#endif /* BF_HE_CONST_H */
