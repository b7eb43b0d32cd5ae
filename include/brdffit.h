/* SPDX-License-Identifier: MIT */
/*
 * brdffit.h -- fit analytic BRDF models to measured (MERL) reflectance data.
 *
 * One public header, plain C11, usable from C++ and through FFI.  Every name
 * is prefixed brdffit_ / BRDFFIT_.  Objects are opaque handles with
 * create/free pairs; every fallible function returns a brdffit_status and
 * takes a brdffit_error * as its last argument (NULL: no message wanted),
 * which it fills with a message naming the fault: the file and byte, the
 * argument, the index, the value.  The library never prints, exits or
 * aborts.
 *
 * CONVENTIONS (a summary: docs/conventions.md is the normative statement;
 * python/tests/test_docs.py checks the figures both state against the code)
 *
 *   Frame.  Local shading frame, z is the surface normal N.  wi points from
 *   the surface TOWARD THE LIGHT, wo TOWARD THE VIEWER, both unit vectors
 *   (brdffit_eval normalises what it is given).  H = normalize(wi + wo),
 *   delta = angle(N, H), theta_i = angle(N, wi), theta_o = angle(N, wo).
 *
 *   BRDF value.  f(wi, wo) in 1/sr, WITHOUT the cosine factor, per channel
 *   c in {R, G, B}:   f_c = d_c / pi + s_c * K_c(wi, wo; p)
 *   d = Lambertian albedo, s = specular coefficient rho_s, p = lobe
 *   parameters shared by the channels.  K is the same for the three channels
 *   except for the He model, whose lobe depends on the wavelength.  A
 *   direction at or below the horizon (z <= 0) gives f = 0; one above it
 *   but closer than cos theta = 1e-6 (5.7e-5 deg) is evaluated at
 *   cos theta = 1e-6, so that every lobe is finite (BF_COS_FLOOR in
 *   kernels/bf_models.h).
 *
 *   Lobes (Ngan, Durand, Matusik 2005, as their published parameters fit):
 *     ward [alpha]           K = exp(-tan^2 d / a^2) / (4 pi a^2 sqrt(cos ti cos to))
 *     ward-duer [alpha]      K = exp(-tan^2 d / a^2) / (4 pi a^2 cos ti cos to)
 *     blinn-phong [n]        K = (n+2)/(2 pi) cos^n d
 *     lafortune [Cxy, Cz, n] K = (n+2)/(2 pi) (max(0, Cxy(lx vx + ly vy) + Cz lz vz)
 *                                               / max(|Cxy|, |Cz|))^n
 *     cook-torrance [F0, m]  K = F(F0, V.H) G exp(-tan^2 d / m^2)
 *                                 / (4 pi m^2 cos^4 d cos ti cos to)
 *                            G = min(1, 2(N.H)(N.V)/(V.H), 2(N.H)(N.L)/(V.H))
 *                            NOTE: the constant 1/(4 pi m^2) is the one the
 *                            published parameters fit; the paper's printed
 *                            formula is 4x larger (only rho_s would change).
 *     ashikhmin-shirley [F0, n]  K = (n+1)/(8 pi) (N.H)^n / ((V.H) max(cos ti, cos to)) F(F0, V.H)
 *     he [tau, sigma0, n]    He et al. 1991 directional-diffuse term (tau, sigma0
 *                            in micrometres, n a real refractive index), per
 *                            channel at wavelengths lambda = (0.645, 0.526,
 *                            0.444) um unless brdffit_params.lambda_um says.
 *     ggx [F0, alpha]        K = D G2 F(F0, V.H) / (4 cos ti cos to), as pbrt-v4:
 *                            D = 1 / (pi a^2 cos^4 th (1 + tan^2 th / a^2)^2)
 *                            (Trowbridge-Reitz), G2 = 1 / (1 + L(wi) + L(wo))
 *                            (height-correlated Smith), L(w) = (sqrt(1 + a^2
 *                            tan^2 theta_w) - 1) / 2
 *     gltf [metallic, roughness, ior = 1.5, specular = 1]  not d/pi + s K:
 *                            the glTF 2.0 metallic-roughness material
 *                            (Appendix B), d = base colour in [0, 1], s =
 *                            specular colour (1, 1, 1); alpha = roughness^2
 *     gltf-ext [metallic, roughness, ior, specular]  the same with
 *                            KHR_materials_ior and KHR_materials_specular
 *                            (s = specularColorFactor): kernels/bf_gltf.h
 *     openpbr [base_metalness, specular_roughness, specular_ior, specular_weight]
 *                            OpenPBR Surface 1.1's base and specular layers
 *                            (d = base_color, s = specular_color, each in
 *                            [0, 1]; alpha = roughness^2): kernels/bf_openpbr.h
 *     F(F0, c) = F0 + (1 - F0)(1 - c)^5 (Schlick).
 *   The Lafortune lobe depends on (Cxy, Cz) only through their direction;
 *   fits report them scaled to 2 Cxy^2 + Cz^2 = 1.
 *
 *   MERL tables.  int32 dims (90, 90, 180), then 3 x 1,458,000 float64, all
 *   R, then G, then B; index k + 180*(j + 90*i) for theta_h bin i, theta_d
 *   bin j, phi_d bin k.  Bin (i, j, k) stands for theta_h = (i/90)^2 pi/2,
 *   theta_d = j/90 pi/2, phi_d = k/180 pi, phi_h = 0.  Negative stored
 *   values mean "not measured / below the horizon" and are masked, never
 *   clamped.  Stored value x channel scale = BRDF value (1/sr):
 *     BRDFFIT_SCALE_STANDARD = (1, 1.15, 1.66) / 1500  (MERL's reader; default)
 *     BRDFFIT_SCALE_FLAT     = 1/1500 for all channels  (the data Ngan et al. fitted)
 *
 *   Error metric "ngan-l2" (the Error of every fit):
 *     E = sqrt( sum_s sum_c w_s ((rho_c(s) - f_c(s)) cos ti(s))^2 / (3 sum_s w_s) )
 *   over the valid samples (all channels >= 0, theta_i and theta_o <= the
 *   cutoff, default 80 deg), w_s = the bin's solid angle
 *   (cos th_lo - cos th_hi)(sin^2 td_hi - sin^2 td_lo)/2.
 *   Two more metrics (brdffit_metric) over the same samples, weights and
 *   channel scale, E = sqrt( sum_s sum_c w_s (g(rho_c) - g(f_c))^2 / (3 sum_s w_s) ):
 *     "log"        g(v) = ln(1 + v cos ti(s))     (Low et al. 2012, E2)
 *     "cube-root"  g(v) = (v + eps)^(1/3), eps = BRDFFIT_CUBE_ROOT_EPS
 *                  = 1e-6 1/sr: finite slope (1/3) eps^(-2/3) at f = 0
 *   ("ngan-l2" is g(v) = v cos ti(s)).  docs/metrics.md.
 *
 *   Renders and incidence-plane curves: the sphere, camera, shading frame,
 *   lights, environment map, coverage and image-error conventions are at
 *   brdffit_render_options below, the curves' directions at
 *   brdffit_curve_options.
 *
 * ABI CONVENTIONS
 *
 *   Sized options.  Every options struct (brdffit_sample_options,
 *   brdffit_context_options, brdffit_fit_options, brdffit_render_options,
 *   brdffit_curve_options) starts with `size_t size`, which its _default()
 *   sets to sizeof the struct as the CALLER was compiled: _default() is
 *   inline (compiled into the caller) and calls the library's
 *   brdffit_*_options_init(opt, sizeof *opt), which writes the defaults of
 *   the members that lie within that size and nothing after it (FFI calls
 *   _init with its mirror's size); members
 *   are only ever appended, and no options struct ends in padding (tested),
 *   so a member appended later never lies inside an older caller's struct.
 *   The library reads the members that lie wholly within `size` and gives
 *   every other member its default: a caller compiled against an older
 *   header (a smaller struct, the same first members) keeps working.  It
 *   refuses, with BRDFFIT_E_OPTIONS_SIZE and a message naming the struct and
 *   the sizes: size 0 (the struct was not set by _default()), a size smaller
 *   than the `size` member itself, one that ends inside a member, and one
 *   larger than this library's struct (a caller built against a newer
 *   header).  Every member has a default, so the smallest struct is `size`
 *   alone.  A NULL options pointer means all the defaults.  A struct the
 *   library fills (brdffit_samples_options) gets the members within its size.
 *   Mirrors (FFI) check their layout with brdffit_struct_size/_offset.
 *
 *   Sized results.  The structs the library fills in the caller's memory and
 *   that may grow (brdffit_fit_result, brdffit_sample) start with `size_t
 *   size` too, which the CALLER sets before the call to sizeof the struct as
 *   it was compiled: brdffit_fit_result_init() / brdffit_sample_init(), which
 *   are inline (compiled into the caller), or size = sizeof the struct.  The
 *   library writes the members that lie wholly within `size` and nothing
 *   after it.  It refuses, with BRDFFIT_E_OPTIONS_SIZE and a message naming
 *   the struct and the sizes, before doing any work: size 0, one smaller
 *   than the struct's first sized layout (brdffit_fit_result: up to `flags`;
 *   brdffit_sample: up to `k`), one that ends inside a member, and one
 *   larger than this library's struct.  brdffit_error (fixed: a status and
 *   BRDFFIT_MESSAGE_MAX characters) and brdffit_params (a member of
 *   brdffit_fit_result) never grow; brdffit_model_info and
 *   brdffit_param_info are the library's own memory, read through pointers.
 *
 *   Versions.  MAJOR changes with every change a program built against the
 *   previous header could misread (a member moved or inserted, a struct that
 *   was not sized given a size): it is the soname's number,
 *   libbrdffit.so.MAJOR.  MINOR changes with additions (functions, members
 *   appended to sized structs, models, statuses), PATCH with fixes alone.
 */
