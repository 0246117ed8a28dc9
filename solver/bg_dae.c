/* Modified BDF for semi-explicit index-2 DAEs F(t, y, y') = 0: the outer loop.
 * The integrator's files and what each holds: the index in bg_dae_impl.h.
 *
 * Method. Variable-order, variable-step BDF in fixed-leading-coefficient form with the history
 * kept as modified divided differences, as in DASSL and IDA (Brenan, Campbell and Petzold 1996,
 * sec. 5.2-5.3), corrected by a modified Newton iteration (dae_nls.c), with the local error test
 * and the step and order rules of IDA's published algorithm (dae_err.c). Index 2 (Brenan et al.
 * sec. 3.3; Hairer and Wanner, Solving ODEs II, sec. VII.3): the index-2 unknowns are left out of
 * the error test or weighted by h (dae_err.c), weighted in full in the Newton test, and the
 * Newton matrix is scaled so that it stays O(1) as h -> 0 (dae_nls.c). Consistent initial values
 * and the structural classification: dae_ic.c, dae_struct.c. Drift: with position constraints
 * g(y) given, the maximum |g| after each step is recorded and, if asked, y is projected back
 * (dae_out.c). Breakpoints and jumps: dae_disc.c. */
#include "bg_dae.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae_impl.h"

#define DETECT_POINTS 3 /* points at which the residual is probed for its patterns */

bg_error *dae_get_error(dae_solver *s)
{
    return s ? &s->err : NULL;
}
double dae_current_time(const dae_solver *s)
{
    return s && s->initialized ? s->tn : NAN;
}
const char *dae_get_warning(const dae_solver *s)
{
    return s ? s->warn.message : NULL;
}

const int *dae_get_kinds(const dae_solver *s)
{
    return s && s->structured ? s->kind : NULL;
}

int dae_get_patterns(const dae_solver *s, const sp_csc **jy, const sp_csc **jyp)
{
    if (!s || !jy || !jyp) return BG_ERR_ARGUMENT;
    if (!s->structured) return BG_ERR_STATE;
    *jy = s->Jy;
    *jyp = s->Jyp;
    return BG_OK;
}

int dae_get_consistent(const dae_solver *s, double *y, double *yp)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!s->yc) return BG_ERR_STATE;
    if (y) memcpy(y, s->yc, (size_t)s->n * sizeof *y);
    if (yp) memcpy(yp, s->yc + s->n, (size_t)s->n * sizeof *yp);
    return BG_OK;
}

const dae_stats *dae_get_stats(const dae_solver *s)
{
    return s ? &s->st : NULL;
}



int dae_init(dae_solver *s, double t0, const double *y0, const double *yp0)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (s->busy)
        return bg_error_raise(&s->err, BG_ERR_STATE, "dae_init",
                              "called from within a callback of the same solver");
    if (!y0) return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_init", "y0 is NULL");
    if (!isfinite(t0))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_init", "t0 = %g is not finite", t0);
    char nb[32];
    for (int i = 0; i < s->n; i++)
        if (!isfinite(y0[i]) || (yp0 && !isfinite(yp0[i])))
            return bg_error_raise(&s->err, BG_ERR_NONFINITE, "dae_init",
                                  "initial value of %s is not finite",
                                  daei_vname(s, i, nb, sizeof nb));
    memset(&s->st, 0, sizeof s->st);
    s->st.h_min_used = INFINITY;
    s->st.rcond_min = INFINITY;
    s->st.t_last_restart = NAN;
    if (s->red) daei_red_reset(s);
    if (s->detect && !s->structured) { /* no patterns given: found from the residual here */
        long added;
        int r = s->red ? daei_red_detect(s, t0, y0, yp0)
                       : daei_probe_patterns(s, t0, y0, yp0, DETECT_POINTS, &added);
        if (r == BG_OK && !s->red) r = daei_setup_structure(s, &s->err);
        if (r != BG_OK) return r;
    }
    s->st.reduced_rows = s->red ? s->p.ncons : 0;
    memcpy(s->phi[0], y0, (size_t)s->n * sizeof *y0);
    if (yp0)
        memcpy(s->phi[1], yp0, (size_t)s->n * sizeof *yp0);
    else
        memset(s->phi[1], 0, (size_t)s->n * sizeof *yp0);
    s->tn = t0;
    s->first = 1;
    s->hh = 0;
    s->hused = 0;
    s->kused = 0;
    s->kk = 1;
    s->ibk = 0;
    while (s->ibk < s->nbkpt && s->bkpt[s->ibk] <= t0)
        s->ibk++;
    s->root_pending = 0;
    s->restart_pending = 0;
    s->nautorestart = 0;
    s->ncrawl = 0;
    s->fail_note[0] = '\0';
    s->dn0_last = HUGE_VAL;
    s->t_fail = NAN;
    s->init_side = 0;
    daei_stab_reset(s);
    s->tlo = t0;
    s->need_setup = 1;
    s->initialized = 1;
    s->failed = 0;
    s->note[0] = '\0';
    bg_error_clear(&s->err);
    bg_error_clear(&s->warn);
    if (s->p.nroots > 0) {
        int r = daei_call_roots(s, "dae_init", t0, y0, s->phi[1], s->glo);
        if (r != BG_OK) return r;
    }
    return BG_OK;
}

