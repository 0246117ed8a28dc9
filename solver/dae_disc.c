/* Discontinuities: the rules by which the integrator meets inputs that jump and switches in the
 * model, each documented once here.
 *
 * Breakpoints (options.breakpoints). Steps are clipped to land exactly on each breakpoint
 * (dae_step.c); the step that lands sees the inputs' left-hand values there, and the method
 * restarts at order 1 from consistent right-hand values (daei_restart).
 *
 * Unannounced jumps (daei_jump_suspected, daei_restart_at_jump). The Newton iteration failed down
 * to the smallest step with the error test never failing: the signature of an input that jumps
 * at tn (a source or a reference that is not given as a breakpoint), which leaves the algebraic
 * unknowns and y' of the history inconsistent on the far side. The same when the last Newton
 * failure ended within JUMP_WINDOW round-off steps of tn: the accepted steps closed in on a point
 * that no step crosses, each step halfway there, until the error test failed on round-off (the
 * IVP Test Set's pump, where a transistor switches off and its charge stops depending on the
 * voltages: it stopped at 1079.9 ns at rtol 1e-10 and 2.8e-11 without the second condition).
 * The solver restarts once, as at a breakpoint, at the end of the last failed step (past the
 * jump, a few units of round-off further on): right-hand consistent values, order 1. The step
 * collapsing again, with no step accepted since, stops the run.
 *
 * Crawl (daei_crawl_check). CRAWL_STEPS accepted steps in a row, each within CRAWL_FACTOR of the
 * round-off limit of t, the steps in between failing: a switch in the model that no step
 * crosses. It would otherwise go on until max_steps or the caller's patience; the run stops
 * with DAE_STEP_TOO_SMALL and a message that names the last Newton failure.
 *
 * First correction (daei_first_correction_jumps). A step is never accepted with algebraic
 * unknowns left at the predictor's values across a jump inside the step: see the function. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae_impl.h"

#define CRAWL_FACTOR 100.0
#define CRAWL_STEPS 200
#define JUMP_WINDOW 1000.0  /* a Newton failure this many round-off steps from tn marks a jump */
#define MAX_AUTO_RESTARTS 1 /* restarts at an unannounced jump before a step is accepted */
/* a first correction of an algebraic unknown larger than JUMP_TOLS tolerances, JUMP_CHANGE times
 * its change over the last step and half its size takes another iteration */
#define JUMP_TOLS 100.0
#define JUMP_CHANGE 5.0

/* Whether the first correction moved an index-1 algebraic unknown by more than half its size,
 * by more than JUMP_TOLS of its tolerances and by more than JUMP_CHANGE times its change over
 * the last step (phi[1]): the predictor missed a jump (an input that switched inside the step),
 * and the linearisation at the predictor says little about where the unknowns that depend on
 * it go. The chain that makes this matter: a reference acceleration jumps, the Newton matrix of
 * a saturated controller has d(out)/d(in) = 0, the first correction moves the input and leaves
 * the output at the predictor's value; the rate of earlier steps (tiny while the controller
 * saturates) then accepts the step with the controller on the wrong side, out of the error
 * test (exclude_alg), and the run goes on silently wrong, by far more than the tolerance.
 * Another iteration evaluates the residual where the first one went and measures the rate
 * there. The last condition keeps unknowns that the steps do not resolve out: beam efforts near
 * zero that the predictor misses by about their change per step (on long beam chains, without
 * it, the rule fires at a large share of the steps and costs Newton iterations); a source that
 * jumps after constant or slowly varying values has a change per step far below the jump. */
int daei_first_correction_jumps(const dae_solver *s, double dn)
{
    /* The first condition bounded by the correction's norm: dn^2 n is, up to a few roundings,
     * the sum of the squares of the weighted corrections, those of the index-1 unknowns among
     * them with the weights ewt used here (the Newton weights differ from ewt on index-2
     * unknowns only), and a rounded sum of nonnegative terms is at least each of them. Where
     * dn^2 n is below 0.99 JUMP_TOLS^2, no index-1 unknown passes the first condition: the
     * answer is 0 without the loop (the margin covers the roundings; a NaN dn takes the loop) */
    if (dn * dn * (double)s->n < 0.99 * JUMP_TOLS * JUMP_TOLS) return 0;
    const double *restrict y = s->y, *restrict ee = s->ee, *restrict w = s->ewt,
                           *restrict p1 = s->phi[1];
    for (int k = 0; k < s->na1; k++) {
        int i = s->a1cols[k];
        double d = fabs(ee[i]); /* after one iteration: the correction */
        if (d * w[i] > JUMP_TOLS && d > 0.5 * fmax(fabs(y[i]), fabs(y[i] - ee[i])) &&
            d > JUMP_CHANGE * fabs(p1[i]))
            return 1;
    }
    return 0;
}

void daei_disc_accepted(dae_solver *s)
{
    s->nautorestart = 0;
    s->ncrawl = fabs(s->hh) < CRAWL_FACTOR * daei_roundoff_h(s) ? s->ncrawl + 1 : 0;
}

