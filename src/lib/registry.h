/* SPDX-License-Identifier: MIT */
/* registry.h -- the model registry: every fact about a model, written once in
 * registry.c.  The public part (brdffit_model_info, brdffit_param_info) is what
 * brdffit_model_get and brdffit_model_param return; the rest is for the fit
 * (its start grid) and the data pass (its lobe functions). */
#ifndef BRDFFIT_REGISTRY_H
#define BRDFFIT_REGISTRY_H

#include "internal.h"

#include "bf_lobe.h"

/* A model's lobe (bf_lobe_<model>) and its forward differences (see bf_lobe.h). */
typedef void bf_lobe_fn(const bf_geom *g, const double *p, const double *lam, double *K);
typedef void bf_lobe_fd_fn(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                           double *K0, double (*Kj)[3], bf_lobe_state *st);

/* The starting points a fit screens.  Start i of n has every lobe parameter at
 * its `start` value except:
 *   param        set to the i-th point of lo..hi, evenly spaced (LINEAR) or
 *                geometrically (LOG): over all n starts when period is 0,
 *                else over `period` points repeated (i % period);
 *   round_param  (unless -1) multiplied by round_factor once per completed
 *                round of `period` starts (i / period), capped at its upper bound. */
typedef struct bf_start_grid {
    int param;
    brdffit_param_map spacing;
    double lo, hi;
    int period;
    int round_param;
    double round_factor;
} bf_start_grid;

typedef struct bf_model_def {
    brdffit_model_info info;     /* the public descriptor                       */
    bf_start_grid grid;          /* the starts the fit screens                  */
    bf_lobe_fn *lobe;            /* host: K per channel                         */
    const char *lobe_name;       /* kernel: -DBF_LOBE=<this>                    */
    bf_lobe_fd_fn *lobe_fd;      /* NULL: the pass evaluates the lobe at each
                                    forward-difference point                    */
    const char *lobe_fd_name;    /* kernel: -DBF_LOBE_FD=<this> (when lobe_fd)  */
} bf_model_def;

/* The registry entry of a model, or NULL for an id out of range. */
const bf_model_def *bf_model_def_get(brdffit_model model);

/* The lobe coordinates a fit uses for a model: one per parameter, one per
 * DIRECTION pair (Lafortune: direction + n = 2); 0 for an unknown model. */
int bf_model_ncoords(brdffit_model model);
/* The first parameter of lobe coordinate j (-1 when out of range). */
int bf_model_coord_param(brdffit_model model, int j);
/* Every lobe parameter at its `start` value (unused entries 0). */
void bf_model_start_params(brdffit_model model, double p[BRDFFIT_MAX_LOBE_PARAMS]);

#endif
