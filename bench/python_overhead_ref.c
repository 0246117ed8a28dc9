/* The C side of bench/python_overhead.py: the same two problems as its Python residuals, solved
 * by the library with C residuals and the same options, to time what a Python residual adds.
 *   python_overhead_ref pendulum RTOL   the index-2 pendulum of examples/residual_only.c
 *   python_overhead_ref heat N RTOL     y' = D (y[i-1] - 2 y[i] + y[i+1]) (zero ends, D = N^2),
 *                                       y(0) = sin(pi x), to t = 0.1, as F = y' - f(y)
 * Prints "steps S res R t_res T wall W": R every residual call (finite differences of the
 * Jacobian and the pattern probes included), T the seconds in them, W the whole solve. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bg_dae.h"
#include "bg_status.h"

static int pendulum(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = yp[2] + y[4] * y[0];
    F[3] = yp[3] + y[4] * y[1] + 9.81;
    F[4] = y[0] * y[2] + y[1] * y[3];
    return 0;
}

static int heat(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)t;
    int n = *(const int *)user;
    double d = (double)n * n;
    for (int i = 0; i < n; i++) {
        double l = i > 0 ? y[i - 1] : 0, r = i < n - 1 ? y[i + 1] : 0;
        F[i] = yp[i] - d * (l - 2 * y[i] + r);
    }
    return 0;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    int heat_n = 0;
    dae_problem p = {0};
    dae_options o;
    dae_options_default(&o);
    double *y, t_end;
    if (argc == 3 && !strcmp(argv[1], "pendulum")) {
        p.n = 5;
        p.res = pendulum;
        o.rtol = o.atol = strtod(argv[2], NULL);
        t_end = 10;
    } else if (argc == 4 && !strcmp(argv[1], "heat")) {
        heat_n = atoi(argv[2]);
        if (heat_n < 2) return 2;
        p.n = heat_n;
        p.res = heat;
        p.user = &heat_n;
        o.rtol = o.atol = strtod(argv[3], NULL);
        t_end = 0.1;
    } else {
        fprintf(stderr, "usage: python_overhead_ref pendulum RTOL | heat N RTOL\n");
        return 2;
    }
    y = calloc((size_t)p.n, sizeof *y);
    if (!y) return 1;
    if (heat_n)
        for (int i = 0; i < heat_n; i++)
            y[i] = sin(acos(-1.0) * (i + 1) / (heat_n + 1));
    else
        y[0] = 1;
    double w0 = now(), t;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    int r = s ? dae_init(s, 0, y, NULL) : -1;
    if (r == BG_OK) r = dae_consistent_init(s);
    if (r >= 0) r = dae_solve_to(s, t_end, &t, y, NULL);
    double wall = now() - w0;
    if (r < 0) {
        fprintf(stderr, "python_overhead_ref: %s\n", s ? dae_get_error(s)->message : err.message);
        dae_free(&s);
        free(y);
        return 1;
    }
    const dae_stats *st = dae_get_stats(s);
    printf("steps %ld res %ld t_res %.6g wall %.6g\n", st->steps,
           st->res_evals + st->res_evals_fd, st->t_res, wall);
    dae_free(&s);
    free(y);
    return 0;
}
