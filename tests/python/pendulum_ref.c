/* The C run that tests/python/test_dae.py compares the Python one with: the pendulum of
 * examples/residual_only.c (velocity level, the rod force an index-2 unknown; nothing given but
 * the residual) with the options given on the command line, "pendulum_ref RTOL ATOL", from the
 * same start. Prints "t y0 .. y4" at t = 1, 2, ..., 10 with 17 digits, then the statistics
 * "steps N newton N res N jac N". Exit status 0, or 1 with the library's message on stderr. */
#include <stdio.h>
#include <stdlib.h>

#include "bg_dae.h"
#include "bg_status.h"

#define G 9.81

static int pendulum(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = yp[2] + y[4] * y[0];
    F[3] = yp[3] + y[4] * y[1] + G;
    F[4] = y[0] * y[2] + y[1] * y[3];
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: pendulum_ref RTOL ATOL\n");
        return 2;
    }
    dae_problem p = {0};
    p.n = 5;
    p.res = pendulum;
    dae_options o;
    dae_options_default(&o);
    o.rtol = strtod(argv[1], NULL);
    o.atol = strtod(argv[2], NULL);
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    if (!s) {
        fprintf(stderr, "pendulum_ref: %s\n", err.message);
        return 1;
    }
    double y[5] = {1, 0, 0, 0, 0}, yp[5], t;
    int r = dae_init(s, 0, y, NULL);
    if (r == BG_OK) r = dae_consistent_init(s);
    for (int k = 1; k <= 10 && r >= 0; k++) {
        r = dae_solve_to(s, k, &t, y, yp);
        if (r >= 0)
            printf("%.17g %.17g %.17g %.17g %.17g %.17g\n", t, y[0], y[1], y[2], y[3], y[4]);
    }
    if (r < 0) {
        fprintf(stderr, "pendulum_ref: %s\n", dae_get_error(s)->message);
        dae_free(&s);
        return 1;
    }
    const dae_stats *st = dae_get_stats(s);
    printf("steps %ld newton %ld res %ld jac %ld\n", st->steps, st->newton_iters, st->res_evals,
           st->jac_evals);
    dae_free(&s);
    return 0;
}