#ifndef BRDFFIT_H
#define BRDFFIT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Every declaration in this header is the ABI of libbrdffit.so, and the
 * only part of it: the library is compiled -fvisibility=hidden. */
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

#define BRDFFIT_VERSION_MAJOR 1
#define BRDFFIT_VERSION_MINOR 0
#define BRDFFIT_VERSION_PATCH 0
const char *brdffit_version(void);

/* Seconds on the monotonic clock that times fits (brdffit_fit_result.seconds):
 * the difference of two calls is wall time. */
double brdffit_seconds(void);

/* Memory.  The library's large arrays (4 MB and up: a table's values, a sample
 * set's fields, weights and bins, its mirror set's and subsets') are not
 * returned to the system when freed (brdffit_table_free, brdffit_samples_free)
 * but kept, process-wide, for the next array of about their size: at most 16
 * arrays and 1 GiB in all.  Reading and fitting one table after another then
 * reuses the last table's memory instead of having the kernel map and zero
 * ~200 MB of fresh pages a MERL table.  brdffit_release_memory returns what is
 * kept to the system and gives its size in bytes; safe to call at any time,
 * from any thread (arrays still in use are not touched).  Builds with
 * AddressSanitizer keep nothing. */
size_t brdffit_release_memory(void);

/* ------------------------------------------------------------------ status */

typedef enum brdffit_status {
    BRDFFIT_OK = 0,
    BRDFFIT_E_INVALID_ARGUMENT = 1, /* NULL pointer, unknown option, bad value   */
    BRDFFIT_E_NO_MEMORY = 2,
    BRDFFIT_E_FILE_OPEN = 3,      /* missing or unreadable file                */
    BRDFFIT_E_FILE_NOT_REGULAR = 4, /* a directory or other non-file             */
    BRDFFIT_E_FILE_READ = 5,      /* an I/O error while reading                */
    BRDFFIT_E_FILE_EMPTY = 6,     /* zero bytes                                */
    BRDFFIT_E_FILE_TRUNCATED = 7, /* fewer bytes than the header promises      */
    BRDFFIT_E_FILE_DIMS = 8,      /* dimensions other than 90 x 90 x 180       */
    BRDFFIT_E_FILE_TRAILING = 9,  /* bytes after the last sample               */
    BRDFFIT_E_FILE_NONFINITE = 10, /* NaN or inf in a table (read, or set in memory) */
    BRDFFIT_E_FILE_WRITE = 11,    /* could not write a file                    */
    BRDFFIT_E_UNKNOWN_MODEL = 12,
    BRDFFIT_E_PARAM_RANGE = 13,   /* parameter NaN, inf or outside its bounds  */
    BRDFFIT_E_NO_SAMPLES = 14,    /* no valid sample to fit                    */
    BRDFFIT_E_NO_DEVICE = 15,     /* no OpenCL platform/device (or none matches) */
    BRDFFIT_E_OPENCL = 16,        /* an OpenCL call failed                     */
    BRDFFIT_E_KERNEL_BUILD = 17,  /* the OpenCL program did not build (log in message) */
    BRDFFIT_E_FIT_FAILED = 18,    /* the optimiser could not produce a result  */
    BRDFFIT_E_CACHE_DIR = 19,    /* PoCL's kernel cache directory is unusable (which, why) */
    BRDFFIT_E_TOO_FEW_SAMPLES = 20, /* fewer distinct sample geometries than the model's unknowns */
    BRDFFIT_E_VALUE_RANGE = 21,  /* a finite value too large: stored, or a render's (named) */
    BRDFFIT_E_OPTIONS_SIZE = 22, /* a sized struct's `size` the library cannot take (ABI CONVENTIONS) */
    BRDFFIT_STATUS_COUNT = 23       /* one more than the last status */
} brdffit_status;

/* A fixed text for each status; never NULL. */
const char *brdffit_strerror(brdffit_status status);

/* Caller-owned failure report: the status a call failed with and why.  Pass
 * NULL where no message is wanted.  (Not to be confused with the Error, the
 * fit metric "ngan-l2": brdffit_fit_result.error, brdffit_error_of.) */
#define BRDFFIT_MESSAGE_MAX 2048
typedef struct brdffit_error {
    brdffit_status status;
    char message[BRDFFIT_MESSAGE_MAX]; /* "path: truncated at byte N (...)" etc. */
} brdffit_error;

/* ------------------------------------------------------------------ models */

/* Model ids.  The values are part of the ABI: they never change, and new
 * models are only appended.  Every fact about a model (name, parameters,
 * bounds, units, how the fit maps them, its default starts) comes from the
 * library's model registry through the functions below; BRDFFIT_MODEL_COUNT
 * is the number this header knows, brdffit_model_count() the library's. */
