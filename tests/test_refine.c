/* SPDX-License-Identifier: MIT */
/* test_refine.c -- which subset runs a fit refines on all samples
 * (refine_select.c): bf_refine_select on synthetic ends, each rule against
 * a plain reading of it (margin, joined, one valley, a chain of valleys,
 * its edges, ties, directions, no margin, NaN, more runs than it takes). */
#include "refine_select.h"

#include <check.h>
#include <math.h>

/* An end with r^T r rr at places (a, b, c) of three bounded coordinates. */
static bf_run_end end3(double rr, double a, double b, double c, int joined)
{
    bf_run_end e = { .rr = rr, .joined = joined };
    e.place[0] = a, e.place[2] = b, e.place[4] = c;
    return e;
}

/* bf_refine_select's choice of n ends as a bit mask (bit r: run r). */
static unsigned choose(const bf_run_end *ends, int n, double margin)
{
    int refine[8];
    bf_refine_select(ends, n, 6, margin, refine);
    unsigned mask = 0;
    for (int r = 0; r < n; r++) {
        ck_assert_msg(refine[r] == 0 || refine[r] == 1, "refine[%d] = %d", r, refine[r]);
        mask |= (unsigned)refine[r] << r;
    }
    return mask;
}

/* Runs within the margin of the lowest are refined, the others and the
 * joined ones not; apart (places 0.1 apart), each on its own. */
START_TEST(margin_and_joined)
{
    bf_run_end e[4] = { end3(1.00, 0.2, 0.5, 0.5, 0), end3(1.019, 0.5, 0.5, 0.5, 0),
                        end3(1.021, 0.8, 0.5, 0.5, 0), end3(1.0, 0.35, 0.5, 0.5, 1) };
    ck_assert_uint_eq(choose(e, 4, 0.02), 0x3u);
    ck_assert_uint_eq(choose(e, 3, 0.02), 0x3u);
    ck_assert_uint_eq(choose(e, 4, INFINITY), 0x7u); /* no margin: all but the joined */
    ck_assert_uint_eq(choose(e, 1, 0.02), 0x1u);
}
END_TEST

/* Two ends in one valley: the lower alone, wherever it stands in the
 * order; a third apart stays; equal r^T r: the earlier. */
START_TEST(one_valley_the_lowest)
{
    bf_run_end e[3] = { end3(1.00003, 0.40, 0.30, 0.20, 0), end3(1.0, 0.405, 0.295, 0.209, 0),
                        end3(1.001, 0.70, 0.30, 0.20, 0) };
    ck_assert_uint_eq(choose(e, 3, 0.02), 0x6u);
    bf_run_end f[3] = { e[1], e[0], e[2] };
    ck_assert_uint_eq(choose(f, 3, 0.02), 0x5u);
    bf_run_end g[2] = { end3(2.0, 0.1, 0.1, 0.1, 0), end3(2.0, 0.1, 0.1, 0.1, 0) };
    ck_assert_uint_eq(choose(g, 2, 0.02), 0x1u);
    /* the valley's lowest refined even when a third end lies in it too */
    bf_run_end h[3] = { end3(1.00005, 0.5, 0.5, 0.5, 0), end3(1.00002, 0.505, 0.5, 0.5, 0),
                        end3(1.0, 0.509, 0.5, 0.5, 0) };
    ck_assert_uint_eq(choose(h, 3, 0.02), 0x4u);
    /* a chain: the middle end shares a valley with each of the others, which
     * share none: the lowest and the far one are refined, the middle not */
    bf_run_end c[3] = { end3(1.00002, 0.516, 0.5, 0.5, 0), end3(1.0, 0.5, 0.5, 0.5, 0),
                        end3(1.00001, 0.508, 0.5, 0.5, 0) };
    ck_assert_uint_eq(choose(c, 3, 0.02), 0x3u);
}
END_TEST

