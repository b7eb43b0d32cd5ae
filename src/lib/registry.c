/* SPDX-License-Identifier: MIT */
/* registry.c -- the model registry: every fact about every model, one entry
 * each (ids as in include/brdffit.h; the lobe of each id is BF_MODEL_LOBES in
 * kernels/bf_models.h, which the kernel sees too).  Bounds, maps and start
 * grids are plain data: the fit, the pass, the program and the tests read
 * them from here. */
#include "registry.h"

#include "bf_lobe.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#define NO_ROUNDS .round_param = -1, .round_factor = 1.0

/* Bounds are inclusive: brdffit_eval accepts exactly these, and fits stay in them. */

static const brdffit_param_info ward_params[] = {
    { "alpha", "", 1e-4, 1.0, 0.1, BRDFFIT_MAP_LOG, "RMS slope of the surface" },
};

static const brdffit_param_info blinn_phong_params[] = {
    { "n", "", 0.1, 1e6, 100, BRDFFIT_MAP_LOG, "exponent of cos(delta)" },
};

static const brdffit_param_info lafortune_params[] = {
    { "Cxy", "", -100, 100, -0.57735026918962576, BRDFFIT_MAP_DIRECTION,
      "weight of the tangential components" },
    { "Cz", "", -100, 100, 0.57735026918962576, BRDFFIT_MAP_DIRECTION,
      "weight of the normal component" },
    { "n", "", 0.1, 1e6, 100, BRDFFIT_MAP_LOG, "exponent" },
};

static const brdffit_param_info cook_torrance_params[] = {
    { "F0", "", 0, 1, 0.5, BRDFFIT_MAP_LINEAR, "reflectance at normal incidence (Schlick)" },
    { "m", "", 1e-4, 2.0, 0.1, BRDFFIT_MAP_LOG, "RMS slope of the microfacets (Beckmann)" },
};

static const brdffit_param_info ashikhmin_shirley_params[] = {
    { "F0", "", 0, 1, 0.5, BRDFFIT_MAP_LINEAR, "reflectance at normal incidence (Schlick)" },
    { "n", "", 0.1, 1e6, 100, BRDFFIT_MAP_LOG, "exponent of N.H" },
};

static const brdffit_param_info he_params[] = {
    { "tau", "um", 1, 200, 16, BRDFFIT_MAP_LOG, "autocorrelation length of the surface" },
    { "sigma0", "um", 0.001, 30, 0.5, BRDFFIT_MAP_LOG, "RMS roughness of the surface" },
    { "n", "", 1, 30, 2, BRDFFIT_MAP_LOG, "refractive index (real)" },
};

static const brdffit_param_info ggx_params[] = {
    { "F0", "", 0, 1, 0.5, BRDFFIT_MAP_LINEAR,
      "Schlick's F0: the lobe is s F0 at normal incidence, s at grazing" },
    { "alpha", "", 1e-4, 1, 0.1, BRDFFIT_MAP_LOG, "width of the Trowbridge-Reitz distribution (alpha, not glTF's roughness = sqrt(alpha))" },
};

/* The glTF 2.0 material's parameters, in its names (kernels/bf_gltf.h).  The
 * core model holds ior, specular and the specular colour at the extensions'
 * defaults, where the core material has them: its bounds are those values. */
#define GLTF_METALLIC { "metallic", "", 0, 1, 0, BRDFFIT_MAP_LINEAR, \
      "metalness: 0 dielectric, 1 metal (metallicFactor)" }
#define GLTF_ROUGHNESS { "roughness", "", 0, 1, 0.3, BRDFFIT_MAP_LINEAR, \
      "perceptual roughness, alpha = roughness^2 (roughnessFactor)" }

static const brdffit_param_info gltf_params[] = {
    GLTF_METALLIC,
    GLTF_ROUGHNESS,
    { "ior", "", 1.5, 1.5, 1.5, BRDFFIT_MAP_LINEAR, "index of refraction: 1.5 in the core material" },
    { "specular", "", 1, 1, 1, BRDFFIT_MAP_LINEAR, "specular factor: 1 in the core material" },
};

