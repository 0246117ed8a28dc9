/* The Newton corrector of the integrator: a modified Newton iteration on
 *     G(y) = F(t_n, y, y_pred' + cj (y - y_pred)) = 0,  cj = alpha_s / h,
 * with the iteration matrix M = dF/dy + cj dF/dy' kept across steps while cj stays within
 * [0.6, 1.67] of the value it was factored with (corrections rescaled by 2/(1 + cj/cj_f)),
 * refreshed after a convergence failure, and refactored by KLU with the symbolic analysis reused.
 * With options.newton_dgmax > 0, the matrix between Jacobians follows cj: when gamma = 1/cj has
 * moved by more than newton_dgmax from the gamma it was factored with, M is formed again from
 * the saved Jacobian at the new cj and refactored, without evaluating the Jacobian (CVODE's rule,
 * dgmax 0.3 there: A. C. Hindmarsh et al., ACM TOMS 31 (2005) 363-396, and CVODE's
 * CVodeSetDeltaGammaMaxLSetup); the Jacobian itself is still evaluated when cj leaves
 * [0.6, 1.67] of the cj it was evaluated at, or after a convergence failure. With
 * options.newton_jac_age = K > 0 as well, the Jacobian is evaluated only after a convergence
 * failure or once K steps were taken since the last evaluation: CVODE's Jacobian-age rule (its
 * msbj, CVodeSetJacEvalFrequency, 51 by default), sound here because the refactorizations keep
 * the matrix within newton_dgmax of the current cj; the Jacobian then follows the state, not
 * the step size. And the rate is not reset when cj changes (below): CVODE keeps its crate from
 * step to step and resets it only when the matrix is formed again (cvNlsLSetup). Caution: a
 * Jacobian kept longer meets more switches of sharp characteristics, and without
 * dae_problem.regimes a modified Newton iteration on a Jacobian from the other side of a switch
 * leaves that switch's equation unsatisfied (bg_dae.h, dae_problem.regimes): give the regimes
 * with it. Off by default.
 * At most max_newton iterations per attempt, or up to twice that on a matrix evaluated at the
 * step itself while the rate (0.5 or better) says it will converge within them
 * (newton_extends).
 *
 * Weights. The convergence norm weighs an index-2 unknown lambda in full by default: its Newton
 * error enters the differential unknowns within the same step (through dF/dlambda) and with them
 * the error estimate, so stopping early on lambda shows up as spurious error-test failures.
 * (Option newton_index2_scale_h scales lambda's weight by |h| instead; on the index-2 pendulum
 * at rtol 1e-10 it took 510 steps against 189 with full weight, bench/ida_compare.)
 * Rate. The convergence-rate estimate is reset (to IDA's cautious 100) whenever cj changes,
 * since a rate measured with one iteration matrix says little about the next; without this the
 * solver accepted one-iteration corrections on a stale rate and the pendulum needed 161 steps
 * instead of 67 at rtol 1e-6. With newton_jac_age > 0 (and so newton_dgmax > 0) the matrix
 * stays within newton_dgmax of the current cj, the rate it was measured with holds, and it is
 * reset (to 20) only when the matrix is formed again. A first correction larger than the last
 * accepted step's has the rate scaled up by the ratio, and one that shows a jump the predictor
 * missed is never accepted on an earlier rate (daei_first_correction_jumps, dae_disc.c).
 * Regimes. With dae_problem.regimes, a Jacobian from another regime of a switching element is
 * not used: the predictor's regimes are compared with the Jacobian's at the start of a step, a
 * converged iterate's at the end of an iteration on an older matrix (bg_dae.h says why).
 * Jacobian check. A matrix formed from a Jacobian evaluated at this step's predictor and
 * factored at this cj differs from the iteration's true derivative G'(y) only through the
 * nonlinearity over the corrections, so the simplified Newton iteration contracts at a rate of
 * the order of the corrections (nearly 0 on a linear problem); a rate that stays large there is
 * what an inaccurate Jacobian shows (Hairer and Wanner, Solving Ordinary Differential Equations
 * II, 2nd ed., Springer 1996, sec. IV.8: the contraction factor Theta measures the quality of
 * the Jacobian; RADAU5 evaluates a new one when Theta > 0.001). With an analytic Jacobian, the
 * first rate above RATE_SUSPECT on such a matrix has the next Jacobian compared once with
 * central differences of the residual (options.check_jacobian = 0, the default, up to
 * CHECK_AUTO_N unknowns: 2n residual evaluations once); a disagreement is a warning naming
 * the entry and that rate. Large corrections (a jump, a switch) also contract slowly on an
 * exact Jacobian: the check then agrees and nothing is said. Measured: a stiff 2 x 2 system
 * with dF0/dy0 three times too large contracts at 0.50 to 0.66, the correct Jacobian at 1e-9;
 * the IVP Test Set's pump, whose corrections at its restarts are 1e7 tolerances, at up to 0.8
 * with its correct Jacobian.
 * Conditioning. The unscaled M has rows of size cj ~ 1/h (rows containing y') and rows of size 1
 * (constraints), and its condition grows like h^-2. We factor R M C instead, with R = h/alpha on
 * rows that contain y' and 1 elsewhere, C = cj on index-2 columns and 1 elsewhere; every block is
 * then O(1). The solution is mapped back by delta = C z. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

#define RATE_MAX 0.9
#define RATE_EXTEND 0.5  /* the Newton iteration may go past max_newton ... */
#define NEWTON_EXTEND 2  /* ... up to this many times max_newton iterations */
#define RATE_SUSPECT 0.1 /* a rate on a Jacobian of this step that calls for the check ... */
#define CHECK_AUTO_N 500 /* ... of problems of at most this many unknowns */

