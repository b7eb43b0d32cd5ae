/* SPDX-License-Identifier: MIT */
/* dropin.c -- the promise docs/library.md makes to renderers: the installed evaluator headers
 * (<brdffit/bf_lobe.h>, <brdffit/bf_gltf.h>) compile on their own, in C and in C++, and
 * bf_lobe gives the lobe brdffit_eval evaluates (f = d/pi + s K), for every model of that
 * form; bf_gltf gives the glTF models' value (tests/packaging.sh). */
#include <brdffit.h>
#include <brdffit/bf_gltf.h>
#include <brdffit/bf_lobe.h>

#include <math.h>
#include <stdio.h>

int main(void)
{
    double wi[3] = { 0.3, -0.2, 0.9 }, wo[3] = { -0.25, 0.3, 0.85 };
    /* unit vectors, as bf_geom wants them (brdffit_eval normalises itself) */
    double li = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
    double lo = sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
    for (int c = 0; c < 3; c++) {
        wi[c] /= li;
        wo[c] /= lo;
    }
    const double lam[3] = { 0.645, 0.526, 0.444 };
    int bad = 0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        if (mi->colour_form == BRDFFIT_COLOUR_OPENPBR)
            continue; /* its albedo table is the library's: not a drop-in header */
        const int gltf = mi->colour_form == BRDFFIT_COLOUR_GLTF;
        brdffit_params p = { { 0, 0, 0 }, { 1, 1, 1 }, { 0, 0, 0 }, { 0, 0, 0 } };
        if (gltf) /* a base colour, half metal */
            p.d[0] = 0.6, p.d[1] = 0.4, p.d[2] = 0.2;
        for (int k = 0; k < mi->nparams; k++)
            p.p[k] = mi->params[k].start;
        if (gltf)
            p.p[0] = 0.5;
        double rgb[3], K[3];
        if (brdffit_eval((brdffit_model)m, &p, wi, wo, rgb, NULL) != BRDFFIT_OK) {
            fprintf(stderr, "dropin: brdffit_eval %s failed\n", mi->name);
            return 1;
        }
        bf_geom g = { wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], 0, 0 };
        bf_geom_derive(&g);
        if (gltf)
            bf_gltf(&g, p.p, p.d, p.s, K);
        else
            bf_lobe(m, &g, p.p, lam, K);
        for (int c = 0; c < 3; c++)
            if (!(fabs(K[c] - rgb[c]) <= 1e-12 * fabs(rgb[c]) + 1e-300)) {
                fprintf(stderr, "dropin: %s channel %d: %s %.17g, brdffit_eval %.17g\n",
                        mi->name, c, gltf ? "bf_gltf" : "bf_lobe", K[c], rgb[c]);
                bad = 1;
            }
    }
    if (!bad)
        printf("dropin: ok\n");
    return bad;
}
