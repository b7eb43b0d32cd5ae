/* SPDX-License-Identifier: MIT */
/* test_screen.c -- which starts a fit's screening takes (round_search.c):
 * bf_round_next on synthetic rounds (every round whose costs fall and rise
 * once is searched to its cheapest start, no start twice, 5 of a round of 7),
 * and on He's screening costs of MERL tables, each of the 21 starts taken
 * by a value pass of its own here (the oracle: the sweep the search
 * replaces). */
#include "testutil.h"
#include "internal.h"
#include "linear.h"
#include "pass.h"
#include "round_search.h"
#include "subsets.h"

#include <check.h>
#include <math.h>
#include <string.h>

/* Search a round of n with these costs: the index it ends at (the cheapest
 * screened) and how many it screened into *taken; each start at most once. */
static int search(int n, const double *costs, int *taken)
{
    double seen[BF_ROUND_MAX];
    for (int k = 0; k < n; k++)
        seen[k] = NAN;
    *taken = 0;
    for (int k; (k = bf_round_next(n, seen)) >= 0;) {
        ck_assert_msg(k < n && isnan(seen[k]), "round of %d: start %d asked again or out of range", n, k);
        seen[k] = costs[k];
        ck_assert_int_le(++*taken, n);
    }
    int best = -1;
    for (int k = 0; k < n; k++)
        if (!isnan(seen[k]) && (best < 0 || seen[k] < seen[best]))
            best = k;
    return best;
}

/* Every round of 1 .. BF_ROUND_MAX starts whose costs fall to one start and
 * rise after it (slopes of either side scaled apart) ends at that start. */
START_TEST(unimodal_rounds)
{
    static const double slopes[][2] = { { 1, 1 }, { 0.01, 5 }, { 7, 0.001 }, { 1e-9, 1e-9 } };
    for (int n = 1; n <= BF_ROUND_MAX; n++)
        for (int m = 0; m < n; m++)
            for (size_t s = 0; s < sizeof slopes / sizeof slopes[0]; s++) {
                double c[BF_ROUND_MAX];
                for (int k = 0; k < n; k++)
                    c[k] = 3.0 + (k < m ? slopes[s][0] * (m - k) * (m - k + 1) : slopes[s][1] * (k - m));
                int taken, got = search(n, c, &taken);
                ck_assert_msg(got == m, "round of %d, cheapest %d: ended at %d", n, m, got);
                ck_assert_msg(taken <= (n + 1) / 2 + 2, "round of %d: %d starts taken", n, taken);
                if (n == 7)
                    ck_assert_int_le(taken, 5);
            }
}
END_TEST

/* A round with two valleys ends at a start both of whose neighbours were
 * taken and are dearer: a local cheapest, here not the round's (start 0,
 * which no coarse start leads to); sizes outside the range: -1. */
START_TEST(other_rounds)
{
    const double c[7] = { 1.0, 5.0, 4.0, 6.0, 2.0, 3.0, 7.0 };
    int taken, got = search(7, c, &taken);
    ck_assert_int_eq(got, 4);
    ck_assert_int_eq(taken, 4); /* 1, 3, 5, then 4 */
    double none[BF_ROUND_MAX + 1];
    for (int k = 0; k <= BF_ROUND_MAX; k++)
        none[k] = NAN;
    ck_assert_int_eq(bf_round_next(0, none), -1);
    ck_assert_int_eq(bf_round_next(BF_ROUND_MAX + 1, none), -1);
    ck_assert_int_eq(bf_round_next(1, none), 0);
}
END_TEST

/* He's screening of a MERL table, every start swept with a value pass on
 * the bin subset at d = s = 0 (as the fit's screening takes it): in each of
 * the three rounds the search ends at the round's cheapest start. */
static const char *const he_tables[] = { "alum-bronze", "blue-rubber", "green-fabric", "nickel" };

START_TEST(he_rounds_found)
{
    brdffit_error err;
    brdffit_samples *set = NULL;
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.scale = BRDFFIT_SCALE_FLAT;
    ck_assert_msg(tu_merl_samples(he_tables[_i], &so, &set, &err) == BRDFFIT_OK, "%s", err.message);
    const brdffit_samples *every = NULL, *bins = NULL;
    ck_assert_msg(bf_screen_subsets(set, BRDFFIT_HE, &every, &bins, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_ptr_nonnull(bins);
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_AUTO, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_driver dr;
    ck_assert_msg(bf_driver_open(&dr, ctx, bins, BRDFFIT_HE, &err) == BRDFFIT_OK, "%s", err.message);
    static const double sigma0[3] = { 0.5, 2.0, 0.125 }; /* docs/fitting.md, Starts */
    const bf_linear zero = { { 0, 0, 0 }, { 0, 0, 0 } };
    for (int r = 0; r < 3; r++) {
        double cost[7];
        for (int k = 0; k < 7; k++) {
            bf_pass_par pp;
            memset(&pp, 0, sizeof pp);
            bf_lambdas(NULL, pp.lam); /* the fit's default wavelengths */
            pp.p[0][0] = 4.0 + 4.0 * k, pp.p[0][1] = sigma0[r], pp.p[0][2] = 2.0;
            double mom[BF_NMOM_MAX];
            ck_assert_msg(bf_driver_run(&dr, 0, &pp, mom, &err) == BRDFFIT_OK, "%s", err.message);
            bf_linear lin;
            cost[k] = bf_linear_best(mom, 3, 0, &zero, &lin);
        }
        int cheapest = 0;
        for (int k = 1; k < 7; k++)
            if (cost[k] < cost[cheapest])
                cheapest = k;
        int taken, got = search(7, cost, &taken);
        ck_assert_msg(got == cheapest, "%s, sigma0 %g: the search ended at tau = %g, the cheapest is %g",
                      he_tables[_i], sigma0[r], 4.0 + 4.0 * got, 4.0 + 4.0 * cheapest);
        ck_assert_int_le(taken, 5);
    }
    bf_driver_close(&dr);
    brdffit_context_free(ctx);
    brdffit_samples_free(set);
}
END_TEST

Suite *screen_suite(void)
{
    Suite *s = suite_create("screen");
    TCase *t = tcase_create("search");
    tcase_add_test(t, unimodal_rounds);
    tcase_add_test(t, other_rounds);
    suite_add_tcase(s, t);
    TCase *h = tcase_create("he");
    tcase_set_timeout(h, 300);
    tcase_set_tags(h, TU_NEEDS_SHARED);
    tcase_add_loop_test(h, he_rounds_found, 0, (int)(sizeof he_tables / sizeof he_tables[0]));
    suite_add_tcase(s, h);
    return s;
}
