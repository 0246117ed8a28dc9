/* A pendulum given as a residual and nothing else: the solver finds the Jacobian patterns, which
 * unknowns are differential, index 1 or index 2, consistent initial derivatives, and integrates
 * with finite-difference Jacobians. Written at velocity level, so the rod force lam is an index-2
 * unknown:
 *     x' = u,  y' = v,  u' = -lam x,  v' = -lam y - g,  0 = x u + y v.
 * Prints the state at t = 1, 2, ..., 10 and checks the rod length and the energy. Exit status 0
 * when both hold to the tolerance. */
#include <math.h>
#include <stdio.h>

#include <bgdae/bgdae.h>

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

int main(void)
{
    dae_problem p = {0};
    p.n = 5;
    p.res = pendulum; /* nothing else: no Jacobian, no patterns, no kinds */
    dae_options o;
    dae_options_default(&o);
    o.rtol = 1e-8;
    o.atol = 1e-8;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    if (!s) {
        fprintf(stderr, "dae_create: %s\n", err.message);
        return 1;
    }
    double y[5] = {1, 0, 0, 0, 0}, yp[5], t; /* horizontal, at rest; lam to be found */
    /* DAE_WARNING (> 0): found, but unknowns ended far from the values given (another
     * solution of the constraints?); dae_get_warning says which */
    int r = dae_init(s, 0, y, NULL);
    if (r == BG_OK) r = dae_consistent_init(s);
    if (r == DAE_WARNING) fprintf(stderr, "warning: %s\n", dae_get_warning(s));
    if (r < 0) {
        fprintf(stderr, "start: %s\n", dae_get_error(s)->message);
        dae_free(&s);
        return 1;
    }
    const int *kind = dae_get_kinds(s);
    printf("kinds found: x %d, y %d, u %d, v %d, lam %d (0 differential, 2 index 2)\n", kind[0],
           kind[1], kind[2], kind[3], kind[4]);
    double worst_len = 0, worst_energy = 0;
    for (int k = 1; k <= 10; k++) {
        int r = dae_solve_to(s, k, &t, y, yp);
        if (r < 0) {
            fprintf(stderr, "t = %g: %s\n", t, dae_get_error(s)->message);
            dae_free(&s);
            return 1;
        }
        double len = hypot(y[0], y[1]), energy = 0.5 * (y[2] * y[2] + y[3] * y[3]) + G * y[1];
        worst_len = fmax(worst_len, fabs(len - 1));
        worst_energy = fmax(worst_energy, fabs(energy));
        printf("t = %4.1f  x = %+.8f  y = %+.8f  lam = %9.5f  |length - 1| = %.1e\n", t, y[0],
               y[1], y[4], fabs(len - 1));
    }
    char line[512];
    dae_stats_line(dae_get_stats(s), line, sizeof line);
    printf("%s\n", line);
    dae_free(&s);
    /* velocity level: the length drifts with the integration error, the energy is conserved */
    int ok = worst_len < 1e-5 && worst_energy < 1e-4;
    printf("rod length within %.1e, energy within %.1e: %s\n", worst_len, worst_energy,
           ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
