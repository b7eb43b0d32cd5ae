/* SPDX-License-Identifier: MIT */
/* render.c -- images of a sphere lit by directional lights and an environment
 * map, shaded by a measured table or by a model, into caller buffers
 * (image_error.c compares two of them).  Conventions: include/brdffit.h. */
#define _POSIX_C_SOURCE 200809L
#include "internal.h"

#include "bf_lobe.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#define MAX_WIDTH 16384
#define MAX_ENV_SAMPLES 65536
#define MAX_THREADS 16

int brdffit_render_default_lights(brdffit_light out[2])
{
    static const brdffit_light dflt[2] = {
        { { -1.0, 1.0, 1.5 }, { 1.0, 1.0, 1.0 } },   /* key: upper left front   */
        { { 1.0, 0.25, -0.6 }, { 0.5, 0.5, 0.5 } },  /* rim: right, from behind */
    };
    if (out)
        memcpy(out, dflt, sizeof dflt);
    return 2;
}

void brdffit_render_options_init(brdffit_render_options *opt, size_t size)
{
    brdffit_render_options d;
    memset(&d, 0, sizeof d);
    d.size = sizeof d;
    d.width = 256;
    d.nlights = BRDFFIT_RENDER_DEFAULT_LIGHTS;
    d.env_samples = 256;
    d.interp = BRDFFIT_INTERP_TRILINEAR;
    d.scale = BRDFFIT_SCALE_STANDARD;
    d.threads = 0;
    bf_options_init(BRDFFIT_STRUCT_RENDER_OPTIONS, &d, opt, size);
}

/* ------------------------------------------------------------------ shading */

/* What shades a pixel: a table lookup or a model.  Returns 1 for a valid
 * value, 0 when the lookup hit a masked bin (rgb then holds the channels
 * that were valid, 0 in the others). */
typedef struct shader {
    const brdffit_table *table;   /* the reference, or NULL for a model */
    brdffit_scale scale;
    brdffit_interp interp;
    brdffit_model model;
    const brdffit_params *params;
    double lam[3];
} shader;

static int shade(const shader *sh, const double wi[3], const double wo[3], double rgb[3])
{
    if (sh->table) {
        if (brdffit_table_lookup(sh->table, wi, wo, sh->scale, sh->interp, rgb, NULL) !=
            BRDFFIT_OK) {
            rgb[0] = rgb[1] = rgb[2] = 0;
            return 0;
        }
        int ok = 1;
        for (int c = 0; c < 3; c++)
            if (rgb[c] < 0) {
                rgb[c] = 0;
                ok = 0;
            }
        return ok;
    }
    /* wi, wo are unit and above the horizon (the caller's frame makes them so) */
    bf_geom g = { wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], 0, 0 };
    bf_geom_derive(&g);
    bf_model_value(sh->model, &g, sh->params, sh->lam, rgb);
    return 1;
}

/* ------------------------------------------------------------------ the scene */

typedef struct scene {
    int n;                        /* image width = height                   */
    int nlights;
    double ldir[BRDFFIT_RENDER_MAX_LIGHTS][3];  /* unit, camera frame     */
    double lrgb[BRDFFIT_RENDER_MAX_LIGHTS][3];
    const float *env;             /* NULL: no environment                   */
    int ew, eh;
    size_t estride;
    int samples;
    double (*hammersley)[2];      /* samples points in [0, 1)^2              */
} scene;

/* Bilinear radiance of the environment in camera-frame direction d (unit). */
static void env_radiance(const scene *sc, const double d[3], double L[3])
{
    double th = acos(fmin(fmax(d[1], -1.0), 1.0));
    double ph = atan2(d[0], -d[2]);
    double u = (ph / (2 * BF_PI) + 0.5) * sc->ew - 0.5; /* texel-centre coordinates */
    double v = th / BF_PI * sc->eh - 0.5;
    double fu = floor(u), fv = floor(v);
    double au = u - fu, av = v - fv;
    int i0 = (int)fu, j0 = (int)fv;
    int i1 = i0 + 1, j1 = j0 + 1;
    i0 = ((i0 % sc->ew) + sc->ew) % sc->ew;
    i1 = ((i1 % sc->ew) + sc->ew) % sc->ew;
    j0 = j0 < 0 ? 0 : j0 >= sc->eh ? sc->eh - 1 : j0;
    j1 = j1 < 0 ? 0 : j1 >= sc->eh ? sc->eh - 1 : j1;
    const float *r0 = sc->env + (size_t)j0 * sc->estride;
    const float *r1 = sc->env + (size_t)j1 * sc->estride;
    for (int c = 0; c < 3; c++) {
        double top = (1 - au) * r0[3 * i0 + c] + au * r0[3 * i1 + c];
        double bot = (1 - au) * r1[3 * i0 + c] + au * r1[3 * i1 + c];
        L[c] = (1 - av) * top + av * bot;
    }
}