enum { SU_OK = 0, SU_RECOVER = 1, SU_SINGULAR = 2, SU_LSFAIL = 3 };

/* The problem's regimes at (t, y) into s->reg_now: 0 as they were at the last Jacobian, 1
 * changed (or no Jacobian yet), < 0 the callback's fatal status. */
static int regimes_changed(dae_solver *s, double t, const double *y)
{
    int r = daei_call_regimes(s, t, y, s->reg_now);
    if (r < 0) return r;
    return !s->reg_valid ||
           memcmp(s->reg_now, s->reg_jac, (size_t)s->p.nregimes * sizeof *s->reg_now) != 0;
}

/* Jacobian, scaled Newton matrix, factorization: SU_*, or the fatal (< 0) status of a callback.
 * A failure is described in s->note. */
static int setup(dae_solver *s, double t, const double *F, int saved_jac)
{
    int r = saved_jac ? 0 : daei_eval_jac(s, t, s->y, s->yp, F);
    if (r < 0) return r;
    if (r > 0) return SU_RECOVER;
    double t0 = daei_clock(s);
    double cj = s->cj;
    sp_union_combine(s->U, s->Jy, 1.0, s->Jyp, cj);
    sp_csc *M = s->U->M;
    for (int j = 0; j < s->n; j++) {
        double cs = s->kind[j] == DAE_ALG2 ? cj : 1.0;
        for (int p = M->colptr[j]; p < M->colptr[j + 1]; p++)
            M->val[p] *= cs * (s->rowscaled[M->rowind[p]] ? 1.0 / cj : 1.0);
    }
    r = ls_factor(s->ls, M);
    s->st.t_linalg += daei_clock(s) - t0;
    if (r == BG_OK) s->st.rcond_min = fmin(s->st.rcond_min, ls_get_stats(s->ls)->rcond);
    s->cjf = cj;
    if (!saved_jac) {
        s->cjj = cj;
        s->jac_nst = s->st.steps;
    }
    s->jac_current = !saved_jac;
    s->need_setup = 0;
    s->need_refactor = 0;
    s->ss = 20.0;
    if (r == BG_OK) return SU_OK;
    if (r == BG_ERR_SINGULAR) {
        char nb[32];
        int c = ls_singular_col(s->ls);
        daei_note(s,
                  "the Newton matrix is singular at t = %.17g: nothing determines %s (column %d; "
                  "%s)",
                  t, daei_vname(s, c, nb, sizeof nb), c, ls_get_error(s->ls)->message);
        return SU_SINGULAR;
    }
    daei_note(s, "the Newton matrix could not be factored at t = %.17g: %s", t,
              ls_get_error(s->ls)->message);
    return r == BG_ERR_NONFINITE ? SU_RECOVER : SU_LSFAIL;
}