int daei_crawl_check(dae_solver *s)
{
    if (s->ncrawl < CRAWL_STEPS) return BG_OK;
    return bg_error_raise(&s->err, DAE_STEP_TOO_SMALL, "dae_solve_to",
                          "the step size stayed below %g times the round-off limit of t for %d "
                          "steps at t = %.17g (h = %.3g, %ld Newton and %ld error-test "
                          "failures so far): the solution cannot pass this point (a switch or "
                          "a singularity of the model)%s%.200s",
                          CRAWL_FACTOR, CRAWL_STEPS, s->tn, s->hused, s->st.newton_fails,
                          s->st.rejected_error, s->fail_note[0] ? "; the last Newton failure: " : "",
                          s->fail_note);
}

int daei_jump_suspected(const dae_solver *s, int nef, int ncf)
{
    return s->hused != 0 && s->nautorestart < MAX_AUTO_RESTARTS &&
           ((ncf > 0 && nef == 0) || fabs(s->t_fail - s->tn) <= JUMP_WINDOW * daei_roundoff_h(s));
}

/* Restart at a breakpoint: left value of y, consistent right value of y', order 1. The first
 * step after a breakpoint is sized from y'' just before it (differenced from the interpolant over
 * the last half step): the local error of the order-1 restart is about h^2/2 |y''|, so
 * h = 0.5 sqrt(2 / |y''|) in the error norm, at most the last step. Far larger than IDA's
 * first-step rule, which would restart from h ~ 0.5/|y'| and double up again.
 * jump: a restart at an unannounced jump, made at tn + dt, past a jump that lies within a few
 * units of round-off of tn, with y carried there along y' (a change far below the tolerances).
 * The steps before it collapsed onto the jump, so neither the last step nor y'' from it says
 * anything about the step after: that one follows IDA's first-step rule on the new y' (y changes
 * by half a tolerance unit). Capped by the collapsed step instead, it fell below the step
 * floor at once on the IVP Test Set's pump with atol = 1e-2 rtol: every rtol from 1e-6 to 2e-8
 * stopped with DAE_STEP_TOO_SMALL at 119.9 to 890.1 ns. */
int daei_restart(dae_solver *s, double tout, double dt, int jump)
{
    double hprev = fabs(s->hused), hpref = hprev, dir = s->hused >= 0 ? 1.0 : -1.0;
    double hm = 0.5 * s->hused;
    dae_dense(s, s->tn, s->y, s->yp);
    if (!jump && dae_dense(s, s->tn - hm, NULL, s->tmp) == BG_OK) {
        for (int i = 0; i < s->n; i++)
            s->tmp[i] = (s->yp[i] - s->tmp[i]) / hm;
        s->hh = 0;
        daei_set_weights(s, s->y);
        double ypp = daei_wrms(s, s->tmp, s->werr);
        if (ypp > 0) hpref = fmin(hprev, 0.5 * sqrt(2.0 / ypp));
    }
    if (dt != 0) {
        for (int i = 0; i < s->n; i++)
            if (s->kind[i] == DAE_DIFF) s->y[i] += dt * s->yp[i];
        s->tn += dt;
    }
    memcpy(s->phi[0], s->y, (size_t)s->n * sizeof(double));
    memcpy(s->phi[1], s->yp, (size_t)s->n * sizeof(double));
    double keep = s->st.init_residual;
    s->init_side = s->hused >= 0 ? 1 : -1; /* the right-hand values past the breakpoint */
    int r = daei_consistent_init(s);
    s->init_side = 0;
    s->st.init_residual = keep;
    if (r != BG_OK) return r;
    if (jump) {
        double ypn = daei_wrms(s, s->phi[1], s->werr);
        if (ypn > 0) hpref = 0.5 / ypn;
    }
    s->first = 1;
    return daei_first_step(s, tout, hpref, dir);
}

int daei_restart_at_jump(dae_solver *s, double tout, double dir, int one, double *tret,
                         double *y, double *yp)
{
    char keep[sizeof s->note];
    snprintf(keep, sizeof keep, "%s", s->note);
    /* past the jump (the end of the last failed step), never behind tn (a stale failure). A
     * tout in (tn, tn + dt] gets the values before the restart, the history extrapolated by
     * less than dt: its left-hand values */
    double dt = (s->t_fail - s->tn) * dir > 0 ? s->t_fail - s->tn : 0.0;
    int out_here = !one && (s->tn + dt - tout) * dir >= 0;
    if (out_here) {
        daei_interpolate(s, tout, y, yp);
        if (y && s->o.projection) daei_project_vec(s, tout, y);
    }
    int rr = daei_restart(s, tout, dt, 1);
    if (rr != BG_OK) {
        daei_output_state(s, s->tn, tret, y, yp);
        char m[BG_MESSAGE_SIZE];
        snprintf(m, sizeof m, "%s", s->err.message);
        return bg_error_raise(&s->err, DAE_STEP_TOO_SMALL, "dae_solve_to",
                              "the step size collapsed at t = %.17g with the Newton iteration "
                              "failing (%.200s), and a restart there with consistent values (as "
                              "at a breakpoint) failed too: %.300s",
                              s->tn, keep, m);
    }
    s->st.restarts++;
    s->st.t_last_restart = s->tn;
    s->nautorestart++;
    if (out_here) {
        *tret = tout;
        return DAE_SUCCESS;
    }
    return 1;
}