/* A fixed hash of a pixel index to two numbers in [0, 1) (splitmix64). */
static void pixel_shift(uint64_t index, double out[2])
{
    uint64_t z = index * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull;
    for (int k = 0; k < 2; k++) {
        z += 0x9E3779B97F4A7C15ull;
        uint64_t x = z;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        x ^= x >> 31;
        out[k] = (double)(x >> 11) * (1.0 / 9007199254740992.0);
    }
}

static void to_local(const double t[3], const double b[3], const double n[3], const double d[3],
                     double out[3])
{
    out[0] = t[0] * d[0] + t[1] * d[1] + t[2] * d[2];
    out[1] = b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
    out[2] = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
}

/* A pixel a render cannot represent: where, which channel, what. */
typedef struct overflow {
    int row, col, c;  /* row -1: none */
    int shading;      /* 1: the BRDF value there is not finite; 0: the radiance exceeds FLT_MAX */
    double value;
    double wi[3];     /* the direction of that value (shading 1) */
} overflow;

/* 0 when every channel of f is finite, else 1 with what into o. */
static int shading_bad(const double f[3], const double wi[3], overflow *o)
{
    for (int c = 0; c < 3; c++)
        if (!isfinite(f[c])) {
            *o = (overflow){ 0, 0, c, 1, f[c], { wi[0], wi[1], wi[2] } };
            return 1;
        }
    return 0;
}

/* One pixel: RGB radiance and coverage into px[0..3]; 0, or 1 with o set
 * (but for row, col) when the pixel has no finite float value. */
static int render_pixel(const scene *sc, const shader *sh, int col, int row, float *px, overflow *o)
{
    int N = sc->n;
    double x = 2.0 * (col + 0.5) / N - 1.0, y = 1.0 - 2.0 * (row + 0.5) / N;
    double r2 = x * x + y * y;
    if (!(r2 < 1.0)) {
        px[0] = px[1] = px[2] = px[3] = 0.0f;
        return 0;
    }
    double n[3] = { x, y, sqrt(1.0 - r2) };
    double tl = sqrt(n[2] * n[2] + n[0] * n[0]); /* > 0: n_z > 0 */
    double t[3] = { n[2] / tl, 0.0, -n[0] / tl };
    double b[3] = { n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2],
                    n[0] * t[1] - n[1] * t[0] };
    const double view[3] = { 0.0, 0.0, 1.0 };
    double wo[3], wi[3], f[3];
    to_local(t, b, n, view, wo);
    double L[3] = { 0, 0, 0 };
    int masked = 0;
    for (int k = 0; k < sc->nlights; k++) {
        to_local(t, b, n, sc->ldir[k], wi);
        if (wi[2] <= 0)
            continue;
        if (!shade(sh, wi, wo, f))
            masked = 1;
        if (shading_bad(f, wi, o))
            return 1;
        for (int c = 0; c < 3; c++)
            L[c] += f[c] * sc->lrgb[k][c] * wi[2];
    }
    if (sc->env) {
        double shift[2], Ls[3], Le[3] = { 0, 0, 0 };
        pixel_shift((uint64_t)row * (uint64_t)N + (uint64_t)col, shift);
        for (int s = 0; s < sc->samples; s++) {
            double u1 = sc->hammersley[s][0] + shift[0], u2 = sc->hammersley[s][1] + shift[1];
            u1 -= floor(u1);
            u2 -= floor(u2);
            /* cosine-distributed: pdf cos(theta)/pi, so f L cos / pdf = pi f L */
            double rr = sqrt(u1), phi = 2.0 * BF_PI * u2;
            wi[0] = rr * cos(phi);
            wi[1] = rr * sin(phi);
            wi[2] = sqrt(fmax(1.0 - u1, 0.0));
            if (!(wi[2] > 0))
                continue;
            double d[3];
            for (int c = 0; c < 3; c++)
                d[c] = wi[0] * t[c] + wi[1] * b[c] + wi[2] * n[c];
            env_radiance(sc, d, Ls);
            if (!shade(sh, wi, wo, f))
                masked = 1;
            if (shading_bad(f, wi, o))
                return 1;
            for (int c = 0; c < 3; c++)
                Le[c] += f[c] * Ls[c];
        }
        for (int c = 0; c < 3; c++)
            L[c] += Le[c] * (BF_PI / sc->samples);
    }
    for (int c = 0; c < 3; c++) {
        if (!(L[c] <= FLT_MAX)) { /* also NaN: inf * 0 */
            *o = (overflow){ 0, 0, c, 0, L[c], { 0, 0, 0 } };
            return 1;
        }
        px[c] = (float)L[c];
    }
    px[3] = masked ? BRDFFIT_COVERAGE_MASKED : 1.0f;
    return 0;
}