static const brdffit_param_info gltf_ext_params[] = {
    GLTF_METALLIC,
    GLTF_ROUGHNESS,
    { "ior", "", 1, 1000, 1.5, BRDFFIT_MAP_LOG, "index of refraction (KHR_materials_ior)" },
    { "specular", "", 0, 1, 1, BRDFFIT_MAP_LINEAR,
      "strength of the dielectric specular (KHR_materials_specular specularFactor)" },
};

/* OpenPBR Surface's base and specular parameters, in its names
 * (kernels/bf_openpbr.h); the ranges are the specification's, specular_ior's
 * widened past its soft [1, 3] to 10 (F_s 0.67), as far as the albedo
 * table holds its accuracy (docs/openpbr.md).  The fit holds specular_weight at 1
 * (bf_model_def.held): for a dielectric only specular_weight F_s counts,
 * so it and specular_ior trade off exactly (docs/openpbr.md). */
static const brdffit_param_info openpbr_params[] = {
    { "base_metalness", "", 0, 1, 0, BRDFFIT_MAP_LINEAR,
      "fraction of the surface that is metal: 0 dielectric, 1 metal" },
    { "specular_roughness", "", 0, 1, 0.3, BRDFFIT_MAP_LINEAR,
      "roughness of the specular lobe, alpha = roughness^2" },
    { "specular_ior", "", 1, 10, 1.5, BRDFFIT_MAP_LOG,
      "index of refraction of the dielectric base" },
    { "specular_weight", "", 0, 1, 1, BRDFFIT_MAP_LINEAR,
      "multiplier of the dielectric's F0 (through its IOR) and of the metal's Fresnel" },
};

#define DS_COLOURS .colour_form = BRDFFIT_COLOUR_DS, .colour_names = { "d", "s" }, \
    .in_default_set = 1
#define GLTF_COLOURS .colour_form = BRDFFIT_COLOUR_GLTF, \
    .colour_names = { "base_color", "specular_color" }
#define OPENPBR_COLOURS .colour_form = BRDFFIT_COLOUR_OPENPBR, \
    .colour_names = { "base_color", "specular_color" }

#define PARAMS(a) .nparams = (int)(sizeof a / sizeof a[0]), .params = a

/* Every model screens its starts on every 8th sample (He: 12th; see
 * bf_model_def): on all 100 MERL tables that keeps the starts a screening
 * on all samples keeps. */
