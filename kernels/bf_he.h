/*
 * bf_he.h -- the He et al. 1991 lobe as Ngan et al. fitted it (p0 = tau,
 * p1 = sigma0, p2 = n).  PLACEHOLDER until the He issue lands: K = 0.
 */
#ifndef BF_HE_H
#define BF_HE_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#endif

BF_FN void bf_he(const bf_geom *g, double tau, double sigma0, double n,
                 const double *lam, BF_REAL *K)
{
    (void)g; (void)tau; (void)sigma0; (void)n; (void)lam;
    K[0] = BF_R(0.0);
    K[1] = BF_R(0.0);
    K[2] = BF_R(0.0);
}

#endif /* BF_HE_H */