typedef enum brdffit_model {
    BRDFFIT_WARD = 0,
    BRDFFIT_WARD_DUER = 1,
    BRDFFIT_BLINN_PHONG = 2,
    BRDFFIT_LAFORTUNE = 3,
    BRDFFIT_COOK_TORRANCE = 4,
    BRDFFIT_ASHIKHMIN_SHIRLEY = 5,
    BRDFFIT_HE = 6,
    BRDFFIT_GGX = 7,
    BRDFFIT_GLTF = 8,     /* glTF 2.0 metallic-roughness, core: what every viewer shows */
    BRDFFIT_GLTF_EXT = 9, /* the same with KHR_materials_ior and KHR_materials_specular */
    BRDFFIT_OPENPBR = 10  /* OpenPBR Surface 1.1, base and specular layers */
} brdffit_model;
#define BRDFFIT_MODEL_COUNT 11

#define BRDFFIT_MAX_LOBE_PARAMS 4

/* How a fit moves a lobe parameter inside its bounds [lower, upper]: through
 * an unbounded coordinate u, v = lo + (hi - lo)(1 + sin u)/2, with lo, hi the
 * bounds (LINEAR) or their logarithms and v the logarithm (LOG).  DIRECTION:
 * this parameter and the next one form a direction (a, b) fitted as one angle
 * phi, (a, b) = (cos phi / sqrt 2, sin phi), i.e. scaled to 2 a^2 + b^2 = 1
 * (Lafortune's Cxy counts twice, for x and y). */
typedef enum brdffit_param_map {
    BRDFFIT_MAP_LOG = 0,
    BRDFFIT_MAP_LINEAR = 1,
    BRDFFIT_MAP_DIRECTION = 2
} brdffit_param_map;

/* One lobe parameter of a model. */
typedef struct brdffit_param_info {
    const char *name;            /* "alpha", "F0", "tau", ...                 */
    const char *unit;            /* "um" for He's tau and sigma0; "" for none */
    double lower, upper;         /* inclusive bounds: brdffit_eval rejects
                                    parameters outside them, fits stay inside */
    double start;                /* a typical value (the fit's starts vary
                                    some parameters around it)                */
    brdffit_param_map map;       /* how the fit maps it                       */
    const char *description;     /* a few words: "RMS slope of the microfacets" */
} brdffit_param_info;

typedef struct brdffit_model_info {
    brdffit_model id;
    const char *name;            /* "ward", "ward-duer", ..., "he"            */
    const char *title;           /* "Ward", "Ward-Duer", ...                  */
    int nparams;                 /* lobe parameters, 1..BRDFFIT_MAX_LOBE_PARAMS */
    int chromatic;               /* 1 when K differs per channel: the lobe
                                    depends on the wavelength (He)            */
    int default_starts;          /* starting points a fit screens by default  */
    const brdffit_param_info *params; /* nparams entries                      */
    /* How the colours enter: BRDFFIT_COLOUR_DS, f_c = d_c/pi + s_c K_c (the
     * paper's models, GGX), or BRDFFIT_COLOUR_GLTF, the glTF BRDF, where
     * brdffit_params.d is the base colour (each in [0, 1]) and .s the
     * specular colour (KHR_materials_specular; the core `gltf` takes 1, 1, 1),
     * and p = metallic, roughness, ior, specular (docs/conventions.md);
     * or BRDFFIT_COLOUR_OPENPBR, the OpenPBR Surface BRDF, where d is
     * base_color and s specular_color (each in [0, 1]) and p =
     * base_metalness, specular_roughness, specular_ior, specular_weight
     * (docs/openpbr.md). */
    int colour_form;
    const char *colour_names[2]; /* the names of d and s: "d", "s" or
                                    "base_color", "specular_color"            */
    int in_default_set;          /* 1: the program fits it when no model is
                                    named (the paper's models and GGX); the
                                    glTF models are fitted when named or with
                                    "all" (their fits take longer: no kernel) */
} brdffit_model_info;

enum { BRDFFIT_COLOUR_DS = 0, BRDFFIT_COLOUR_GLTF = 1, BRDFFIT_COLOUR_OPENPBR = 2 };

/* The number of models the library has (ids 0 .. count-1). */
int brdffit_model_count(void);
/* The descriptor of a model, or NULL for an id out of range. */
const brdffit_model_info *brdffit_model_get(brdffit_model model);
/* Lobe parameter `index` (0-based) of a model, or NULL when either is out of range. */
const brdffit_param_info *brdffit_model_param(brdffit_model model, int index);
/* Look a model up by name ("cook-torrance"; any case, '_' accepted for '-'):
 * BRDFFIT_E_UNKNOWN_MODEL, the message listing the models, for any other. */
brdffit_status brdffit_model_from_name(const char *name, brdffit_model *out, brdffit_error *err);

typedef struct brdffit_params {
    double d[3];          /* Lambertian albedo per channel (diffuse = d/pi), >= 0;
                             glTF: the base colour, in [0, 1]                   */
    double s[3];          /* specular coefficient rho_s per channel, >= 0;
                             glTF: the specular colour (colour_names)           */
    double p[BRDFFIT_MAX_LOBE_PARAMS]; /* lobe parameters in the paper's units
                             (glTF: the specification's)                        */
    double lambda_um[3];  /* He only: wavelength per channel in micrometres;
                             0 means the default (0.645, 0.526, 0.444)          */
} brdffit_params;

/* Check params against the model's bounds: BRDFFIT_OK or BRDFFIT_E_PARAM_RANGE. */
brdffit_status brdffit_params_check(brdffit_model model, const brdffit_params *params,
                                    brdffit_error *err);

/* f(wi, wo) per channel (no cosine factor) into rgb[3].  Allocates nothing.
 * Directions need not be normalised but must be finite and non-zero
 * (BRDFFIT_E_INVALID_ARGUMENT naming the direction and its value);
 * parameters as brdffit_params_check. */
brdffit_status brdffit_eval(brdffit_model model, const brdffit_params *params,
                            const double wi[3], const double wo[3], double rgb[3],
                            brdffit_error *err);

/* The same for n pairs: wi, wo are 3n doubles (x, y, z per pair), rgb 3n.
 * Every pair is evaluated; a pair with a non-finite or zero direction gets
 * rgb = 0 and the call then returns BRDFFIT_E_INVALID_ARGUMENT, the message
 * naming the first such pair (its index and the direction's value) and how
 * many there were. */
brdffit_status brdffit_eval_batch(brdffit_model model, const brdffit_params *params,
                                  size_t n, const double *wi, const double *wo,
                                  double *rgb, brdffit_error *err);

/* ------------------------------------------------------------------ MERL tables */

#define BRDFFIT_MERL_NTH 90
#define BRDFFIT_MERL_NTD 90
#define BRDFFIT_MERL_NPD 180
#define BRDFFIT_MERL_BINS (90 * 90 * 180)   /* 1,458,000 per channel */
/* The largest stored value a table may hold.  A finite value above it is no
 * measurement (MERL's largest are ~1e4) and would swamp or overflow every
 * sum of a fit: brdffit_table_read and brdffit_samples_create refuse it with
 * BRDFFIT_E_VALUE_RANGE, naming the bin, the channel and the value. */
#define BRDFFIT_VALUE_MAX 1e20

typedef enum brdffit_scale {
    BRDFFIT_SCALE_STANDARD = 0,  /* (1, 1.15, 1.66) / 1500 */
    BRDFFIT_SCALE_FLAT = 1       /* 1/1500, 1/1500, 1/1500 */
} brdffit_scale;