static const bf_model_def registry[] = {
    [BRDFFIT_WARD] = {
        .info = { BRDFFIT_WARD, "ward", "Ward", PARAMS(ward_params), .chromatic = 0,
                  .default_starts = 8, DS_COLOURS },
        .grid = { .param = 0, .spacing = BRDFFIT_MAP_LOG, .lo = 0.005, .hi = 0.5, NO_ROUNDS },
        .screen_stride = 8,
    },
    [BRDFFIT_WARD_DUER] = {
        .info = { BRDFFIT_WARD_DUER, "ward-duer", "Ward-Duer", PARAMS(ward_params),
                  .chromatic = 0, .default_starts = 8, DS_COLOURS },
        .grid = { .param = 0, .spacing = BRDFFIT_MAP_LOG, .lo = 0.005, .hi = 0.5, NO_ROUNDS },
        .screen_stride = 8,
    },
    [BRDFFIT_BLINN_PHONG] = {
        .info = { BRDFFIT_BLINN_PHONG, "blinn-phong", "Blinn-Phong", PARAMS(blinn_phong_params),
                  .chromatic = 0, .default_starts = 8, DS_COLOURS },
        .grid = { .param = 0, .spacing = BRDFFIT_MAP_LOG, .lo = 2, .hi = 5e4, NO_ROUNDS },
        .screen_stride = 8,
    },
    [BRDFFIT_LAFORTUNE] = {
        .info = { BRDFFIT_LAFORTUNE, "lafortune", "Lafortune", PARAMS(lafortune_params),
                  .chromatic = 0, .default_starts = 8, DS_COLOURS },
        .grid = { .param = 2, .spacing = BRDFFIT_MAP_LOG, .lo = 2, .hi = 5e4, NO_ROUNDS },
        .screen_stride = 8,
    },
    [BRDFFIT_COOK_TORRANCE] = {
        .info = { BRDFFIT_COOK_TORRANCE, "cook-torrance", "Cook-Torrance",
                  PARAMS(cook_torrance_params), .chromatic = 0, .default_starts = 8, DS_COLOURS },
        .grid = { .param = 1, .spacing = BRDFFIT_MAP_LOG, .lo = 0.005, .hi = 0.5, NO_ROUNDS },
        .screen_stride = 8,
    },
    [BRDFFIT_ASHIKHMIN_SHIRLEY] = {
        .info = { BRDFFIT_ASHIKHMIN_SHIRLEY, "ashikhmin-shirley", "Ashikhmin-Shirley",
                  PARAMS(ashikhmin_shirley_params), .chromatic = 0, .default_starts = 8, DS_COLOURS },
        .grid = { .param = 1, .spacing = BRDFFIT_MAP_LOG, .lo = 2, .hi = 5e4, NO_ROUNDS },
        .screen_stride = 8,
    },
    /* He's starts: tau over 4, 8, ..., 28 as Ngan et al. at sigma0 = 0.5,
     * then the same round at sigma0 = 2 and at 0.125 um (further rounds of 7
     * multiply or divide sigma0 by 4 again): the second round reaches rough
     * surfaces, the third the minima at small tau and sigma0 that some
     * materials have (docs/fidelity.md).  A subset pass of He costs more than
     * its share of samples, since its memos work per (theta_h, theta_d) bin;
     * so the starts are screened on the bin subset (every 3rd theta_h and
     * theta_d index, every 12th phi_d: a 108th of the samples), each kept
     * start refined by LM there first, and only the ends within BINS_MARGIN
     * of the lowest go on to the stride-12 subset, then to all samples
     * (fit/refine.c, bins_runs).  An end with sigma0 >= 0.3 um goes on from its
     * start instead: He is at its rough limit there over most directions,
     * so where the bin subset's run ends along that line is no guide to the
     * stride subset's.  Why each number: docs/fitting.md, Starts and
     * Refinement. */
    [BRDFFIT_HE] = {
        .info = { BRDFFIT_HE, "he", "He", PARAMS(he_params), .chromatic = 1,
                  .default_starts = 21, DS_COLOURS },
        .grid = { .param = 0, .spacing = BRDFFIT_MAP_LINEAR, .lo = 4, .hi = 28, .period = 7,
                  .round_param = 1, .round_factor = 4.0 },
        .screen_stride = 12,
        .screen_bins = { 3, 3, 12 },
        .secant = BF_SECANT_ON_ALL,
        .refine_on_subset = 1,
        .refine_on_bins = 1,
        .rough_param = 1,
        .rough_from = 0.3,
    },
    [BRDFFIT_GGX] = {
        .info = { BRDFFIT_GGX, "ggx", "GGX", PARAMS(ggx_params), .chromatic = 0,
                  .default_starts = 8, DS_COLOURS },
        .grid = { .param = 1, .spacing = BRDFFIT_MAP_LOG, .lo = 0.005, .hi = 0.8, NO_ROUNDS },
        .screen_stride = 8,
    },
    /* The glTF models are fitted by the affine engine (fit/affine.c): the
     * base colour solved exactly at every point, LM on the rest.  Its starts:
     * roughness over the grid, metallic near 0 and near 1 in turn. */
    [BRDFFIT_GLTF] = {
        .info = { BRDFFIT_GLTF, "gltf", "glTF 2.0", PARAMS(gltf_params), .chromatic = 0,
                  .default_starts = 8, GLTF_COLOURS },
        .grid = { .param = 1, .spacing = BRDFFIT_MAP_LOG, .lo = 0.1, .hi = 0.8, .period = 4,
                  NO_ROUNDS },
        .screen_stride = 8,
    },
    [BRDFFIT_GLTF_EXT] = {
        .info = { BRDFFIT_GLTF_EXT, "gltf-ext", "glTF 2.0 extended", PARAMS(gltf_ext_params),
                  .chromatic = 0, .default_starts = 8, GLTF_COLOURS },
        .grid = { .param = 1, .spacing = BRDFFIT_MAP_LOG, .lo = 0.1, .hi = 0.8, .period = 4,
                  NO_ROUNDS },
        .screen_stride = 8,
    },
    /* OpenPBR by the affine engine as glTF: base_color solved exactly,
     * base_metalness, specular_roughness and specular_ior by LM, specular_weight
     * held at 1 and the specular colour white (docs/openpbr.md).  Its
     * albedo scaling is not reciprocal: the fit takes every sample, not the
     * mirror set's merged pairs. */
    [BRDFFIT_OPENPBR] = {
        .info = { BRDFFIT_OPENPBR, "openpbr", "OpenPBR Surface",
                  PARAMS(openpbr_params), .chromatic = 0, .default_starts = 8, OPENPBR_COLOURS },
        .grid = { .param = 1, .spacing = BRDFFIT_MAP_LOG, .lo = 0.1, .hi = 0.8, .period = 4,
                  NO_ROUNDS },
        .screen_stride = 8,
        .held = 1 << 3,
        .nonreciprocal = 1,
    },
};

