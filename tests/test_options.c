/* SPDX-License-Identifier: MIT */
/* test_options.c -- the sized options structs: a caller's smaller struct (the
 * first members only) gets the defaults for the rest, members beyond its size
 * are never read, and bad sizes are refused with BRDFFIT_E_OPTIONS_SIZE.  The
 * sized results (brdffit_fit_result, brdffit_sample): a caller's older, smaller
 * struct gets its members and nothing after them. */
#include "testutil.h"

#include "internal.h"

#include <check.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define MEMBER_END(type, m) (offsetof(type, m) + sizeof(((type *)0)->m))

static const brdffit_struct_kind sized[] = {
    BRDFFIT_STRUCT_SAMPLE_OPTIONS, BRDFFIT_STRUCT_CONTEXT_OPTIONS, BRDFFIT_STRUCT_FIT_OPTIONS,
    BRDFFIT_STRUCT_RENDER_OPTIONS, BRDFFIT_STRUCT_CURVE_OPTIONS,
};
#define NSIZED (sizeof sized / sizeof sized[0])

/* A Ward-Duer table and its samples within 30 degrees (few: fits are quick). */
static brdffit_table *small_table(void)
{
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.05, 0.04, 0.03 }, { 0.04, 0.03, 0.02 }, { 0.2, 0, 0 }, { 0 } };
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD,
                                              NULL),
                     BRDFFIT_OK);
    return t;
}

static brdffit_samples *small_samples(const brdffit_table *t)
{
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.cutoff_deg = 30;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_samples_create(t, &so, &s, NULL), BRDFFIT_OK);
    return s;
}

/* Every options struct starts with `size` and ends on its last member, so a
 * member appended later cannot lie inside an older caller's struct. */
START_TEST(size_first_no_tail_padding)
{
    for (size_t k = 0; k < NSIZED; k++) {
        ck_assert_uint_eq(brdffit_struct_offset(sized[k], "size"), 0);
        ck_assert_msg(bf_struct_members_end(sized[k]) == brdffit_struct_size(sized[k]),
                      "kind %d: members end at %zu, sizeof %zu", (int)sized[k],
                      bf_struct_members_end(sized[k]), brdffit_struct_size(sized[k]));
    }
    brdffit_sample_options so;
    brdffit_context_options co;
    brdffit_fit_options fo;
    brdffit_render_options ro;
    brdffit_curve_options cu;
    brdffit_sample_options_default(&so);
    brdffit_context_options_default(&co);
    brdffit_fit_options_default(&fo);
    brdffit_render_options_default(&ro);
    brdffit_curve_options_default(&cu);
    ck_assert_uint_eq(so.size, sizeof so);
    ck_assert_uint_eq(co.size, sizeof co);
    ck_assert_uint_eq(fo.size, sizeof fo);
    ck_assert_uint_eq(ro.size, sizeof ro);
    ck_assert_uint_eq(cu.size, sizeof cu);
}
END_TEST

/* bf_options_read itself: the members within size are the caller's, every
 * other one the default, whatever bytes lie beyond size. */
START_TEST(read_takes_members_within_size)
{
    brdffit_fit_options dflt, in, out;
    brdffit_fit_options_default(&dflt);
    memset(&in, 0xA5, sizeof in);
    in.starts = 5;
    in.refine = 2;
    in.size = MEMBER_END(brdffit_fit_options, refine);
    out = dflt;
    ck_assert_int_eq(bf_options_read(BRDFFIT_STRUCT_FIT_OPTIONS, &in, &out, NULL), BRDFFIT_OK);
    ck_assert_uint_eq(out.size, sizeof out);
    ck_assert_int_eq(out.starts, 5);
    ck_assert_int_eq(out.refine, 2);
    ck_assert(out.ftol == dflt.ftol && out.xtol == dflt.xtol && out.gtol == dflt.gtol);
    ck_assert_int_eq(out.max_evals, dflt.max_evals);
    ck_assert(out.lambda_um[0] == 0 && out.lambda_um[1] == 0 && out.lambda_um[2] == 0);
    /* the padding after max_evals belongs to the struct that ends there */
    in.max_evals = 77;
    in.size = offsetof(brdffit_fit_options, lambda_um);
    out = dflt;
    ck_assert_int_eq(bf_options_read(BRDFFIT_STRUCT_FIT_OPTIONS, &in, &out, NULL), BRDFFIT_OK);
    ck_assert_int_eq(out.max_evals, 77);
    ck_assert(out.lambda_um[0] == 0);
    /* NULL: the defaults untouched */
    out = dflt;
    ck_assert_int_eq(bf_options_read(BRDFFIT_STRUCT_FIT_OPTIONS, NULL, &out, NULL), BRDFFIT_OK);
    ck_assert_int_eq(memcmp(&out, &dflt, sizeof out), 0);
}
END_TEST

