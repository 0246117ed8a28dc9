/* Helpers shared by the component tests (header-only, all static).
 *
 *   B(...)          a bond between two ports, failing the test point on error
 *   V(m, path)      variable id by path (diagnostic if absent); at(y, v) reads it (NaN if absent)
 *   solver_new      a dae_solver for a compiled model (tolerances, optional breakpoints and
 *                   per-variable absolute tolerances), started from bgr_y0/bgr_yp0 and made
 *                   consistent
 *   random_point    y, y' at random, of given scales
 *   check_jac       bgr_check_jacobian at y, y': one test point, the report in a diagnostic
 * Numbers the tests compare against are derived in the tests themselves (closed forms, hand
 * computations), never read back from the components. */
#ifndef CMP_TESTS_CMPTEST_H
#define CMP_TESTS_CMPTEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bgr_elements.h"
#include "bgr_model.h"
#include "modeltest.h"
#include "tap.h"

#define PI 3.14159265358979323846

static int ct_bond_fail = 0;
static double ct_h_init = 0; /* dae_options.h_init of the next solver_new (0: the solver's) */

/* Bond from port pa of element a to port pb of element b (power a -> b). */
TAP_UNUSED static int B(bgr_model *m, const char *name, int a, int pa, int b, int pb)
{
    int id = bgr_bond(m, 0, name, 1, bgr_port_of(m, a, pa), bgr_port_of(m, b, pb), NULL, NULL);
    if (id < 0) {
        ct_bond_fail++;
        tap_diag("bond %s: %s", name, bgr_model_error(m)->message);
    }
    return id;
}

TAP_UNUSED static int V(const bgr_model *m, const char *path)
{
    int v = bgr_find_var(m, path);
    if (v < 0) tap_diag("no variable named %s", path);
    return v;
}

/* Compiles m; one test point. */
TAP_UNUSED static int compile_ok(bgr_model *m, const char *what)
{
    int st = bgr_compile(m);
    tap_ok(st == BG_OK && ct_bond_fail == 0, "%s: model built and compiled", what);
    if (st != BG_OK) tap_diag("%s", bgr_model_error(m)->message);
    return st == BG_OK && ct_bond_fail == 0;
}

TAP_UNUSED static dae_solver *solver_new(bgr_model *m, double rtol, double atol,
                                         const double *atol_vec, const double *bkpt, int nbkpt,
                                         double t0)
{
    dae_options o;
    dae_options_default(&o);
    o.rtol = rtol;
    o.atol = atol;
    o.atol_vec = atol_vec;
    o.breakpoints = bkpt;
    o.nbreakpoints = nbkpt;
    o.h_init = ct_h_init;
    return model_solver(m, &o, NULL, t0);
}

/* Integrates to tout; diagnostic on failure. */
TAP_UNUSED static int solve_to(dae_solver *s, double tout, double *y, double *yp)
{
    double tret;
    int r = dae_solve_to(s, tout, &tret, y, yp);
    if (r < 0)
        tap_diag("dae_solve_to(%g): %s: %s", tout, dae_return_name(r), dae_get_error(s)->message);
    return r;
}

/* A random point: y_i uniform in scale[i] * [0.5, 1.5] with a random sign (scale NULL: 1), y'_i
 * in scale[i] * [-1, 1]. */
TAP_UNUSED static void random_point(int n, const double *scale, uint64_t seed, double *y,
                                    double *yp)
{
    tap_rng r = tap_rng_seed(seed);
    for (int i = 0; i < n; i++) {
        double sc = scale ? scale[i] : 1.0;
        y[i] = sc * tap_rng_range(&r, 0.5, 1.5) * (tap_rng_unif(&r) < 0.5 ? -1.0 : 1.0);
        yp[i] = sc * tap_rng_range(&r, -1.0, 1.0);
    }
}

/* The analytic partial derivatives of every element against central differences at (t, y, yp):
 * one test point, the checker's report in a diagnostic. */
TAP_UNUSED static void check_jac(bgr_model *m, double t, const double *y, const double *yp,
                                 double tol, const char *what)
{
    char rep[512];
    int bad = bgr_check_jacobian(m, t, y, yp, tol, rep, sizeof rep);
    tap_ok(bad == 0, "%s: analytic Jacobian agrees with finite differences (%d mismatches)", what,
           bad);
    tap_diag("%s", rep);
}

#endif
