/* SPDX-License-Identifier: MIT */
/* grid.h -- the MERL grid inside the library: bins <-> directions, the
 * bins' solid-angle weights, the table object's layout.  The public side of
 * the same mapping is brdffit_bin_index / _directions / _weight. */
#ifndef BRDFFIT_GRID_H
#define BRDFFIT_GRID_H

#include "brdffit.h"

#include <stddef.h>

#define BF_NTH BRDFFIT_MERL_NTH
#define BF_NTD BRDFFIT_MERL_NTD
#define BF_NPD BRDFFIT_MERL_NPD
#define BF_NBINS ((size_t)BRDFFIT_MERL_BINS)   /* bins per channel plane */
#define BF_NVALUES (3 * BF_NBINS)              /* stored values of a table */

struct brdffit_table {
    double v[BF_NVALUES]; /* R plane, G plane, B plane, bin b at v[c * BF_NBINS + b] */
};

/* "R", "G", "B" as characters, for messages. */
extern const char bf_channel_name[3];

/* The bin (i, j, k) of plane index b = k + 180*(j + 90*i), b < BF_NBINS. */
void bf_bin_ijk(size_t b, int *i, int *j, int *k);

/* The directions bin (i, j, k) stands for; (i, j, k) must be in range
 * (brdffit_bin_directions checks). */
void bf_bin_dirs(int i, int j, int k, double wi[3], double wo[3]);

/* The sines and cosines of every bin's angles and every bin's solid-angle
 * weight, for walking all the bins without a sin or cos per bin:
 * bf_bin_dirs_trig gives bf_bin_dirs's directions bit for bit, w[i][j] is
 * brdffit_bin_weight(i, j). */
typedef struct bf_grid_trig {
    double sth[BF_NTH], cth[BF_NTH], std[BF_NTD], ctd[BF_NTD], spd[BF_NPD], cpd[BF_NPD];
    double w[BF_NTH][BF_NTD];
} bf_grid_trig;
void bf_grid_trig_init(bf_grid_trig *g);
void bf_bin_dirs_trig(const bf_grid_trig *g, int i, int j, int k, double wi[3], double wo[3]);

/* The continuous grid coordinates of a direction pair (the inverse of
 * bf_bin_dirs): u[0] = theta_h index, u[1] = theta_d index, u[2] = phi_d
 * index, phi_d folded into [0, pi].  Returns 0 for a non-finite or zero
 * direction or for wo = -wi. */
int bf_grid_coords(const double wi[3], const double wo[3], double u[3]);

#endif /* BRDFFIT_GRID_H */