/* An older caller's sample options: size and scale only. */
START_TEST(sample_options_prefix)
{
    brdffit_table *t = small_table();
    struct {
        size_t size;
        brdffit_scale scale;
    } old = { sizeof old, BRDFFIT_SCALE_FLAT };
    brdffit_samples *s = NULL;
    brdffit_error err;
    ck_assert_msg(brdffit_samples_create(t, (const brdffit_sample_options *)&old, &s, &err) ==
                      BRDFFIT_OK, "%s", err.message);
    brdffit_sample_options got;
    brdffit_sample_options_default(&got);
    ck_assert_int_eq(brdffit_samples_options(s, &got, &err), BRDFFIT_OK);
    ck_assert_int_eq(got.scale, BRDFFIT_SCALE_FLAT);
    ck_assert_double_eq(got.cutoff_deg, 80.0);
    /* written back into the old struct: its members only (a guard after it stays) */
    struct {
        size_t size;
        brdffit_scale scale;
        char guard[16];
    } back;
    memset(&back, 0x5A, sizeof back);
    back.size = MEMBER_END(brdffit_sample_options, scale);
    back.scale = BRDFFIT_SCALE_STANDARD;
    ck_assert_int_eq(brdffit_samples_options(s, (brdffit_sample_options *)&back, &err),
                     BRDFFIT_OK);
    ck_assert_int_eq(back.scale, BRDFFIT_SCALE_FLAT);
    for (size_t b = 0; b < sizeof back.guard; b++)
        ck_assert_int_eq((unsigned char)back.guard[b], 0x5A);
    brdffit_samples_free(s);
    /* a full struct whose size stops before cutoff_deg: the NaN there is not read */
    brdffit_sample_options cut;
    brdffit_sample_options_default(&cut);
    cut.cutoff_deg = NAN;
    cut.size = offsetof(brdffit_sample_options, cutoff_deg);
    ck_assert_int_eq(brdffit_samples_create(t, &cut, &s, &err), BRDFFIT_OK);
    brdffit_sample_options_default(&got);
    brdffit_samples_options(s, &got, NULL);
    ck_assert_double_eq(got.cutoff_deg, 80.0);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* An older caller's context options: size and backend; device beyond them unread. */
START_TEST(context_options_prefix)
{
    struct {
        size_t size;
        brdffit_backend backend;
    } old = { sizeof old, BRDFFIT_BACKEND_HOST };
    brdffit_context *ctx = NULL;
    brdffit_error err;
    ck_assert_msg(brdffit_context_create((const brdffit_context_options *)&old, &ctx, &err) ==
                      BRDFFIT_OK, "%s", err.message);
    ck_assert_int_eq(brdffit_context_backend(ctx), BRDFFIT_BACKEND_HOST);
    brdffit_context_free(ctx);
    /* within size, device is read: a device that matches nothing is refused */
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    co.backend = BRDFFIT_BACKEND_OPENCL;
    co.device = "no such device anywhere";
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_E_NO_DEVICE);
    /* beyond size it is not: the default device */
    co.size = offsetof(brdffit_context_options, device);
    ck_assert_msg(brdffit_context_create(&co, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_int_eq(brdffit_context_backend(ctx), BRDFFIT_BACKEND_OPENCL);
    brdffit_context_free(ctx);
}
END_TEST

/* An older caller's fit options (size, starts, refine): the same fit as the
 * whole struct with those values; the invalid values beyond size unread. */
START_TEST(fit_options_prefix)
{
    brdffit_table *t = small_table();
    brdffit_samples *s = small_samples(t);
    brdffit_context *ctx = NULL;
    brdffit_error err;
    ck_assert_int_eq(tu_context(BRDFFIT_BACKEND_HOST, &ctx, &err), BRDFFIT_OK);
    brdffit_fit_options full;
    brdffit_fit_options_default(&full);
    full.starts = 2;
    brdffit_fit_result want, got;
    brdffit_fit_result_init(&want);
    brdffit_fit_result_init(&got);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD_DUER, &full, &want, &err) == BRDFFIT_OK, "%s",
                  err.message);
    struct {
        size_t size;
        int starts, refine;
    } old = { sizeof old, 2, 1 };
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD_DUER, (const brdffit_fit_options *)&old, &got,
                              &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(got.error == want.error);
    ck_assert_int_eq(got.passes, want.passes);
    brdffit_fit_options cut = full;
    cut.max_evals = 0;      /* invalid, beyond size */
    cut.lambda_um[0] = -1;  /* invalid, beyond size */
    cut.size = offsetof(brdffit_fit_options, max_evals);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD_DUER, &cut, &got, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert(got.error == want.error);
    ck_assert_int_eq(got.passes, want.passes);
    cut.size = sizeof cut; /* now they are read */
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_WARD_DUER, &cut, &got, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(err.message, "max_evals"));
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* Render and curve options that stop early: the defaults past their size. */
START_TEST(render_curve_options_prefix)
{
    brdffit_params p = { { 0.1, 0.1, 0.1 }, { 0.5, 0.5, 0.5 }, { 0.5, 0.3, 0 }, { 0 } };
    enum { W = 8 };
    float a[4 * W * W], b[4 * W * W];
    brdffit_render_options ro;
    brdffit_render_options_default(&ro);
    ro.width = W;
    brdffit_error err;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &ro, a, 0, &err), BRDFFIT_OK);
    ro.nlights = 999; /* invalid, beyond size */
    ro.env_samples = -3;
    ro.size = offsetof(brdffit_render_options, nlights);
    ck_assert_msg(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &ro, b, 0, &err) == BRDFFIT_OK,
                  "%s", err.message);
    ck_assert_int_eq(memcmp(a, b, sizeof a), 0);

    brdffit_curve_options co;
    brdffit_curve_options_default(&co);
    co.ntheta_i = 1;
    co.npoints = 5;
    double ca[5 * 3], cb[5 * 3];
    ck_assert_int_eq(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &co, ca, 0, &err), BRDFFIT_OK);
    co.theta_i_deg[0] = 95; /* invalid, beyond size: the default 20 is used */
    co.size = offsetof(brdffit_curve_options, theta_i_deg);
    ck_assert_msg(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &co, cb, 0, &err) == BRDFFIT_OK,
                  "%s", err.message);
    ck_assert_int_eq(memcmp(ca, cb, sizeof ca), 0);
    co.size = sizeof co;
    ck_assert_int_eq(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &co, cb, 0, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
}
END_TEST