/* ------------------------------------------------------------------ threads */

typedef struct job {
    const scene *sc;
    const shader *sh;
    float *rgba;
    size_t stride;
    int first, step; /* rows first, first + step, ... */
    overflow bad;    /* the job's first pixel with no float value (it stops there) */
} job;

static void *render_rows(void *arg)
{
    job *j = arg;
    j->bad.row = -1;
    for (int row = j->first; row < j->sc->n; row += j->step) {
        float *line = j->rgba + (size_t)row * j->stride;
        for (int col = 0; col < j->sc->n; col++)
            if (render_pixel(j->sc, j->sh, col, row, line + 4 * (size_t)col, &j->bad)) {
                j->bad.row = row;
                j->bad.col = col;
                return NULL;
            }
    }
    return NULL;
}

/* The first pixel (in row order) of any job with no float value: the image
 * is cleared (no inf or NaN left in it) and the render refused. */
static brdffit_status refuse_overflow(const scene *sc, const shader *sh, const job *jobs, int nt,
                                      float *rgba, size_t stride, brdffit_error *err)
{
    const overflow *b = NULL;
    for (int k = 0; k < nt; k++)
        if (jobs[k].bad.row >= 0 && (!b || jobs[k].bad.row < b->row ||
                                     (jobs[k].bad.row == b->row && jobs[k].bad.col < b->col)))
            b = &jobs[k].bad;
    if (!b)
        return BRDFFIT_OK;
    for (int row = 0; row < sc->n; row++)
        memset(rgba + (size_t)row * stride, 0, 4 * (size_t)sc->n * sizeof *rgba);
    static const char ch[3] = { 'R', 'G', 'B' };
    if (b->shading)
        return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                       "render: pixel (%d, %d): the %s's value in channel %c is %g at wi = "
                       "(%.3g, %.3g, %.3g) (not finite: lower s or d)",
                       b->col, b->row, sh->table ? "table" : "model", ch[b->c], b->value, b->wi[0],
                       b->wi[1], b->wi[2]);
    return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                   "render: pixel (%d, %d) channel %c would be %g, beyond the largest float (%g): "
                   "lower the lights' irradiance, the environment's radiance or the BRDF's scale",
                   b->col, b->row, ch[b->c], b->value, (double)FLT_MAX);
}

static int thread_count(int asked, int rows)
{
    int n = asked;
    if (n <= 0) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        n = cpus > 0 ? (int)cpus : 1;
    }
    if (n > MAX_THREADS)
        n = MAX_THREADS;
    if (n > rows)
        n = rows;
    return n < 1 ? 1 : n;
}

/* Rows are dealt round-robin to the threads; every pixel is computed the
 * same way whichever thread does it, so the bytes do not depend on threads. */