/* The three channel factors of a scale mode (stored x factor = BRDF). */
brdffit_status brdffit_scale_factors(brdffit_scale scale, double factors[3], brdffit_error *err);
/* "standard" / "flat" ("unknown" for any other value) */
const char *brdffit_scale_name(brdffit_scale scale);
brdffit_status brdffit_scale_from_name(const char *name, brdffit_scale *out, brdffit_error *err);

typedef struct brdffit_table brdffit_table;

/* A new table with every stored value 0. */
brdffit_status brdffit_table_create(brdffit_table **out, brdffit_error *err);
/* Read and validate a MERL .binary file. */
brdffit_status brdffit_table_read(const char *path, brdffit_table **out, brdffit_error *err);
/* Write the table in MERL .binary format. */
brdffit_status brdffit_table_write(const brdffit_table *table, const char *path,
                                   brdffit_error *err);
void brdffit_table_free(brdffit_table *table);

/* The stored values: 3 x BRDFFIT_MERL_BINS doubles, R plane, G plane, B plane,
 * in stored units (multiply by the channel scale for the BRDF). */
double *brdffit_table_values(brdffit_table *table);
const double *brdffit_table_values_const(const brdffit_table *table);

/* Index of bin (i, j, k) within a plane: k + 180*(j + 90*i). */
size_t brdffit_bin_index(int i, int j, int k);
/* The directions a bin stands for (see the conventions above); an index out
 * of range is BRDFFIT_E_INVALID_ARGUMENT naming it. */
brdffit_status brdffit_bin_directions(int i, int j, int k, double wi[3], double wo[3],
                                      brdffit_error *err);
/* The bin's solid-angle weight w (see the conventions above). */
double brdffit_bin_weight(int i, int j);

/* Fill a table from a model: every bin whose directions are both above the
 * horizon gets f(wi, wo) / scale, the others -1 (as MERL stores them). */
brdffit_status brdffit_table_fill_model(brdffit_table *table, brdffit_model model,
                                        const brdffit_params *params, brdffit_scale scale,
                                        brdffit_error *err);

typedef enum brdffit_interp {
    BRDFFIT_INTERP_NEAREST = 0,  /* MERL's BRDFRead bin                          */
    BRDFFIT_INTERP_TRILINEAR = 1 /* trilinear in the (theta_h index, theta_d, phi_d) grid */
} brdffit_interp;

/* Value at (wi, wo) in BRDF units (stored x scale), MERL's BRDFRead mapping:
 * theta_h index = floor(sqrt(theta_h / (pi/2)) * 90), phi_d folded into
 * [0, pi) by reciprocity.  Masked (negative) bins give -1 in that channel;
 * trilinear lookup gives -1 where any contributing bin is masked.  A
 * non-finite or zero direction, or wo = -wi, is BRDFFIT_E_INVALID_ARGUMENT. */
brdffit_status brdffit_table_lookup(const brdffit_table *table, const double wi[3],
                                    const double wo[3], brdffit_scale scale,
                                    brdffit_interp interp, double rgb[3], brdffit_error *err);
/* The values of n (wi, wo) pairs as brdffit_table_lookup gives them, in one
 * call: wi, wo are 3n doubles (x, y, z per pair), rgb 3n.  Every pair is
 * looked up; a pair with a non-finite or zero direction (or wo = -wi) gets
 * rgb = -1 (no value) and the call then returns BRDFFIT_E_INVALID_ARGUMENT,
 * the message naming the first such pair and how many there were. */
brdffit_status brdffit_table_lookup_batch(const brdffit_table *table, size_t n,
                                          const double *wi, const double *wo,
                                          brdffit_scale scale, brdffit_interp interp,
                                          double *rgb, brdffit_error *err);

/* ------------------------------------------------------------------ sample sets */

typedef struct brdffit_sample_options {
    size_t size;           /* sizeof(brdffit_sample_options), set by _default() */
    brdffit_scale scale;   /* default BRDFFIT_SCALE_STANDARD              */
    double cutoff_deg;     /* theta_i, theta_o <= cutoff; default 80      */
} brdffit_sample_options;

void brdffit_sample_options_init(brdffit_sample_options *opt, size_t size);
static inline void brdffit_sample_options_default(brdffit_sample_options *opt)
{
    brdffit_sample_options_init(opt, sizeof *opt);
}

typedef struct brdffit_samples brdffit_samples;

typedef struct brdffit_sample {
    size_t size;           /* sizeof(brdffit_sample), set by the caller:
                              brdffit_sample_init (ABI CONVENTIONS)        */
    double wi[3], wo[3];   /* unit directions (wi toward the light)        */
    double rgb[3];         /* measured BRDF value (stored x scale)         */
    double weight;         /* the bin's solid-angle weight w               */
    int i, j, k;           /* the bin                                      */
} brdffit_sample;

/* Every member 0 and size = sizeof *sample as the caller is compiled. */
static inline void brdffit_sample_init(brdffit_sample *sample)
{
    for (size_t b = 0; b < sizeof *sample; b++)
        ((unsigned char *)sample)[b] = 0;
    sample->size = sizeof *sample;
}

/* The valid samples of a table: all channels >= 0, both directions above the
 * horizon and within the cutoff.  opt may be NULL for the defaults. */
brdffit_status brdffit_samples_create(const brdffit_table *table,
                                      const brdffit_sample_options *opt,
                                      brdffit_samples **out, brdffit_error *err);
void brdffit_samples_free(brdffit_samples *samples);
size_t brdffit_samples_count(const brdffit_samples *samples);
/* Bins with a negative stored value in some channel (masked, not clamped). */
size_t brdffit_samples_masked(const brdffit_samples *samples);
/* Bins with valid values whose directions fall outside the cutoff. */
size_t brdffit_samples_beyond_cutoff(const brdffit_samples *samples);
/* Sample `index` (0 .. count-1; beyond: BRDFFIT_E_INVALID_ARGUMENT) into
 * out, whose size the caller set (brdffit_sample_init). */
brdffit_status brdffit_samples_get(const brdffit_samples *samples, size_t index,
                                   brdffit_sample *out, brdffit_error *err);
/* The options the set was made with (samples NULL: the defaults), into out:
 * out->size as set by brdffit_sample_options_default (the members within it
 * are written). */
brdffit_status brdffit_samples_options(const brdffit_samples *samples,
                                       brdffit_sample_options *out, brdffit_error *err);
/* Make now what fits of `model` derive from the set and share: the mirror
 * set its passes on all samples read (each pair of samples at phi_d and
 * pi - phi_d, which every model gives one value, merged into one:
 * docs/fitting.md), the subsets its starts are screened on (every 8th
 * sample, He: every 12th and a bin subset) and, for He, the bin tables of
 * the mirror set and of those subsets.  A set keeps them until it is freed,
 * and every fit of it (any context, any thread) uses the same ones, so that
 * a fit need not read the whole set to make them (~8 ms each for a MERL
 * table: docs/performance.md).  Optional: without it the
 * first fit that needs one makes it, and that fit's `seconds` include it.
 * Memory: ~0.8 of the set's own for all the models
 * (docs/fitting.md).  Safe while other threads fit the set.
 * BRDFFIT_E_INVALID_ARGUMENT (NULL samples), BRDFFIT_E_UNKNOWN_MODEL,
 * BRDFFIT_E_NO_MEMORY (nothing is kept then). */
brdffit_status brdffit_samples_prepare(const brdffit_samples *samples, brdffit_model model,
                                       brdffit_error *err);

/* ------------------------------------------------------------------ fitting */