int dae_reinit(dae_solver *s, double t, const double *y, const double *yp)
{
    if (!s) return BG_ERR_ARGUMENT;
    dae_stats keep = s->st;
    int r = dae_init(s, t, y, yp);
    if (r == BG_OK) s->st = keep;
    return r;
}

int dae_set_history(dae_solver *s, double t0, double h, int k, const double *Y)
{
    int kmax = s && s->o.method == DAE_MEBDF ? MAXORD : BDF_MAXORD;
    if (!s || !Y || k < 1 || k > kmax || !(h > 0))
        return s ? bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_set_history",
                                  "needs 1 <= k <= %d and h > 0 (k = %d, h = %g)", kmax, k, h)
                 : BG_ERR_ARGUMENT;
    int n = s->n;
    for (size_t i = 0; i < (size_t)(k + 1) * n; i++)
        if (!isfinite(Y[i]))
            return bg_error_raise(&s->err, BG_ERR_NONFINITE, "dae_set_history",
                                  "history value %zu (y(t0 - %zu h) of unknown %zu) is not finite",
                                  i, i / (size_t)n, i % (size_t)n);
    int r = dae_init(s, t0, Y, NULL);
    if (r != BG_OK) return r;
    /* at constant step the modified divided differences are backward differences:
     * phi_j = nabla^j y_n */
    for (int j = 0; j <= k; j++) {
        for (int i = 0; i < n; i++) {
            double d = 0, c = 1; /* sum_m (-1)^m C(j,m) y_{n-m} */
            for (int m = 0; m <= j; m++) {
                d += c * Y[(size_t)m * n + i];
                c = -c * (double)(j - m) / (double)(m + 1);
            }
            s->phi[j][i] = d;
        }
    }
    for (int j = 0; j <= MAXORD; j++)
        s->psi[j] = (j + 1) * h;
    s->hh = h;
    s->hused = h;
    s->kk = k;
    s->kused = k;
    s->ns = 0; /* the first set_coeffs computes the (constant-step) coefficients */
    s->phase = 1;
    s->first = 0;
    s->o.h_init = h;
    s->o.max_order = k;
    return BG_OK;
}