static brdffit_status run_jobs(const scene *sc, const shader *sh, int threads, float *rgba,
                               size_t stride, brdffit_error *err)
{
    int nt = thread_count(threads, sc->n);
    job jobs[MAX_THREADS];
    pthread_t tid[MAX_THREADS];
    int started = 0;
    for (int k = 0; k < nt; k++)
        jobs[k] = (job){ sc, sh, rgba, stride, k, nt, { -1, 0, 0, 0, 0, { 0, 0, 0 } } };
    for (int k = 1; k < nt; k++) {
        if (pthread_create(&tid[k], NULL, render_rows, &jobs[k]) != 0)
            break;
        started++;
    }
    render_rows(&jobs[0]);
    for (int k = 1; k <= started; k++)
        pthread_join(tid[k], NULL);
    /* rows of threads that could not start: done here */
    for (int k = started + 1; k < nt; k++)
        render_rows(&jobs[k]);
    return refuse_overflow(sc, sh, jobs, nt, rgba, stride, err);
}

/* ------------------------------------------------------------------ options */

/* The options in effect: opt's members inside opt->size over the defaults. */
static brdffit_status read_options(const brdffit_render_options *opt, brdffit_render_options *o,
                                   brdffit_error *err)
{
    brdffit_render_options_default(o);
    return bf_options_read(BRDFFIT_STRUCT_RENDER_OPTIONS, opt, o, err);
}

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static brdffit_status make_lights(const brdffit_render_options *o, scene *sc, brdffit_error *err)
{
    brdffit_light dflt[2];
    const brdffit_light *src = o->lights;
    int n = o->nlights;
    if (n == BRDFFIT_RENDER_DEFAULT_LIGHTS) {
        n = brdffit_render_default_lights(dflt);
        src = dflt;
    }
    if (n < 0 || n > BRDFFIT_RENDER_MAX_LIGHTS)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: nlights = %d (0..%d or %d)",
                       n, BRDFFIT_RENDER_MAX_LIGHTS, BRDFFIT_RENDER_DEFAULT_LIGHTS);
    sc->nlights = n;
    for (int k = 0; k < n; k++) {
        const double *d = src[k].dir, *e = src[k].rgb;
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!finite3(d) || !isfinite(len) || !(len > 0))
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "render: light %d: direction (%g, %g, %g) must be finite and non-zero",
                           k, d[0], d[1], d[2]);
        if (!finite3(e) || e[0] < 0 || e[1] < 0 || e[2] < 0)
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "render: light %d: irradiance (%g, %g, %g) must be finite and >= 0", k,
                           e[0], e[1], e[2]);
        if (e[0] > BRDFFIT_RADIANCE_MAX || e[1] > BRDFFIT_RADIANCE_MAX || e[2] > BRDFFIT_RADIANCE_MAX)
            return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                           "render: light %d: irradiance (%g, %g, %g) is above BRDFFIT_RADIANCE_MAX "
                           "(%g): scale the lights down", k, e[0], e[1], e[2], BRDFFIT_RADIANCE_MAX);
        for (int c = 0; c < 3; c++) {
            sc->ldir[k][c] = d[c] / len;
            sc->lrgb[k][c] = e[c];
        }
    }
    return BRDFFIT_OK;
}