typedef enum brdffit_backend {
    BRDFFIT_BACKEND_AUTO = 0,   /* OpenCL when a device is found, else host C */
    BRDFFIT_BACKEND_OPENCL = 1, /* OpenCL or fail with BRDFFIT_E_NO_DEVICE    */
    BRDFFIT_BACKEND_HOST = 2    /* the same model maths compiled as C, 1 thread */
} brdffit_backend;

typedef struct brdffit_context_options {
    size_t size;                /* sizeof(brdffit_context_options), set by _default() */
    brdffit_backend backend;    /* default AUTO                                 */
    const char *device;         /* "PLATFORM:DEVICE" by index or name substring;
                                   NULL: $BRDFFIT_DEVICE, else the first PoCL CPU
                                   device, else the first device                */
} brdffit_context_options;

void brdffit_context_options_init(brdffit_context_options *opt, size_t size);
static inline void brdffit_context_options_default(brdffit_context_options *opt)
{
    brdffit_context_options_init(opt, sizeof *opt);
}

/* A context is used by one thread at a time (its kernels' arguments are set
 * per pass); use one context per thread to fit in parallel: contexts may be
 * created, used and freed from several threads at once (the library makes
 * every OpenCL set-up and tear-down call under one lock).  Tables, sample
 * sets and the evaluators are read-only once made and may be shared (a
 * sample set adds the subsets its fits share under a lock of its own:
 * brdffit_samples_prepare). */
typedef struct brdffit_context brdffit_context;

/* Create a context: picks the device, owns the OpenCL state and the per-model
 * program cache.
 * PoCL's kernel cache directory (PoCL loads the kernels it finds there as
 * shared objects) is settled once per process, by the first context that may
 * use OpenCL, before the library's first OpenCL call:
 *   POCL_CACHE_DIR set: it must be a directory a file can be made in (made
 *     when missing);
 *   unset: the first PRIVATE one of $XDG_CACHE_HOME/brdffit/pocl,
 *     ~/.cache/brdffit/pocl, ${TMPDIR:-/tmp}/brdffit-pocl-UID -- made with
 *     mode 0700, or existing, owned by the user, not a symbolic link, not
 *     group- or world-writable, in directories only root or the user can
 *     replace it in -- and POCL_CACHE_DIR is set to it (the library's only
 *     setenv; a program whose other threads read the environment makes its
 *     first context before starting them, or sets POCL_CACHE_DIR itself).
 * Without a usable one: BRDFFIT_E_CACHE_DIR (each directory and why) under
 * BRDFFIT_BACKEND_OPENCL, the host path under AUTO (brdffit_context_fallback
 * says why); OpenCL is then not touched.  A device spec that matches nothing
 * ("P:D" indices out of range included; never wrapped) is
 * BRDFFIT_E_NO_DEVICE under OPENCL, the host path under AUTO. */
brdffit_status brdffit_context_create(const brdffit_context_options *opt,
                                      brdffit_context **out, brdffit_error *err);
void brdffit_context_free(brdffit_context *ctx);
/* The path the context uses: BRDFFIT_BACKEND_OPENCL or BRDFFIT_BACKEND_HOST
 * (never AUTO; HOST for a NULL context). */
brdffit_backend brdffit_context_backend(const brdffit_context *ctx);
/* A human description: "opencl: Portable Computing Language / pthread-haswell..."
 * or "host: C (no OpenCL device: ...)". */
const char *brdffit_context_describe(const brdffit_context *ctx);
/* Why a context asked for AUTO fits on the host path: the status and message
 * of the OpenCL set-up that failed (BRDFFIT_E_CACHE_DIR, BRDFFIT_E_NO_DEVICE
 * with the device asked for, ...), for the caller to show.  BRDFFIT_OK and an
 * empty message when the context uses OpenCL or HOST was asked. */
brdffit_status brdffit_context_fallback(const brdffit_context *ctx, brdffit_error *why);

/* Build the OpenCL kernels of a model now, so that no fit pays for it
 * (without this the first fit of each model in a context builds them, and
 * its `seconds` include the build: see brdffit_fit_result.seconds_build).
 * BRDFFIT_OK and nothing to do on the host backend; BRDFFIT_E_KERNEL_BUILD
 * with the build log in err.  Once per model and context; later calls are free. */
brdffit_status brdffit_context_prepare(brdffit_context *ctx, brdffit_model model,
                                       brdffit_error *err);
/* The wall time in seconds that building a model's kernels took in this
 * context (0 when they are not built, and on the host backend). */
double brdffit_context_build_seconds(const brdffit_context *ctx, brdffit_model model);

/* The Error metrics (see "Error metric" at the top; docs/metrics.md).  A fit
 * minimises the one its options name and reports its Error under each. */
typedef enum brdffit_metric {
    BRDFFIT_METRIC_NGAN_L2 = 0,   /* "ngan-l2": the paper's; the default     */
    BRDFFIT_METRIC_LOG = 1,       /* "log": ln(1 + f cos ti)                */
    BRDFFIT_METRIC_CUBE_ROOT = 2  /* "cube-root": (f + eps)^(1/3)            */
} brdffit_metric;
#define BRDFFIT_METRIC_COUNT 3
#define BRDFFIT_CUBE_ROOT_EPS 1e-6

typedef struct brdffit_fit_options {
    size_t size;         /* sizeof(brdffit_fit_options), set by _default()  */
    int starts;          /* starting points screened; 0 (default): the model's
                            default_starts (brdffit_model_info)             */
    int refine;          /* best starts refined by LM; default 1             */
    double ftol, xtol, gtol; /* cminpack tolerances; default 1e-8, 1e-8, 0    */
    int max_evals;       /* data passes per LM run; default 200              */
    double lambda_um[3]; /* He only: wavelengths; 0 = (0.645, 0.526, 0.444)  */
    int metric;          /* the brdffit_metric the fit minimises; default
                            BRDFFIT_METRIC_NGAN_L2 (docs/metrics.md)        */
    int all_errors;      /* 1: an "ngan-l2" fit also gives its Error under
                            every other metric (result errors[]; one more
                            host pass over the samples); default 0: NaN
                            there.  A fit under "log" or "cube-root" gives
                            all three whatever this is (docs/metrics.md)    */
} brdffit_fit_options;

void brdffit_fit_options_init(brdffit_fit_options *opt, size_t size);
static inline void brdffit_fit_options_default(brdffit_fit_options *opt)
{
    brdffit_fit_options_init(opt, sizeof *opt);
}

/* What a fit found.  `error` is the fit's Error, the metric it minimised
 * (`metric`; "ngan-l2" by default) of params, as brdffit_error_metric gives
 * it (brdffit_error_of for "ngan-l2"); `errors` holds params' Error under
 * every metric (NaN under "log" and "cube-root" for an "ngan-l2" fit
 * without brdffit_fit_options.all_errors).  A measure of the fit, not a failure; failures are the
 * brdffit_status a call returns, with its message in a brdffit_error. */