/* delta = M^-1 F with the scaling of the factored matrix. */
static int lsolve(dae_solver *s, double *v)
{
    double t0 = daei_clock(s);
    double cj = s->cjf, rcj = 1.0 / cj;
    for (int k = 0; k < s->nsrows; k++)
        v[s->srows[k]] *= rcj;
    int r = ls_solve(s->ls, v, 1);
    for (int k = 0; k < s->na2; k++)
        v[s->a2cols[k]] *= cj;
    if (s->cj != cj) {
        double f = 2.0 / (1.0 + s->cj / cj);
        for (int j = 0; j < s->n; j++)
            v[j] *= f;
    }
    s->st.linear_solves++;
    s->st.t_linalg += daei_clock(s) - t0;
    return r;
}

/* Describes a Newton failure by the unknown with the largest weighted correction. */
static void note_newton(dae_solver *s, double t, double rate)
{
    char nb[32];
    int i = daei_largest_weighted(s, s->delta, s->wnewt);
    if (i < 0) {
        daei_note(s, "the Newton iteration did not converge at t = %.17g", t);
        return;
    }
    daei_note(s,
              "the Newton iteration did not converge at t = %.17g (rate %.3g): the largest "
              "weighted correction is in %s (%.3g against the tolerance %.3g)",
              t, rate, daei_vname(s, i, nb, sizeof nb), fabs(s->delta[i]), 1.0 / s->wnewt[i]);
}

/* Whether the iteration goes on past max_newton after iteration m (0-based) with correction
 * norm dn at rate: only on a Newton matrix evaluated at this step (a stale one is refreshed
 * instead, at the same h), while it contracts at RATE_EXTEND or better, and while the rate says
 * it will pass the test within NEWTON_EXTEND * max_newton iterations in all. Failing there
 * instead cuts the step by 4. Where the predictor misses the index-2 unknowns by hundreds of
 * tolerances (the reactions of large flexible structures), a converging iteration needs 5 or 6
 * iterations at rates of 0.2 to 0.4, and cutting its steps costs more Jacobians and more time
 * per step than letting it finish. */
static int newton_extends(const dae_solver *s, int m, double dn, double rate)
{
    if (!s->jac_current || m < 1 || !(rate <= RATE_EXTEND) || rate <= 0) return 0;
    double need = ceil(log(EPS_NEWT / (s->ss * dn)) / log(rate));
    return m + 1 + need <= NEWTON_EXTEND * s->o.max_newton;
}

/* The end of a converged iteration: NL_OK, or NL_RECOVER when it ran on a matrix from an earlier
 * step whose Jacobian belongs to other regimes than the iterate (the caller then evaluates a
 * fresh Jacobian and redoes the step), or a fatal status. */
static int converged(dae_solver *s, double t)
{
    if (s->p.nregimes == 0 || s->jac_current) return NL_OK;
    int rc = regimes_changed(s, t, s->y);
    if (rc <= 0) return rc < 0 ? rc : NL_OK;
    s->st.jac_regime++;
    daei_note(s,
              "the Newton iteration at t = %.17g converged on a matrix from an earlier step "
              "whose Jacobian was evaluated in another regime of a switching element",
              t);
    return NL_RECOVER;
}

/* The update y -= delta, yp -= cj delta, ee -= delta (ee = 0 - delta on the first iteration,
 * first: the sum starts there, as from zero) and the weighted norms of the correction (all
 * unknowns; without the index-2 ones) in one pass; first constant where it is inlined. */
