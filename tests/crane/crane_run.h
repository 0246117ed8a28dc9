/* Shared by the crane model tests: a run of the crane model through the library, as the crane
 * program sets it up (exclude_alg, the reference's breakpoints), with its outputs. */
#ifndef CRANE_RUN_H
#define CRANE_RUN_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crane_model.h"
#include "crane_setup.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

/* the paper's tolerances */
#define RTOL 1e-6

enum {
    O_T,
    O_TH,
    O_THR,
    O_W,
    O_WR,
    O_A,
    O_AR,
    O_TIP,
    O_DL = 10,
    O_DS,
    O_LOAD,
    O_TEN = 15,
    O_X,
    O_PH,
    O_PL,
    O_DRIFT
};

typedef struct run {
    crane *c;
    dae_solver *s;
    int n;
    double *y, *yp, out[CRANE_NOUT];
    double pmin, pmax; /* line pressures over the steps of step_past */
    double *bp;        /* the breakpoints (crane_solver_setup), owned */
} run;

static inline int start_tol(run *r, const crane_scene *sc, int settle, double tol)
{
    bg_error err = {0};
    memset(r, 0, sizeof *r);
    r->c = crane_build(sc, &err);
    if (!r->c) {
        tap_diag("build: %s", err.message);
        return -1;
    }
    if (settle && crane_settle(r->c, &err) != BG_OK) {
        tap_diag("settle: %s", err.message);
        return -1;
    }
    bgr_model *m = crane_model(r->c);
    dae_problem p;
    dae_options o;
    crane_dae_problem(r->c, &p); /* the scene's tolerance convention, as the program */
    /* the options as the program (crane_setup.h), at the tolerance tol */
    if (crane_solver_setup(sc, r->c, &o, &r->bp, &err) != BG_OK) {
        tap_diag("setup: %s", err.message);
        return -1;
    }
    o.rtol = tol;
    o.atol = tol;
    o.has_t_stop = 0; /* the tests step on past the scene's t_end */
    o.max_steps = 1000000;
    r->n = bgr_n(m);
    r->y = calloc(2 * (size_t)r->n, sizeof(double));
    r->yp = r->y + r->n;
    r->s = dae_create(&p, &o, &err);
    if (!r->s) {
        tap_diag("create: %s", err.message);
        return -1;
    }
    if (dae_init(r->s, 0, bgr_y0(m), bgr_yp0(m)) != BG_OK || dae_consistent_init(r->s) != BG_OK) {
        tap_diag("init: %s", dae_get_error(r->s)->message);
        return -1;
    }
    if (dae_dense(r->s, 0.0, r->y, r->yp) != BG_OK) { /* the consistent values */
        tap_diag("dense: %s", dae_get_error(r->s)->message);
        return -1;
    }
    crane_outputs(r->c, 0, r->y, r->yp, r->out);
    return 0;
}

static inline int start(run *r, const crane_scene *sc, int settle)
{
    return start_tol(r, sc, settle, RTOL);
}

static inline int advance(run *r, double t)
{
    double tr;
    int rc = dae_solve_to(r->s, t, &tr, r->y, r->yp);
    if (rc < 0) {
        tap_diag("t = %g: %s", t, dae_get_error(r->s)->message);
        return -1;
    }
    crane_outputs(r->c, tr, r->y, r->yp, r->out);
    return 0;
}

/* Steps (no interpolation) until t is passed: y, y' of an accepted step satisfy the equations to
 * the Newton tolerance. */
static inline int step_past(run *r, double t)
{
    double tr = 0;
    r->pmin = INFINITY;
    r->pmax = -INFINITY;
    while (tr < t) {
        if (dae_step(r->s, 2 * t, &tr, r->y, r->yp) < 0) {
            tap_diag("step: %s", dae_get_error(r->s)->message);
            return -1;
        }
        crane_outputs(r->c, tr, r->y, r->yp, r->out);
        r->pmin = fmin(r->pmin, fmin(r->out[O_PH], r->out[O_PL]));
        r->pmax = fmax(r->pmax, fmax(r->out[O_PH], r->out[O_PL]));
    }
    return 0;
}

static inline void finish(run *r)
{
    dae_free(&r->s);
    free(r->y);
    free(r->bp);
    r->bp = NULL;
    crane_free(&r->c);
}

#endif