typedef struct brdffit_fit_result {
    size_t size;             /* sizeof(brdffit_fit_result), set by the caller:
                                brdffit_fit_result_init (ABI CONVENTIONS)   */
    brdffit_model model;
    brdffit_params params;   /* in the paper's units                        */
    double error;            /* the Error of params under `metric`          */
    int cminpack_info;       /* lmder's info of the run kept (1..4 converged) */
    int iterations;          /* Jacobian evaluations (njev) of the LM runs that
                                led to params, those on the screening's subset
                                (He) included                               */
    int passes;              /* all data passes of the fit (starts + LM), those
                                on the screening's subset included           */
    double seconds;          /* wall time of brdffit_fit: checks, the kernel
                                build if the fit made it (seconds_build),
                                the set's mirror set and screening subsets if
                                the fit made them (brdffit_samples_prepare),
                                screening the starts, the LM runs           */
    double seconds_solver;   /* of which inside cminpack (not the passes)   */
    double seconds_passes;   /* of which in data passes                     */
    size_t samples;          /* samples fitted                              */
    brdffit_backend backend; /* the path used                               */
    unsigned at_bound;       /* parameters that ended on a bound: bits of
                                brdffit_at_bound (lobe parameter k at its lower
                                or upper bound, d_c = 0, s_c = 0)           */
    unsigned flags;          /* bits of brdffit_fit_flag                    */
    double seconds_build;    /* of `seconds`: building the model's OpenCL
                                kernels, 0 when the context had them
                                (brdffit_context_prepare, an earlier fit)   */
    double errors[BRDFFIT_METRIC_COUNT]; /* the Error of params under each
                                brdffit_metric (errors[metric] == error);
                                NaN where not computed (all_errors)         */
    int metric;              /* the brdffit_metric the fit minimised        */
    int metric_iterations;   /* LM iterations after the "ngan-l2" fit (0
                                for an "ngan-l2" fit; docs/metrics.md)      */
} brdffit_fit_result;

/* Every member 0 and size = sizeof *result as the caller is compiled. */
static inline void brdffit_fit_result_init(brdffit_fit_result *result)
{
    for (size_t b = 0; b < sizeof *result; b++)
        ((unsigned char *)result)[b] = 0;
    result->size = sizeof *result;
}

/* Bits of brdffit_fit_result.at_bound.  A lobe parameter is on its bound when
 * it lies within 1e-6 of its range (in the fit's coordinate) of lower or
 * upper: the data may want it beyond, so the fit is not that of the model. */
typedef enum brdffit_at_bound {
    BRDFFIT_AT_BOUND_P0 = 1u << 0,  /* lobe parameter k: BRDFFIT_AT_BOUND_P0 << k */
    BRDFFIT_AT_BOUND_P1 = 1u << 1,
    BRDFFIT_AT_BOUND_P2 = 1u << 2,
    BRDFFIT_AT_BOUND_P3 = 1u << 3,
    BRDFFIT_AT_BOUND_LOBE = 15u,    /* any lobe parameter                       */
    BRDFFIT_AT_BOUND_D_R = 1u << 8, /* d_c = 0 (glTF: base colour 0 or 1):
                                       BRDFFIT_AT_BOUND_D_R << c               */
    BRDFFIT_AT_BOUND_D_G = 1u << 9,
    BRDFFIT_AT_BOUND_D_B = 1u << 10,
    BRDFFIT_AT_BOUND_S_R = 1u << 12, /* s_c = 0: BRDFFIT_AT_BOUND_S_R << c      */
    BRDFFIT_AT_BOUND_S_G = 1u << 13,
    BRDFFIT_AT_BOUND_S_B = 1u << 14
} brdffit_at_bound;

/* Bits of brdffit_fit_result.flags. */
typedef enum brdffit_fit_flag {
    BRDFFIT_FIT_LIMIT = 1u << 0     /* the LM run kept stopped on max_evals (cminpack
                                       info 5) after its restarts: not converged */
} brdffit_fit_flag;

/* Fit a model to a sample set.  opt may be NULL for the defaults.  The
 * starts are screened on every 8th sample of a large set (He: 12th), and
 * He's kept starts are refined there first; the result (params, error) is always that
 * of all samples (docs/fitting.md).  A sample
 * set with fewer distinct geometries than the model's unknowns per channel
 * (d, s and the lobe parameters; directions differing only by a turn about
 * the normal or by exchanging wi and wo count once) is refused with
 * BRDFFIT_E_TOO_FEW_SAMPLES.  result->size is set by the caller
 * (brdffit_fit_result_init); result is written only when the fit succeeds. */
brdffit_status brdffit_fit(brdffit_context *ctx, const brdffit_samples *samples,
                           brdffit_model model, const brdffit_fit_options *opt,
                           brdffit_fit_result *result, brdffit_error *err);

/* The "ngan-l2" Error (the metric, into *error) of given parameters on a
 * sample set; a failure is the returned status, explained in err.
 *
 * Fits and Errors come from data passes (OpenCL kernel or host loop) over
 * the sample set's mirror set: each pair of samples at phi_d and pi - phi_d,
 * which every model gives one value, merged into one sample, with the same
 * sums up to rounding (docs/fitting.md).  For He a pass takes a
 * flat sample's K from its (theta_h, theta_d) bin's row and the others'
 * series from their bin's table; its K then agrees with brdffit_eval's to
 * ~1e-12 relative (tested), not bit for bit, and a flat sample's K below
 * e^-28 of K at normal incidence counts as 0 (BF_HE_ROW_FLOOR in
 * kernels/bf_he_rows.h; docs/conventions.md, He). */
brdffit_status brdffit_error_of(brdffit_context *ctx, const brdffit_samples *samples,
                                brdffit_model model, const brdffit_params *params,
                                double *error, brdffit_error *err);

/* The Error of given parameters under a metric (brdffit_metric), into
 * *error.  "ngan-l2" is brdffit_error_of's; "log" and "cube-root" are
 * summed on the host over the set's samples (each pair of mirror samples,
 * one model value, summed as two), split over the online CPUs.  An
 * unknown metric is BRDFFIT_E_INVALID_ARGUMENT. */
brdffit_status brdffit_error_metric(brdffit_context *ctx, const brdffit_samples *samples,
                                    brdffit_model model, const brdffit_params *params,
                                    brdffit_metric metric, double *error, brdffit_error *err);

/* "ngan-l2" (the default metric's name) */
const char *brdffit_metric_name(void);
/* A metric's name ("ngan-l2", "log", "cube-root"), NULL for an unknown one. */
const char *brdffit_metric_get_name(brdffit_metric metric);
/* A metric by name (any case, '_' for '-'): BRDFFIT_E_INVALID_ARGUMENT, the
 * message listing the metrics, for any other. */
brdffit_status brdffit_metric_from_name(const char *name, brdffit_metric *out,
                                        brdffit_error *err);

/* ------------------------------------------------------------------ ABI introspection */

/* For callers that mirror the public structs through FFI (the Python package
 * in python/ does): the size and the member offsets of each struct as this
 * library was compiled, so that a mirror written for another layout is
 * refused instead of read as garbage.  Kinds are only appended.  A member
 * added to a public struct is added to the list in src/lib/abi.c too. */
typedef enum brdffit_struct_kind {
    BRDFFIT_STRUCT_ERROR = 0,           /* brdffit_error          */
    BRDFFIT_STRUCT_MODEL_INFO = 1,      /* brdffit_model_info     */
    BRDFFIT_STRUCT_PARAMS = 2,          /* brdffit_params         */
    BRDFFIT_STRUCT_SAMPLE_OPTIONS = 3,  /* brdffit_sample_options */
    BRDFFIT_STRUCT_SAMPLE = 4,          /* brdffit_sample         */
    BRDFFIT_STRUCT_CONTEXT_OPTIONS = 5, /* brdffit_context_options */
    BRDFFIT_STRUCT_FIT_OPTIONS = 6,     /* brdffit_fit_options    */
    BRDFFIT_STRUCT_FIT_RESULT = 7,      /* brdffit_fit_result     */
    BRDFFIT_STRUCT_PARAM_INFO = 8,      /* brdffit_param_info     */
    BRDFFIT_STRUCT_LIGHT = 9,           /* brdffit_light          */
    BRDFFIT_STRUCT_RENDER_OPTIONS = 10, /* brdffit_render_options */
    BRDFFIT_STRUCT_CURVE_OPTIONS = 11   /* brdffit_curve_options  */
} brdffit_struct_kind;