typedef struct size_case {
    brdffit_table *t;
    brdffit_samples *s;
    brdffit_context *ctx;
} size_case;

/* The small table, its samples and a host context. */
static void case_open(size_case *c)
{
    c->t = small_table();
    c->s = small_samples(c->t);
    ck_assert_int_eq(tu_context(BRDFFIT_BACKEND_HOST, &c->ctx, NULL), BRDFFIT_OK);
}

static void case_close(size_case *c)
{
    brdffit_context_free(c->ctx);
    brdffit_samples_free(c->s);
    brdffit_table_free(c->t);
}

/* The call of kind's options struct (all defaults, then `size`). */
static brdffit_status call_sized(const size_case *c, brdffit_struct_kind kind, size_t size,
                                 brdffit_error *err)
{
    brdffit_params p = { { 0.1, 0.1, 0.1 }, { 0.5, 0.5, 0.5 }, { 0.5, 0.3, 0 }, { 0 } };
    double rgb[3 * 180 * 4];
    brdffit_samples *s = NULL;
    brdffit_context *ctx = NULL;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    brdffit_status st = BRDFFIT_E_FIT_FAILED;
    if (kind == BRDFFIT_STRUCT_SAMPLE_OPTIONS) {
        brdffit_sample_options o;
        brdffit_sample_options_default(&o);
        o.size = size;
        st = brdffit_samples_create(c->t, &o, &s, err);
        brdffit_samples_free(s);
    } else if (kind == BRDFFIT_STRUCT_CONTEXT_OPTIONS) {
        brdffit_context_options o;
        brdffit_context_options_default(&o);
        o.backend = BRDFFIT_BACKEND_HOST;
        o.size = size;
        st = brdffit_context_create(&o, &ctx, err);
        brdffit_context_free(ctx);
    } else if (kind == BRDFFIT_STRUCT_FIT_OPTIONS) {
        brdffit_fit_options o;
        brdffit_fit_options_default(&o);
        o.starts = 1;
        o.size = size;
        st = brdffit_fit(c->ctx, c->s, BRDFFIT_WARD_DUER, &o, &r, err);
    } else if (kind == BRDFFIT_STRUCT_RENDER_OPTIONS) {
        brdffit_render_options o;
        brdffit_render_options_default(&o);
        o.width = 4;
        o.env_samples = 1;
        o.size = size; /* 8: every default, a 256 x 256 image */
        float *img = malloc(4 * sizeof(float) * 256 * 256);
        ck_assert_ptr_nonnull(img);
        st = brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, img, 0, err);
        free(img);
    } else if (kind == BRDFFIT_STRUCT_CURVE_OPTIONS) {
        brdffit_curve_options o;
        brdffit_curve_options_default(&o);
        o.size = size;
        st = brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &o, rgb, 0, err);
    }
    return st;
}