DAEI_INLINE void update(int first, int n, double cj, const double *restrict d,
                        const double *restrict w, const double *restrict wd, double *restrict y,
                        double *restrict yp, double *restrict ee, double *dn, double *dn_diff)
{
    double q0 = 0, q1 = 0, r0 = 0, r1 = 0;
    int i = 0;
#if defined(__GNUC__)
    /* the pairs below as two-lane vectors, lane l summing the unknowns i = l (mod 2) as q0/q1
     * and r0/r1 do: the same operations in the same order, the same bits */
    typedef double v2 __attribute__((vector_size(2 * sizeof(double))));
    v2 q = {0, 0}, r = {0, 0}, vcj = {cj, cj}, zero = {0, 0};
    for (; i + 2 <= n; i += 2) {
        v2 dv, wv, wdv, yv, ypv, ev;
        memcpy(&dv, d + i, sizeof dv);
        memcpy(&wv, w + i, sizeof wv);
        memcpy(&wdv, wd + i, sizeof wdv);
        memcpy(&yv, y + i, sizeof yv);
        memcpy(&ypv, yp + i, sizeof ypv);
        if (first)
            ev = zero;
        else
            memcpy(&ev, ee + i, sizeof ev);
        v2 a = dv * wv, b = dv * wdv;
        q += a * a;
        r += b * b;
        yv -= dv;
        ypv -= vcj * dv;
        ev -= dv;
        memcpy(y + i, &yv, sizeof yv);
        memcpy(yp + i, &ypv, sizeof ypv);
        memcpy(ee + i, &ev, sizeof ev);
    }
    q0 = q[0], q1 = q[1], r0 = r[0], r1 = r[1];
#endif
    for (; i + 2 <= n; i += 2) {
        double a0 = d[i] * w[i], a1 = d[i + 1] * w[i + 1];
        double b0 = d[i] * wd[i], b1 = d[i + 1] * wd[i + 1];
        q0 += a0 * a0;
        q1 += a1 * a1;
        r0 += b0 * b0;
        r1 += b1 * b1;
        y[i] -= d[i];
        y[i + 1] -= d[i + 1];
        yp[i] -= cj * d[i];
        yp[i + 1] -= cj * d[i + 1];
        ee[i] = (first ? 0.0 : ee[i]) - d[i];
        ee[i + 1] = (first ? 0.0 : ee[i + 1]) - d[i + 1];
    }
    for (; i < n; i++) {
        double a0 = d[i] * w[i], b0 = d[i] * wd[i];
        q0 += a0 * a0;
        r0 += b0 * b0;
        y[i] -= d[i];
        yp[i] -= cj * d[i];
        ee[i] = (first ? 0.0 : ee[i]) - d[i];
    }
    double nn = n > 0 ? n : 1;
    *dn = sqrt((q0 + q1) / nn);
    *dn_diff = sqrt((r0 + r1) / nn);
}