/* sizeof the struct of that kind, or 0 for a kind this library does not know. */
size_t brdffit_struct_size(brdffit_struct_kind kind);
/* offsetof the named member ("params", "message", "d", ...; an array member by
 * its name), or (size_t)-1 when the struct has no such member or the kind is
 * unknown. */
size_t brdffit_struct_offset(brdffit_struct_kind kind, const char *member);

/* ------------------------------------------------------------------ renders
 *
 * Render conventions (docs/conventions.md, Renders, states them for users):
 *   Scene.  A unit sphere at the origin seen by an orthographic camera looking
 *   down -z: camera frame x right, y up, z toward the viewer, so the view
 *   direction wo = (0, 0, 1) at every pixel.  The sphere fills the N x N image
 *   exactly: pixel (col, row), row 0 at the TOP, has centre
 *   x = 2 (col + 0.5) / N - 1, y = 1 - 2 (row + 0.5) / N and lies on the sphere
 *   when x^2 + y^2 < 1; its normal n = (x, y, sqrt(1 - x^2 - y^2)).
 *   Shading frame of a pixel: z = n, x = t = normalize((0, 1, 0) x n) =
 *   (n_z, 0, -n_x)/|.|, y = n x t; wi and wo are expressed in it before the
 *   BRDF is evaluated (every model and the table are isotropic, so t only
 *   fixes the frame).
 *   Radiance.  L_c = sum_lights f_c(wi, wo) E_c max(0, n.l)
 *                  + integral over the hemisphere of f_c(wi, wo) L_env,c(wi) cos(theta_i) dwi,
 *   in the units of E (or of L_env) per steradian, linear, no tone mapping.
 *   Lights are directional: dir points FROM the surface TOWARD the light, in
 *   the camera frame.  Default lights (brdffit_render_default_lights): a key
 *   light from the upper left front, dir (-1, 1, 1.5), E = (1, 1, 1), and a
 *   grazing rim light from the right behind the sphere, dir (1, 0.25, -0.6),
 *   E = (0.5, 0.5, 0.5): the key shows the highlight, the rim lights a
 *   crescent at the right edge where theta_o > ~60 deg and theta_d is large
 *   (Fresnel, shadowing and the 1/cos terms, where models differ).
 *   Environment.  A latitude-longitude map of RGB radiance, env_width x
 *   env_height texels, row 0 at the top: texel centre (i + 0.5, j + 0.5) is
 *   direction (sin th sin ph, cos th, -sin th cos ph), th = pi (j + 0.5) / H
 *   from +y (up), ph = 2 pi ((i + 0.5) / W - 0.5), so the map's centre is the
 *   direction -z (behind the sphere as the camera sees it) and +x is at
 *   three quarters of the width.  Bilinear between texel centres (wrapping
 *   in longitude, clamped in latitude).  The integral is a fixed quadrature:
 *   env_samples cosine-distributed directions per pixel from a Hammersley
 *   set, shifted per pixel by a fixed hash of the pixel's index (Cranley-
 *   Patterson rotation): estimate = pi / S sum_s f(wi_s, wo) L_env(wi_s).  No
 *   random state: the same inputs give the same bytes, with any number of
 *   threads.  A constant environment of radiance 1 gives a Lambertian
 *   surface exactly d (up to rounding).  Sharp lobes under a small bright
 *   source are noisy at low sample counts (BRDF-unaware sampling).
 *   Output.  RGBA float, row-major, stride floats from one row to the next
 *   (0: 4 N).  A is the coverage: 0 off the sphere (RGB 0), 1 on the sphere,
 *   BRDFFIT_COVERAGE_MASKED (0.5) on the sphere where the table lookup of some
 *   light or environment sample hit a masked bin (brdffit_table_lookup's -1
 *   in some channel): the masked channels of that contribution count 0, so RGB
 *   there is a lower bound.  Model renders have no masked pixels.
 *   Limits.  A render refuses, never clamps, what it cannot represent, with
 *   BRDFFIT_E_VALUE_RANGE and a message naming it: a light irradiance or an
 *   environment texel above BRDFFIT_RADIANCE_MAX (1e20; with a table, whose
 *   values are at most BRDFFIT_VALUE_MAX, no pixel can then overflow), and a
 *   pixel whose value is not finite (a model whose d or s makes the BRDF
 *   infinite) or beyond the largest float (FLT_MAX): the first such pixel in
 *   row order is named and rgba is set to 0.  No accepted render has an inf
 *   or NaN pixel.
 *   Image error (brdffit_image_error): over the pixels whose reference A is
 *   1, sqrt(sum_pixels sum_c (img - ref)^2 / sum_pixels sum_c ref^2), i.e.
 *   the RMS difference relative to the reference's RMS.
 */

typedef struct brdffit_light {
    double dir[3];   /* toward the light, camera frame; finite, non-zero (normalised) */
    double rgb[3];   /* irradiance E per channel, in 0..BRDFFIT_RADIANCE_MAX          */
} brdffit_light;

#define BRDFFIT_RENDER_MAX_LIGHTS 16
#define BRDFFIT_RADIANCE_MAX 1e20 /* the largest light irradiance or environment texel */
#define BRDFFIT_RENDER_DEFAULT_LIGHTS (-1) /* nlights: use the two default lights */
#define BRDFFIT_COVERAGE_MASKED 0.5f

/* The default key and rim lights (above) into out[0], out[1]; returns 2. */
int brdffit_render_default_lights(brdffit_light out[2]);

typedef struct brdffit_render_options {
    size_t size;            /* sizeof(brdffit_render_options), set by _default()        */
    int width;              /* N: the image is N x N; default 256, in 1..16384          */
    int nlights;            /* BRDFFIT_RENDER_DEFAULT_LIGHTS (default), or 0..16: lights[] */
    brdffit_light lights[BRDFFIT_RENDER_MAX_LIGHTS];
    const float *env;       /* lat-long RGB radiance (0..BRDFFIT_RADIANCE_MAX), or NULL (default) */
    int env_width, env_height; /* texels, >= 1 each when env is set                     */
    size_t env_stride;      /* floats from one env row to the next; 0: 3 env_width      */
    int env_samples;        /* quadrature directions per pixel; default 256, 1..65536   */
    brdffit_interp interp;  /* table lookup; default BRDFFIT_INTERP_TRILINEAR            */
    brdffit_scale scale;    /* table channel scale; default BRDFFIT_SCALE_STANDARD       */
    int threads;            /* worker threads; 0 (default): the online CPUs, at most 16 */
} brdffit_render_options;

void brdffit_render_options_init(brdffit_render_options *opt, size_t size);
static inline void brdffit_render_options_default(brdffit_render_options *opt)
{
    brdffit_render_options_init(opt, sizeof *opt);
}

/* Render the measured table (brdffit_table_lookup) / a model (the evaluators
 * at params) into rgba (see the conventions).  opt NULL: the defaults.
 * Thread-safe: nothing but rgba is written. */
