/* SPDX-License-Identifier: MIT */
/* check_main.c -- runs every suite listed in tests/suites.def (Check, CK_ENV verbosity).
 *
 * The test cases that read ../shared carry the Check tag "shared"
 * (TU_NEEDS_SHARED).  Without ../shared they are left out: the rest runs,
 * one line says what is missing, and the run fails. */
#include "testutil.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>

#define SUITE(name) Suite *name##_suite(void);
#include "suites.def"
#undef SUITE

int main(void)
{
    SRunner *sr = srunner_create(NULL);
#define SUITE(name) srunner_add_suite(sr, name##_suite());
#include "suites.def"
#undef SUITE
    char why[1024];
    int have_data = tu_shared_present(why, sizeof why);
    if (have_data) {
        srunner_run_all(sr, CK_ENV);
    } else {
        fprintf(stderr, "brdffit tests: %s\n", why);
        srunner_run_tagged(sr, NULL, NULL, NULL, TU_NEEDS_SHARED, CK_ENV);
    }
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 && have_data ? EXIT_SUCCESS : EXIT_FAILURE;
}