/* daei_newton's iteration; *updated is set once the first correction is in y, yp and ee. */
static int newton_iterate(dae_solver *s, double t, int *updated)
{
    int n = s->n;
    double ratio = s->cj / (s->cjj != 0 ? s->cjj : s->cj);
    int old_jac = s->o.newton_jac_age > 0 ? s->st.steps - s->jac_nst >= s->o.newton_jac_age
                                          : ratio < CJ_LOW || ratio > CJ_HIGH;
    if (s->reg_valid && !s->first && !old_jac && !s->need_setup) { /* a switch since it */
        int rc = regimes_changed(s, t, s->y);
        if (rc < 0) return rc;
        if (rc) {
            old_jac = 1;
            s->st.jac_regime++;
        }
    }
    if (s->first || old_jac)
        s->need_setup = 1;
    else if (s->o.newton_dgmax > 0 && fabs(s->cjf / s->cj - 1) > s->o.newton_dgmax)
        s->need_refactor = 1;
    /* a rate measured at another cj says little about this one: start cautious, unless the
     * matrix follows cj and the Jacobian goes by age (newton_jac_age), where the rate holds
     * until the next setup (CVODE) */
    if (s->cj != s->cjold && !(s->o.newton_jac_age > 0)) s->ss = 100.0;
    s->jac_current = 0;
    double oldnrm = 0, rate = 0;
    for (int m = 0;; m++) {
        int r = daei_call_res(s, t, s->y, s->yp, s->res, 0);
        if (r < 0) return r;
        if (r > 0) return NL_RES_RECOVER;
        if (s->need_setup || s->need_refactor) {
            r = setup(s, t, s->res, !s->need_setup);
            if (r < 0) return r;
            if (r == SU_SINGULAR) return NL_SINGULAR;
            if (r == SU_LSFAIL) return NL_LSFAIL;
            if (r == SU_RECOVER) return NL_RES_RECOVER;
        }
        { /* the residual becomes the right-hand side in place: swap the arrays */
            double *sw = s->delta;
            s->delta = s->res;
            s->res = sw;
        }
        if (lsolve(s, s->delta) != BG_OK) {
            daei_note(s, "the linear solve failed at t = %.17g: %s", t,
                      ls_get_error(s->ls)->message);
            return NL_LSFAIL;
        }
        s->st.newton_iters++;
        double dn, dn_diff;
        if (m == 0)
            update(1, n, s->cj, s->delta, s->wnewt, s->wdiff, s->y, s->yp, s->ee, &dn, &dn_diff);
        else
            update(0, n, s->cj, s->delta, s->wnewt, s->wdiff, s->y, s->yp, s->ee, &dn, &dn_diff);
        *updated = 1;
        if (!isfinite(dn)) {
            char nb[32];
            int i = daei_first_nonfinite(s->delta, n);
            daei_note(s, "the Newton correction of %s is %g at t = %.17g",
                      daei_vname(s, i, nb, sizeof nb), i >= 0 ? s->delta[i] : dn, t);
            return NL_RES_RECOVER;
        }
        if (m == 0) {
            oldnrm = dn;
            if (dn <= 1e-4 * EPS_NEWT) return converged(s, t);
        } else {
            /* Round-off floor of index-2 unknowns: their corrections carry the rounding errors
             * of the other unknowns amplified by about 1/h^2, so at very small steps they stop
             * decreasing while everything else has converged. Once the corrections of the
             * differential and index-1 unknowns are far below the tolerance, accept: below
             * 1e-6 of it, or at ten times their own rounding (eps |y| against rtol |y|, so
             * 2.2e-5 of the tolerance at rtol 1e-10), which no iteration goes under. The
             * latter lets the crank of the IVP Test Set start at rtol 1e-10 and 1e-11: its
             * steps of 1e-12 s left the multipliers' corrections 1e4 tolerances large while the
             * positions' and velocities' stayed at 2e-6, their round-off, and the steps
             * collapsed at t = 4.5e-12. A fixed floor of 3e-5 instead (10 eps / rtol at rtol
             * 1e-10 and above it at 1e-8) accepts unconverged iterations at 1e-8, and the drift
             * of the position constraints grows with them. With rtol = 0 (atol alone)
             * the rounding has no bound relative to the tolerance: 1e-6; and at most 1e-2. */
            double floor_diff =
                s->o.rtol > 0 ? fmin(1e-2, fmax(1e-6, 10 * DBL_EPSILON / s->o.rtol)) : 1e-6;
            if (s->has_alg2 && dn_diff <= floor_diff) return converged(s, t);
            rate = pow(dn / oldnrm, 1.0 / m);
            if (rate > RATE_SUSPECT && s->jac_current && s->cjf == s->cj && s->p.jac &&
                s->o.check_jacobian == 0 && !s->jac_checked && !(s->jac_suspect_rate > 0) &&
                n <= CHECK_AUTO_N) {
                s->jac_suspect_rate = rate; /* the next Jacobian is checked (dae_eval.c) */
                s->jac_suspect_t = t;
            }
            if (rate > RATE_MAX) {
                note_newton(s, t, rate);
                return NL_RECOVER;
            }
            s->ss = rate / (1.0 - rate);
        }
        /* The first iteration is accepted on the rate of earlier ones only as far as that rate
         * applies: the nonlinear part of the contraction grows with the size of the correction,
         * so a first correction larger than the last accepted step's (the predictor missed a
         * jump of an algebraic unknown, e.g. a saturated controller that switches inside the
         * step) has the rate scaled up by the ratio, and usually takes another iteration.
         * Without this, a step over a switch was accepted with the algebraic unknowns of the
         * predictor, out of the error test (exclude_alg), and the run went on silently wrong. */
        if (m == 0) s->dn0 = dn;
        double ssm = m == 0 ? s->ss * fmax(1.0, dn / s->dn0_last) : s->ss;
        if (ssm * dn <= EPS_NEWT && (m > 0 || !daei_first_correction_jumps(s, dn)))
            return converged(s, t);
        if (m + 1 >= s->o.max_newton && !newton_extends(s, m, dn, rate)) break;
    }
    note_newton(s, t, rate);
    return NL_RECOVER;
}

int daei_newton(dae_solver *s, double t)
{
    /* y and yp start at the predictor (predict); ee accumulates the corrections, which keep
     * their own digits. Formed as y - ypred after the iteration instead, it carries the
     * rounding of every update of y (eps |y|) into the history, which on stiff structures is
     * not small against the corrections: the iteration then stalls at rate 1 on the stiffest
     * efforts and the steps collapse. The first update starts ee (update); an iteration that
     * stops before it leaves ee = 0 */
    int updated = 0;
    int r = newton_iterate(s, t, &updated);
    if (!updated) memset(s->ee, 0, (size_t)s->n * sizeof(double));
    return r;
}