brdffit_status brdffit_render_table(const brdffit_table *table, const brdffit_render_options *opt,
                                    float *rgba, size_t stride, brdffit_error *err);
brdffit_status brdffit_render_model(brdffit_model model, const brdffit_params *params,
                                    const brdffit_render_options *opt, float *rgba,
                                    size_t stride, brdffit_error *err);

/* The image error of img against ref (both RGBA as rendered, width x height,
 * the same stride, 0: 4 width) over the pixels whose ref A is 1; covered
 * (may be NULL) gets their number.  BRDFFIT_E_NO_SAMPLES when no pixel is
 * covered or the reference is black on all of them (the error is undefined);
 * BRDFFIT_E_INVALID_ARGUMENT for a non-finite value on a covered pixel. */
brdffit_status brdffit_image_error(const float *ref, const float *img, int width, int height,
                                   size_t stride, double *error, size_t *covered,
                                   brdffit_error *err);

/* LDR FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating
 * Images", HPG 2020), the perceptual difference of test from ref as NVIDIA's
 * reference implementation (github.com/NVlabs/flip) defines it: both images
 * sRGB-encoded RGB in [0, 1] (clamped), 3 floats a pixel, width x height,
 * the same stride (floats from one row to the next; 0: 3 width); viewed at
 * ppd pixels per degree (0: BRDFFIT_FLIP_PPD, a 0.7 m wide 3840-pixel display
 * at 0.7 m; else 1..1000).  map (may be NULL; width x height floats, row-major)
 * gets the per-pixel FLIP in [0, 1] (0: no visible difference); mean the mean
 * over all pixels, what NVIDIA's tool and the flip-evaluator package report.
 * BRDFFIT_E_INVALID_ARGUMENT
 * for a non-finite value (the pixel is named) or bad sizes; BRDFFIT_E_NO_MEMORY. */
#define BRDFFIT_FLIP_PPD 67.0206432
brdffit_status brdffit_flip(const float *ref, const float *test, int width, int height,
                            size_t stride, double ppd, float *map, double *mean,
                            brdffit_error *err);

/* The same against one reference many times: brdffit_flip_ref_create does
 * the reference's half of the work once (its arguments as brdffit_flip's;
 * *out NULL on failure); brdffit_flip_compare then takes a test image of the
 * reference's size (stride 0: 3 width), and may be called from several
 * threads at once; brdffit_flip_ref_free (NULL: nothing) releases it. */
typedef struct brdffit_flip_ref brdffit_flip_ref;
brdffit_status brdffit_flip_ref_create(const float *ref, int width, int height, size_t stride,
                                       double ppd, brdffit_flip_ref **out, brdffit_error *err);
brdffit_status brdffit_flip_compare(const brdffit_flip_ref *ref, const float *test, size_t stride,
                                    float *map, double *mean, brdffit_error *err);
void brdffit_flip_ref_free(brdffit_flip_ref *ref);

/* ------------------------------------------------------------------ incidence-plane curves
 *
 * For each incidence angle theta_i (degrees), wi = (-sin ti, 0, cos ti) in
 * the x-z plane of the local frame and wo = (sin to, 0, cos to) swept over
 * theta_o = -90 + 180 (k + 0.5) / npoints degrees, k = 0..npoints-1 (cell
 * centres: no sample on the horizon); theta_o > 0 is the mirror side
 * (theta_o = theta_i is the mirror direction).  Values are f per channel in
 * 1/sr (no cosine factor, no cube root: plots apply it).  A measured value
 * whose lookup hits a masked bin is -1 in that channel (as the lookup).
 * Output rgb: ntheta_i rows of npoints x 3 doubles, row a at rgb + a stride
 * (stride in doubles, 0: 3 npoints).
 */

#define BRDFFIT_CURVE_MAX_THETA_I 16

typedef struct brdffit_curve_options {
    size_t size;            /* sizeof(brdffit_curve_options), set by _default()   */
    int ntheta_i;           /* 1..16; default 4                                     */
    int npoints;            /* theta_o samples, 2..100000; default 180 (1 deg apart) */
    double theta_i_deg[BRDFFIT_CURVE_MAX_THETA_I]; /* each in [0, 90); default 20, 40, 60, 75 */
    brdffit_interp interp;  /* table lookup; default BRDFFIT_INTERP_TRILINEAR      */
    brdffit_scale scale;    /* table channel scale; default BRDFFIT_SCALE_STANDARD */
} brdffit_curve_options;

void brdffit_curve_options_init(brdffit_curve_options *opt, size_t size);
static inline void brdffit_curve_options_default(brdffit_curve_options *opt)
{
    brdffit_curve_options_init(opt, sizeof *opt);
}

/* The theta_o of the npoints samples, in degrees, into theta_o_deg. */
brdffit_status brdffit_curve_theta_o(const brdffit_curve_options *opt, double *theta_o_deg,
                                     brdffit_error *err);
/* The measured curves (brdffit_table_lookup) / a model's (brdffit_eval). */
brdffit_status brdffit_curve_table(const brdffit_table *table, const brdffit_curve_options *opt,
                                   double *rgb, size_t stride, brdffit_error *err);
brdffit_status brdffit_curve_model(brdffit_model model, const brdffit_params *params,
                                   const brdffit_curve_options *opt, double *rgb, size_t stride,
                                   brdffit_error *err);
/* ------------------------------------------------------------------ directional albedo
 *
 * a_c(theta_o) = integral over the hemisphere of f_c(wi, wo) cos theta_i d wi,
 * wo = (sin theta_o, 0, cos theta_o): the share of light from wo (or, by
 * reciprocity, toward it) that the surface reflects, per channel.  A
 * Lambertian term d gives d exactly; an energy-conserving BRDF gives at most
 * 1.  theta_o_deg: n angles in [0, 90) degrees; rgb: 3n doubles (R, G, B
 * per angle).  The sums are in double; no accepted input gives NaN or inf.
 *
 * Models (brdffit_albedo_model): d_c + s_c times the lobe's integral (the
 * d/pi term exactly), or f's integral for the glTF models.  The quadrature
 * is Gauss-Legendre over the half vector (theta_h graded geometrically down
 * to the lobe's width: alpha, m, sqrt(2 / (n + 2)) of a cos^n lobe, ...;
 * Lafortune about its lobe's axis), only where wi is above the horizon:
 * within 1e-4 of the integral (relative to max(1, a)) over the registry's
 * bounds for theta_o in 0..85 deg (docs/library.md states what is tested).
 * Parameters as brdffit_params_check; a d or s so large that the albedo
 * overflows is BRDFFIT_E_VALUE_RANGE.
 *
 * Tables (brdffit_albedo_table): the same integral of the table's lookups
 * (brdffit_table_lookup at scale and interp), with the theta_h intervals its
 * bins'.  A channel whose lookup is masked (-1) counts 0 there, as in the
 * renders, so the albedo is then a lower bound; masked (may be NULL) gets,
 * per angle, the share of the cosine-weighted hemisphere where some channel
 * was masked (0..1). */
brdffit_status brdffit_albedo_model(brdffit_model model, const brdffit_params *params, size_t n,
                                    const double *theta_o_deg, double *rgb, brdffit_error *err);
brdffit_status brdffit_albedo_table(const brdffit_table *table, brdffit_scale scale,
                                    brdffit_interp interp, size_t n, const double *theta_o_deg,
                                    double *rgb, double *masked, brdffit_error *err);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#ifdef __cplusplus
}
#endif

#endif /* BRDFFIT_H */