/* Size 0, smaller than `size`, inside a member, larger than the library's:
 * BRDFFIT_E_OPTIONS_SIZE with the struct's name, for every options struct;
 * a whole-member size and the full size pass. */
START_TEST(bad_sizes_refused)
{
    static const char *const names[] = { "brdffit_sample_options", "brdffit_context_options",
                                         "brdffit_fit_options", "brdffit_render_options",
                                         "brdffit_curve_options" };
    /* a size that cuts a member: inside the second member, a double or pointer
     * in most of them; inside `width` / `ntheta_i`, ints, for the others */
    static const char *const cut[] = { "cutoff_deg", "device", "ftol", "lights", "theta_i_deg" };
    size_case c;
    case_open(&c);
    for (size_t k = 0; k < NSIZED; k++) {
        size_t full = brdffit_struct_size(sized[k]);
        size_t inside = brdffit_struct_offset(sized[k], cut[k]) + 1;
        size_t bad[] = { 0, 4, inside, full + 8, full + 1 };
        const char *what[] = { "size 0", "smaller than its `size` member", "ends inside member",
                               "larger than this library's struct",
                               "larger than this library's struct" };
        for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
            brdffit_error err;
            memset(&err, 0, sizeof err);
            brdffit_status st = call_sized(&c, sized[k], bad[q], &err);
            ck_assert_msg(st == BRDFFIT_E_OPTIONS_SIZE, "%s size %zu: status %d (%s)", names[k],
                          bad[q], (int)st, err.message);
            ck_assert_int_eq(err.status, BRDFFIT_E_OPTIONS_SIZE);
            ck_assert_msg(strncmp(err.message, names[k], strlen(names[k])) == 0, "%s",
                          err.message);
            ck_assert_msg(strstr(err.message, what[q]), "%s", err.message);
            if (q == 2)
                ck_assert_ptr_nonnull(strstr(err.message, cut[k]));
        }
        brdffit_error err;
        ck_assert_msg(call_sized(&c, sized[k], full, &err) == BRDFFIT_OK, "%s", err.message);
        ck_assert_msg(call_sized(&c, sized[k], sizeof(size_t), &err) == BRDFFIT_OK, "%s: %s",
                      names[k], err.message);
    }
    case_close(&c);
}
END_TEST

/* brdffit_fit_result in its first sized layout, the members before
 * seconds_build: what a program built against that header holds.  Every
 * member where the library's struct has it. */