static int advance_run(dae_solver *s, double tout, double *tret, double *y, double *yp, int one)
{
    const char *w = "dae_solve_to";
    if (!isfinite(tout))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w, "tout = %g is not finite", tout);
    if (s->first) {
        if (tout == s->tn) {
            daei_output_state(s, s->tn, tret, y, yp);
            return DAE_SUCCESS;
        }
        double dir0 = tout >= s->tn ? 1.0 : -1.0;
        if (s->o.has_t_stop && (s->o.t_stop - s->tn) * dir0 < 0)
            return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w,
                                  "t_stop = %.17g lies behind the start t = %.17g in the direction "
                                  "of tout = %.17g: the integration could never stop there",
                                  s->o.t_stop, s->tn, tout);
        int r = daei_first_step(s, tout, 0, 0);
        if (r != BG_OK) return r;
    }
    double dir = s->hh >= 0 ? 1.0 : -1.0;
    if (!one && (tout - (s->tn - s->hused)) * dir < 0 && !s->root_pending)
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w,
                              "tout = %g lies behind the last step [%g, %g]", tout,
                              s->tn - s->hused, s->tn);
    for (long nsteps = 0;; nsteps++) {
        if (s->root_pending && (s->troot - tout) * dir <= 0) {
            s->root_pending = 0;
            daei_output_state(s, s->troot, tret, y, yp);
            return DAE_ROOT_RETURN;
        }
        if (!one && (s->tn - tout) * dir >= 0) {
            daei_output_state(s, tout, tret, y, yp);
            return DAE_SUCCESS;
        }
        if (s->o.has_t_stop && s->tn == s->o.t_stop) {
            daei_output_state(s, s->tn, tret, y, yp);
            return DAE_TSTOP_RETURN;
        }
        if (one && nsteps == 1) {
            daei_output_state(s, s->tn, tret, y, yp);
            return DAE_SUCCESS;
        }
        if (nsteps >= s->o.max_steps) {
            daei_output_state(s, s->tn, tret, y, yp);
            return bg_error_raise(&s->err, DAE_TOO_MUCH_WORK, w,
                                  "%ld steps taken before reaching tout = %g (t = %g)", nsteps,
                                  tout, s->tn);
        }
        if (s->restart_pending) {
            s->restart_pending = 0;
            int rr = daei_restart(s, tout, 0, 0);
            if (rr != BG_OK) {
                daei_output_state(s, s->tn, tret, y, yp);
                return rr;
            }
        }
        int r = daei_step(s);
        daei_sync_stats(s);
        if (r < 0) {
            daei_output_state(s, s->tn, tret, y, yp);
            return r;
        }
        if (r == STEP_JUMP) { /* an unannounced jump at tn: restart there (no step was taken) */
            r = daei_restart_at_jump(s, tout, dir, one, tret, y, yp);
            if (r <= 0) return r; /* tout reached before the restart point, or a failure */
            nsteps--;
            continue;
        }
        int rp = 0; /* r says whether the step landed on a breakpoint: kept */
        if (s->p.cons && s->p.ncons > 0 && (rp = daei_project_step(s)) < 0) {
            daei_output_state(s, s->tn, tret, y, yp);
            return rp;
        }
        if (r == STEP_ON_BREAKPOINT) { /* landed on a breakpoint: restart before the next step
                         (which may be in the next call, when tout is the breakpoint itself) */
            s->ibk++;
            if (s->p.nroots > 0 && (r = daei_find_root(s)) < 0) {
                daei_output_state(s, s->tn, tret, y, yp);
                return r;
            }
            s->restart_pending = 1;
            continue;
        }
        if (s->p.nroots > 0 && (r = daei_find_root(s)) < 0) {
            daei_output_state(s, s->tn, tret, y, yp);
            return r;
        }
    }
}

/* advance_run behind the checks of the call order; a failure stops the integration until
 * dae_init or dae_reinit (DAE_TOO_MUCH_WORK and argument errors do not). */
static int advance(dae_solver *s, double tout, double *tret, double *y, double *yp, int one)
{
    const char *w = one ? "dae_step" : "dae_solve_to";
    if (!s) return BG_ERR_ARGUMENT;
    if (!tret) return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w, "tret is NULL");
    if (!s->initialized)
        return bg_error_raise(&s->err, BG_ERR_STATE, w, "call dae_init before integrating");
    if (s->failed)
        return bg_error_raise(&s->err, BG_ERR_STATE, w,
                              "the integration stopped with %s at t = %.17g: call dae_reinit (or "
                              "dae_init) before integrating again",
                              dae_return_name(s->failed), s->tn);
    if (s->busy)
        return bg_error_raise(&s->err, BG_ERR_STATE, w,
                              "called from within a callback of the same solver (its residual, "
                              "Jacobian, constraint or root function): the solver is not "
                              "re-entrant; use a second solver for a nested integration");
    s->busy = 1;
    int r = advance_run(s, tout, tret, y, yp, one);
    s->busy = 0;
    if (r < 0 && r != DAE_TOO_MUCH_WORK && r != BG_ERR_ARGUMENT) s->failed = r;
    return r;
}

int dae_solve_to(dae_solver *s, double tout, double *tret, double *y, double *yp)
{
    return advance(s, tout, tret, y, yp, 0);
}

int dae_step(dae_solver *s, double tout, double *tret, double *y, double *yp)
{
    return advance(s, tout, tret, y, yp, 1);
}