static brdffit_status make_env(const brdffit_render_options *o, scene *sc, brdffit_error *err)
{
    sc->env = NULL;
    sc->hammersley = NULL;
    if (!o->env)
        return BRDFFIT_OK;
    if (o->env_width < 1 || o->env_height < 1 || o->env_width > (1 << 20) ||
        o->env_height > (1 << 20))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: environment %d x %d texels",
                       o->env_width, o->env_height);
    size_t stride = o->env_stride ? o->env_stride : 3 * (size_t)o->env_width;
    if (stride < 3 * (size_t)o->env_width)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "render: environment stride %zu < 3 x width %d", stride, o->env_width);
    if (o->env_samples < 1 || o->env_samples > MAX_ENV_SAMPLES)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: env_samples = %d (1..%d)",
                       o->env_samples, MAX_ENV_SAMPLES);
    for (int j = 0; j < o->env_height; j++) {
        const float *r = o->env + (size_t)j * stride;
        for (int i = 0; i < 3 * o->env_width; i++)
            if (!isfinite(r[i]) || r[i] < 0)
                return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                               "render: environment texel (%d, %d) channel %d is %g (radiance "
                               "must be finite and >= 0)",
                               i / 3, j, i % 3, (double)r[i]);
            else if (r[i] > (float)BRDFFIT_RADIANCE_MAX) /* the float nearest: 1e20f is above 1e20 */
                return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                               "render: environment texel (%d, %d) channel %d is %g, above "
                               "BRDFFIT_RADIANCE_MAX (%g): scale the map down",
                               i / 3, j, i % 3, (double)r[i], BRDFFIT_RADIANCE_MAX);
    }
    sc->hammersley = bf_alloc_aligned((size_t)o->env_samples * sizeof *sc->hammersley);
    if (!sc->hammersley)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "render: no memory for %d samples",
                       o->env_samples);
    for (int s = 0; s < o->env_samples; s++) {
        /* (s + 1/2) / S and the radical inverse of s in base 2 */
        uint32_t bits = (uint32_t)s;
        bits = (bits << 16) | (bits >> 16);
        bits = ((bits & 0x55555555u) << 1) | ((bits & 0xAAAAAAAAu) >> 1);
        bits = ((bits & 0x33333333u) << 2) | ((bits & 0xCCCCCCCCu) >> 2);
        bits = ((bits & 0x0F0F0F0Fu) << 4) | ((bits & 0xF0F0F0F0u) >> 4);
        bits = ((bits & 0x00FF00FFu) << 8) | ((bits & 0xFF00FF00u) >> 8);
        sc->hammersley[s][0] = (s + 0.5) / o->env_samples;
        sc->hammersley[s][1] = bits * (1.0 / 4294967296.0);
    }
    sc->env = o->env;
    sc->ew = o->env_width;
    sc->eh = o->env_height;
    sc->estride = stride;
    sc->samples = o->env_samples;
    return BRDFFIT_OK;
}

/* Check the options and the output buffer; build the scene (free its
 * hammersley set with bf_free_aligned). */
static brdffit_status prepare(const brdffit_render_options *opt, float *rgba, size_t *stride,
                              brdffit_render_options *o, scene *sc, brdffit_error *err)
{
    memset(sc, 0, sizeof *sc);
    brdffit_status st = read_options(opt, o, err);
    if (st != BRDFFIT_OK)
        return st;
    if (o->width < 1 || o->width > MAX_WIDTH)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: width %d (1..%d)", o->width,
                       MAX_WIDTH);
    if (!rgba)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: rgba is NULL");
    if (*stride == 0)
        *stride = 4 * (size_t)o->width;
    if (*stride < 4 * (size_t)o->width)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: stride %zu < 4 x width %d",
                       *stride, o->width);
    if ((o->interp != BRDFFIT_INTERP_NEAREST && o->interp != BRDFFIT_INTERP_TRILINEAR) ||
        (o->scale != BRDFFIT_SCALE_STANDARD && o->scale != BRDFFIT_SCALE_FLAT))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "render: unknown interp %d or scale %d",
                       (int)o->interp, (int)o->scale);
    sc->n = o->width;
    st = make_lights(o, sc, err);
    if (st == BRDFFIT_OK)
        st = make_env(o, sc, err);
    return st;
}

static brdffit_status render(const shader *sh, const brdffit_render_options *opt, float *rgba,
                             size_t stride, brdffit_error *err)
{
    brdffit_render_options o;
    scene sc;
    brdffit_status st = prepare(opt, rgba, &stride, &o, &sc, err);
    if (st == BRDFFIT_OK) {
        shader s = *sh;
        s.scale = o.scale;
        s.interp = o.interp;
        st = run_jobs(&sc, &s, o.threads, rgba, stride, err);
    }
    bf_free_aligned(sc.hammersley);
    if (st == BRDFFIT_OK)
        bf_ok(err);
    return st;
}

brdffit_status brdffit_render_table(const brdffit_table *table, const brdffit_render_options *opt,
                                    float *rgba, size_t stride, brdffit_error *err)
{
    if (!table)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_render_table: table is NULL");
    shader sh;
    memset(&sh, 0, sizeof sh);
    sh.table = table;
    return render(&sh, opt, rgba, stride, err);
}

brdffit_status brdffit_render_model(brdffit_model model, const brdffit_params *params,
                                    const brdffit_render_options *opt, float *rgba,
                                    size_t stride, brdffit_error *err)
{
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    shader sh;
    memset(&sh, 0, sizeof sh);
    sh.model = model;
    sh.params = params;
    bf_lambdas(params, sh.lam);
    return render(&sh, opt, rgba, stride, err);
}
