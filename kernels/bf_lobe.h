/* SPDX-License-Identifier: MIT */
/*
 * bf_lobe.h -- one entry point to the lobes of every model, for the C library,
 * the OpenCL kernel and a renderer that includes it (it needs nothing else:
 * no allocation, no state).  The cases come from BF_MODEL_LOBES (bf_models.h);
 * in the kernel `model` is a compile-time constant (-DBF_MODEL=...), so the
 * switch folds away.  It includes the closed-form lobes (bf_models.h) and He
 * (bf_he_model.h) only; a data pass's forward differences, state and bin
 * rows are bf_lobe_pass.h's.
 */
#ifndef BF_LOBE_H
#define BF_LOBE_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#include "bf_he_model.h"
#endif

/* K per channel into K[0..2] of model `model` (a brdffit_model id; 0 for any
 * other) for lobe parameters p[0..2] (paper units) and, for a chromatic lobe
 * (He), wavelengths lam[0..2] in micrometres. */
BF_FN void bf_lobe(int model, const bf_geom *g, const double *p, const double *lam,
                   BF_REAL *K)
{
    switch (model) {
#define BF_LOBE_CASE(id, name, fd) \
    case id: bf_lobe_##name(g, p, lam, K); return;
    BF_MODEL_LOBES(BF_LOBE_CASE)
#undef BF_LOBE_CASE
    default: break;
    }
    K[0] = K[1] = K[2] = BF_R(0.0);
}

#endif /* BF_LOBE_H */
