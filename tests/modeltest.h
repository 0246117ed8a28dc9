/* Helpers shared by the tests of compiled bond-graph models (bondgraph/bgtest.h,
 * components/cmptest.h; header-only, all static):
 *   at            y[v], NaN for a missing variable
 *   model_solver  a dae_solver for a compiled model, started from bgr_y0/bgr_yp0 and made
 *                 consistent, diagnostics on failure */
#ifndef BG_TESTS_MODELTEST_H
#define BG_TESTS_MODELTEST_H

#include <math.h>
#include <string.h>

#include "bg_dae.h"
#include "bgr_model.h"
#include "tap.h"

/* y[v], NaN for v < 0 (so that a missing name fails every comparison). */
TAP_UNUSED static double at(const double *y, int v)
{
    return v >= 0 ? y[v] : NAN;
}

/* A solver with options o for the compiled model m, started at t0 from bgr_y0/bgr_yp0 and made
 * consistent. roots (may be NULL) adds one event function. NULL on failure (diagnostic
 * printed). */
TAP_UNUSED static dae_solver *model_solver(bgr_model *m, const dae_options *o, dae_root_fn roots,
                                           double t0)
{
    dae_problem p;
    bg_error err;
    memset(&err, 0, sizeof err);
    if (bgr_dae_problem(m, &p) != BG_OK) {
        tap_diag("bgr_dae_problem: %s", bgr_model_error(m)->message);
        return NULL;
    }
    if (roots) {
        p.nroots = 1;
        p.roots = roots;
    }
    dae_solver *s = dae_create(&p, o, &err);
    if (!s) {
        tap_diag("dae_create: %s", err.message);
        return NULL;
    }
    int r = dae_init(s, t0, bgr_y0(m), bgr_yp0(m));
    if (r == BG_OK) r = dae_consistent_init(s);
    if (r != BG_OK) {
        tap_diag("dae_init/dae_consistent_init: %s: %s", dae_return_name(r),
                 dae_get_error(s)->message);
        dae_free(&s);
    }
    return s;
}

#endif