/* Just outside either tolerance, both are refined; just inside, one. */
START_TEST(valley_edges)
{
    const double d = BF_VALLEY_PLACE, q = BF_VALLEY_RR;
    bf_run_end in[2] = { end3(1.0, 0.3, 0.3, 0.3, 0), end3(1.0 + 0.9 * q, 0.3 + 0.9 * d, 0.3, 0.3 - 0.9 * d, 0) };
    ck_assert_uint_eq(choose(in, 2, 0.02), 0x1u);
    ck_assert(bf_same_valley(&in[0], &in[1], 6) && bf_same_valley(&in[1], &in[0], 6));
    bf_run_end far_place[2] = { in[0], end3(1.0, 0.3, 0.3 + 1.1 * d, 0.3, 0) };
    ck_assert_uint_eq(choose(far_place, 2, 0.02), 0x3u);
    bf_run_end far_rr[2] = { in[0], end3(1.0 + 1.1 * q * (1.0 + 1.1 * q), 0.3, 0.3, 0.3, 0) };
    ck_assert_uint_eq(choose(far_rr, 2, 0.02), 0x3u);
    /* places past nplaces are not compared */
    bf_run_end tail[2] = { in[0], in[0] };
    tail[1].place[5] = 0.9;
    ck_assert(!bf_same_valley(&tail[0], &tail[1], 6));
    ck_assert(bf_same_valley(&tail[0], &tail[1], 5));
}
END_TEST

/* A direction is two places (cos, sin): the same angle one turn apart is
 * one place, the opposite direction another. */
START_TEST(direction_places)
{
    const double u = 0.7, turn = 6.283185307179586;
    bf_run_end a = { .rr = 1.0 }, b = { .rr = 1.0 }, c = { .rr = 1.0 };
    a.place[0] = cos(u), a.place[1] = sin(u);
    b.place[0] = cos(u + turn), b.place[1] = sin(u + turn);
    c.place[0] = cos(u + 0.5 * turn), c.place[1] = sin(u + 0.5 * turn);
    ck_assert(bf_same_valley(&a, &b, 2));
    ck_assert(!bf_same_valley(&a, &c, 2));
}
END_TEST

/* Runs past BF_REFINE_MAX are not refined; those before it are chosen as
 * ever. */
START_TEST(past_the_bound)
{
    bf_run_end e[BF_REFINE_MAX + 2];
    int refine[BF_REFINE_MAX + 2];
    for (int r = 0; r < BF_REFINE_MAX + 2; r++)
        e[r] = end3(1.0 + 1e-3 * r, 0.05 * r, 0.5, 0.5, 0);
    bf_refine_select(e, BF_REFINE_MAX + 2, 6, 0.02, refine);
    for (int r = 0; r < BF_REFINE_MAX + 2; r++)
        ck_assert_int_eq(refine[r], r < BF_REFINE_MAX);
}
END_TEST

/* A NaN r^T r is never refined and holds no valley; an infinite one is the
 * lowest only when every one is. */
START_TEST(not_finite)
{
    bf_run_end e[3] = { end3(NAN, 0.5, 0.5, 0.5, 0), end3(1.0, 0.5, 0.5, 0.5, 0),
                        end3(INFINITY, 0.9, 0.5, 0.5, 0) };
    ck_assert_uint_eq(choose(e, 3, 0.02), 0x2u);
    ck_assert(!bf_same_valley(&e[0], &e[1], 6));
    bf_run_end inf[2] = { end3(INFINITY, 0.1, 0.5, 0.5, 0), end3(INFINITY, 0.9, 0.5, 0.5, 0) };
    ck_assert_uint_eq(choose(inf, 2, 0.02), 0x3u);
}
END_TEST

Suite *refine_suite(void)
{
    Suite *s = suite_create("refine");
    TCase *t = tcase_create("select");
    tcase_add_test(t, margin_and_joined);
    tcase_add_test(t, one_valley_the_lowest);
    tcase_add_test(t, valley_edges);
    tcase_add_test(t, direction_places);
    tcase_add_test(t, not_finite);
    tcase_add_test(t, past_the_bound);
    suite_add_tcase(s, t);
    return s;
}