#define NMODELS (int)(sizeof registry / sizeof registry[0])
_Static_assert(NMODELS == BRDFFIT_MODEL_COUNT, "one registry entry per brdffit_model");
/* ... and one lobe per entry, ids 0 .. NMODELS-1 in order */
#define ONE_LOBE(id, name, fd) +1
_Static_assert(0 BF_MODEL_LOBES(ONE_LOBE) == BF_LOBE_MODELS,
               "BF_MODEL_LOBES: one lobe per model of the form d/pi + s K");
#undef ONE_LOBE


int brdffit_model_count(void)
{
    return NMODELS;
}

const bf_model_def *bf_model_def_get(brdffit_model model)
{
    if ((int)model < 0 || (int)model >= NMODELS)
        return NULL;
    return &registry[model];
}

const brdffit_model_info *brdffit_model_get(brdffit_model model)
{
    const bf_model_def *def = bf_model_def_get(model);
    return def ? &def->info : NULL;
}

const brdffit_param_info *brdffit_model_param(brdffit_model model, int index)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi || index < 0 || index >= mi->nparams)
        return NULL;
    return &mi->params[index];
}

brdffit_status brdffit_model_from_name(const char *name, brdffit_model *out, brdffit_error *err)
{
    if (!name || !out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_model_from_name: %s is NULL",
                       !name ? "name" : "out");
    for (int m = 0; m < NMODELS; m++) {
        const char *a = registry[m].info.name, *b = name;
        while (*a && (tolower((unsigned char)*b) == *a || (*a == '-' && *b == '_')))
            a++, b++;
        if (*a == '\0' && *b == '\0') {
            *out = (brdffit_model)m;
            bf_ok(err);
            return BRDFFIT_OK;
        }
    }
    char names[512] = "";
    for (int m = 0; m < NMODELS; m++) {
        size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s%s", m ? ", " : "",
                 registry[m].info.name);
    }
    return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "no model named '%.200s' (models: %s)", name,
                   names);
}

int bf_model_coord_param(brdffit_model model, int j)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi)
        return -1;
    for (int k = 0, c = 0; k < mi->nparams; k++, c++) {
        if (mi->params[k].lower == mi->params[k].upper || (registry[model].held >> k & 1)) {
            c--; /* held at its one value (or its start): not a coordinate */
            continue;
        }
        if (c == j)
            return k;
        if (mi->params[k].map == BRDFFIT_MAP_DIRECTION)
            k++; /* with the next parameter: one angle */
    }
    return -1;
}

int bf_model_has_lobe(brdffit_model model)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    return mi && mi->colour_form == BRDFFIT_COLOUR_DS;
}

int bf_model_ncoords(brdffit_model model)
{
    int n = 0;
    while (bf_model_coord_param(model, n) >= 0)
        n++;
    return n;
}

void bf_model_start_params(brdffit_model model, double *p, int n)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    for (int k = 0; k < n; k++)
        p[k] = mi && k < mi->nparams ? mi->params[k].start : 0.0;
}