typedef struct old_fit_result {
    size_t size;
    brdffit_model model;
    brdffit_params params;
    double error;
    int cminpack_info;
    int iterations;
    int passes;
    double seconds;
    double seconds_solver;
    double seconds_passes;
    size_t samples;
    brdffit_backend backend;
    unsigned at_bound;
    unsigned flags;
} old_fit_result;

#define SAME_OFFSET(m) \
    _Static_assert(offsetof(old_fit_result, m) == offsetof(brdffit_fit_result, m), #m)
SAME_OFFSET(size);
SAME_OFFSET(model);
SAME_OFFSET(params);
SAME_OFFSET(error);
SAME_OFFSET(cminpack_info);
SAME_OFFSET(iterations);
SAME_OFFSET(passes);
SAME_OFFSET(seconds);
SAME_OFFSET(seconds_solver);
SAME_OFFSET(seconds_passes);
SAME_OFFSET(samples);
SAME_OFFSET(backend);
SAME_OFFSET(at_bound);
SAME_OFFSET(flags);
#undef SAME_OFFSET
_Static_assert(sizeof(old_fit_result) < sizeof(brdffit_fit_result),
               "the library's result has members the old one has not");

#define GUARD 64
#define GUARD_BYTE 0xA5

/* A call refused for the size of the result it was given (struct `name`,
 * bytes[0..n) with `size` first): BRDFFIT_E_OPTIONS_SIZE, the message naming
 * the struct and saying why, and no byte after `size` written. */
static void expect_size_refused(brdffit_status st, const brdffit_error *err, const char *name,
                                size_t size, const char *why, const unsigned char *bytes, size_t n)
{
    ck_assert_msg(st == BRDFFIT_E_OPTIONS_SIZE, "%s size %zu: status %d (%s)", name, size,
                  (int)st, err->message);
    ck_assert_msg(strncmp(err->message, name, strlen(name)) == 0 &&
                      err->message[strlen(name)] == ':', "%s", err->message);
    ck_assert_msg(strstr(err->message, why), "size %zu: %s", size, err->message);
    size_t got;
    memcpy(&got, bytes, sizeof got);
    ck_assert_uint_eq(got, size);
    for (size_t b = sizeof got; b < n; b++)
        ck_assert_msg(bytes[b] == GUARD_BYTE, "%s size %zu: byte %zu written", name, size, b);
}

/* A fit into an old caller's result: the members it has are those of the same
 * fit into the whole struct; not a byte after its size is written (guard bytes
 * after it; an exactly sized heap block for AddressSanitizer). */
/* An options struct as a caller built against an older header has it (the
 * fit options without lambda_um, the member appended last): _default() in
 * that caller sets its own size, and the library writes the defaults of its
 * members and nothing after them. */
typedef struct old_fit_options {
    size_t size;
    int starts, refine;
    double ftol, xtol, gtol;
    int max_evals;
} old_fit_options;

START_TEST(old_options_defaults_within_size)
{
    brdffit_fit_options full;
    brdffit_fit_options_default(&full);
    ck_assert_uint_eq(full.size, sizeof full);
    ck_assert_uint_eq(offsetof(old_fit_options, max_evals),
                      brdffit_struct_offset(BRDFFIT_STRUCT_FIT_OPTIONS, "max_evals"));
    size_t old = offsetof(old_fit_options, max_evals) + sizeof(int);
    ck_assert(old < sizeof full);

    union {
        old_fit_options o;
        unsigned char bytes[sizeof(old_fit_options) + GUARD];
    } buf;
    memset(&buf, GUARD_BYTE, sizeof buf);
    brdffit_fit_options_init((brdffit_fit_options *)&buf.o, old);
    for (size_t b = old; b < sizeof buf; b++)
        ck_assert_msg(buf.bytes[b] == GUARD_BYTE, "byte %zu after the old options written", b);
    ck_assert_uint_eq(buf.o.size, old);
    ck_assert_int_eq(buf.o.starts, full.starts);
    ck_assert_int_eq(buf.o.refine, full.refine);
    ck_assert(buf.o.ftol == full.ftol && buf.o.xtol == full.xtol && buf.o.gtol == full.gtol);
    ck_assert_int_eq(buf.o.max_evals, full.max_evals);

    /* too small for `size` itself: nothing written */
    memset(&buf, GUARD_BYTE, sizeof buf);
    brdffit_fit_options_init((brdffit_fit_options *)&buf.o, sizeof(size_t) - 1);
    for (size_t b = 0; b < sizeof buf; b++)
        ck_assert_msg(buf.bytes[b] == GUARD_BYTE, "byte %zu written for a size below `size`", b);
    brdffit_fit_options_init(NULL, sizeof full); /* no effect, no crash */
}
END_TEST

START_TEST(old_fit_result_written_within_size)
{
    size_case c;
    case_open(&c);
    brdffit_error err;
    brdffit_fit_options fo;
    brdffit_fit_options_default(&fo);
    fo.starts = 2;
    brdffit_fit_result want;
    brdffit_fit_result_init(&want);
    ck_assert_uint_eq(want.size, sizeof want);
    ck_assert_int_eq(want.model, 0);
    ck_assert(want.error == 0 && want.seconds_build == 0);
    ck_assert_msg(brdffit_fit(c.ctx, c.s, BRDFFIT_WARD_DUER, &fo, &want, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert_uint_eq(want.size, sizeof want);

    union {
        old_fit_result r;
        unsigned char bytes[sizeof(old_fit_result) + GUARD];
    } buf;
    memset(&buf, GUARD_BYTE, sizeof buf);
    buf.r.size = sizeof buf.r;
    ck_assert_msg(brdffit_fit(c.ctx, c.s, BRDFFIT_WARD_DUER, &fo, (brdffit_fit_result *)&buf.r,
                              &err) == BRDFFIT_OK, "%s", err.message);
    for (size_t b = sizeof buf.r; b < sizeof buf; b++)
        ck_assert_msg(buf.bytes[b] == GUARD_BYTE, "byte %zu after the old result written", b);
    const old_fit_result *o = &buf.r;
    ck_assert_uint_eq(o->size, sizeof *o);
    ck_assert_int_eq(o->model, BRDFFIT_WARD_DUER);
    ck_assert(memcmp(&o->params, &want.params, sizeof o->params) == 0);
    ck_assert(o->error == want.error);
    ck_assert_int_eq(o->cminpack_info, want.cminpack_info);
    ck_assert_int_eq(o->iterations, want.iterations);
    ck_assert_int_eq(o->passes, want.passes);
    ck_assert(o->seconds > 0 && o->seconds >= o->seconds_passes);
    ck_assert_uint_eq(o->samples, want.samples);
    ck_assert_uint_eq(o->samples, brdffit_samples_count(c.s));
    ck_assert_int_eq(o->backend, BRDFFIT_BACKEND_HOST);
    ck_assert_uint_eq(o->at_bound, want.at_bound);
    ck_assert_uint_eq(o->flags, want.flags);

    old_fit_result *heap = malloc(sizeof *heap);
    ck_assert_ptr_nonnull(heap);
    heap->size = sizeof *heap;
    ck_assert_msg(brdffit_fit(c.ctx, c.s, BRDFFIT_WARD_DUER, &fo, (brdffit_fit_result *)heap,
                              &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(heap->error == want.error);
    free(heap);
    case_close(&c);
}
END_TEST

/* A result's size below its first sized layout, inside a member or beyond the
 * library's struct is refused before any work, the caller's struct untouched;
 * the first sized layout exactly is taken. */
START_TEST(result_bad_sizes_refused)
{
    size_case c;
    case_open(&c);
    brdffit_error err;
    brdffit_fit_options fo;
    brdffit_fit_options_default(&fo);
    fo.starts = 1;
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_FIT_RESULT, "size"), 0);
    ck_assert_uint_eq(bf_struct_members_end(BRDFFIT_STRUCT_FIT_RESULT),
                      sizeof(brdffit_fit_result));
    size_t first = MEMBER_END(brdffit_fit_result, flags);
    size_t bad[] = { 0, sizeof(size_t), offsetof(brdffit_fit_result, flags),
                     offsetof(brdffit_fit_result, seconds_build) + 4,
                     sizeof(brdffit_fit_result) + 8 };
    const char *what[] = { "size 0", "smaller than its first sized layout",
                           "smaller than its first sized layout", "ends inside member",
                           "larger than this library's struct" };
    union {
        brdffit_fit_result r;
        unsigned char bytes[sizeof(brdffit_fit_result) + GUARD];
    } buf;
    for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
        memset(&buf, GUARD_BYTE, sizeof buf);
        buf.r.size = bad[q];
        memset(&err, 0, sizeof err);
        brdffit_status st = brdffit_fit(c.ctx, c.s, BRDFFIT_WARD_DUER, &fo, &buf.r, &err);
        expect_size_refused(st, &err, "brdffit_fit_result", bad[q], what[q], buf.bytes,
                            sizeof buf);
        if (q == 3)
            ck_assert_ptr_nonnull(strstr(err.message, "'seconds_build'"));
    }
    memset(&buf, GUARD_BYTE, sizeof buf);
    buf.r.size = first;
    ck_assert_msg(brdffit_fit(c.ctx, c.s, BRDFFIT_WARD_DUER, &fo, &buf.r, &err) == BRDFFIT_OK,
                  "%s", err.message);
    ck_assert_int_eq(buf.r.model, BRDFFIT_WARD_DUER);
    ck_assert(isfinite(buf.r.error));
    for (size_t b = first; b < sizeof buf; b++)
        ck_assert_msg(buf.bytes[b] == GUARD_BYTE, "byte %zu after size %zu written", b, first);
    case_close(&c);
}
END_TEST

/* brdffit_samples_get into a caller's sample: its members only, bad sizes refused. */
START_TEST(sample_sized)
{
    brdffit_table *t = small_table();
    brdffit_samples *s = small_samples(t);
    brdffit_sample want;
    brdffit_sample_init(&want);
    ck_assert_uint_eq(want.size, sizeof want);
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_SAMPLE, "size"), 0);
    brdffit_error err;
    size_t last = brdffit_samples_count(s) - 1;
    ck_assert_int_eq(brdffit_samples_get(s, last, &want, &err), BRDFFIT_OK);
    ck_assert_uint_eq(want.size, sizeof want);
    ck_assert(want.weight > 0 && want.wi[2] > 0);

    size_t first = MEMBER_END(brdffit_sample, k);
    unsigned char *heap = malloc(first); /* exactly the first layout, for AddressSanitizer */
    ck_assert_ptr_nonnull(heap);
    memcpy(heap, &first, sizeof first);
    ck_assert_int_eq(brdffit_samples_get(s, last, (brdffit_sample *)heap, &err), BRDFFIT_OK);
    ck_assert(memcmp(heap + sizeof first, (const unsigned char *)&want + sizeof first,
                     first - sizeof first) == 0);
    free(heap);

    size_t bad[] = { 0, sizeof(size_t), offsetof(brdffit_sample, k), sizeof(brdffit_sample) + 8 };
    const char *what[] = { "size 0", "smaller than its first sized layout",
                           "smaller than its first sized layout",
                           "larger than this library's struct" };
    union {
        brdffit_sample x;
        unsigned char bytes[sizeof(brdffit_sample) + GUARD];
    } buf;
    for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
        memset(&buf, GUARD_BYTE, sizeof buf);
        buf.x.size = bad[q];
        expect_size_refused(brdffit_samples_get(s, 0, &buf.x, &err), &err, "brdffit_sample",
                            bad[q], what[q], buf.bytes, sizeof buf);
    }
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

Suite *options_suite(void)
{
    Suite *s = suite_create("options");
    TCase *tc = tcase_create("options");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, size_first_no_tail_padding);
    tcase_add_test(tc, read_takes_members_within_size);
    tcase_add_test(tc, sample_options_prefix);
    tcase_add_test(tc, context_options_prefix);
    tcase_add_test(tc, fit_options_prefix);
    tcase_add_test(tc, render_curve_options_prefix);
    tcase_add_test(tc, bad_sizes_refused);
    tcase_add_test(tc, old_options_defaults_within_size);
    tcase_add_test(tc, old_fit_result_written_within_size);
    tcase_add_test(tc, result_bad_sizes_refused);
    tcase_add_test(tc, sample_sized);
    suite_add_tcase(s, tc);
    return s;
}
