/* SPDX-License-Identifier: MIT */
/* collide.c -- a caller whose own functions have the names of the library's
 * internals (bf_fail, bf_now, bf_ok, bf_kernel_sources): it links against
 * libbrdffit.a and libbrdffit.so without a clash, each side calls its own,
 * and the library still works (tests/packaging.sh). */
#include <brdffit.h>

#include <stdio.h>
#include <string.h>

static int my_calls;

/* Not the library's bf_fail: another signature, another job. */
int bf_fail(const char *what)
{
    my_calls++;
    return (int)strlen(what);
}
double bf_now(void)
{
    return -1.0;
}
void bf_ok(void)
{
    my_calls++;
}
const char *bf_kernel_sources = "the caller's";

int main(void)
{
    brdffit_params p;
    memset(&p, 0, sizeof p);
    p.p[0] = 99; /* Ward alpha above its bound: the library's own bf_fail reports it */
    brdffit_error err;
    memset(&err, 0, sizeof err);
    brdffit_status st = brdffit_params_check(BRDFFIT_WARD, &p, &err);
    if (st != BRDFFIT_E_PARAM_RANGE || err.status != BRDFFIT_E_PARAM_RANGE ||
        strstr(err.message, "alpha") == NULL) {
        fprintf(stderr, "collide: the library's error report is wrong: %d '%s'\n", (int)st,
                err.message);
        return 1;
    }
    double t = brdffit_seconds();
    if (bf_fail("abc") != 3 || bf_now() != -1.0 || !(t > 0) || my_calls != 1 ||
        strcmp(bf_kernel_sources, "the caller's") != 0) {
        fprintf(stderr, "collide: the caller's functions were not its own\n");
        return 1;
    }
    bf_ok();
    printf("collide: ok (brdffit %s)\n", brdffit_version());
    return my_calls == 2 ? 0 : 1;
}
