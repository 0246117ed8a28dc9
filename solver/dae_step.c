/* One step of the integrator: variable-order, variable-step BDF in fixed-leading-coefficient
 * form with the history kept as modified divided differences phi[0..k+1], as in DASSL and IDA
 * (Brenan, Campbell and Petzold 1996, sec. 5.2-5.3; IDA's published algorithm, Hindmarsh et al.,
 * "SUNDIALS: Suite of nonlinear and differential/algebraic equation solvers", ACM TOMS 2005).
 *
 * daei_step is a retry loop over named parts: the checks before a step (tolerances against
 * round-off, the crawl stop, dae_disc.c), the step floor (check_floor: a step below it stops the
 * run or marks an unannounced jump), coefficients and prediction, the Newton corrector
 * (dae_nls.c), the error test (dae_err.c), and on failure one function, handle_failure, that
 * decides: retry with another h and order, or stop with a status and a message. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae_impl.h"

/* What one call of daei_step has met so far. */
typedef struct step_attempt {
    int nef;           /* error-test failures */
    int ncf;           /* Newton failures (not counting refreshes of a stale Jacobian) */
    int last_res_fail; /* the last failure was the residual's (or the Jacobian's) */
} step_attempt;

enum { RETRY = 1 };

/* ------------------------------------------------------------ BDF machinery ---- */

static void set_coeffs(dae_solver *s)
{
    int k = s->kk;
    if (s->hh != s->hused || k != s->kused) s->ns = 0;
    s->ns = s->ns + 1 < s->kused + 2 ? s->ns + 1 : s->kused + 2;
    if (k + 1 >= s->ns) {
        double temp1 = s->hh;
        s->beta[0] = 1;
        s->alpha[0] = 1;
        s->gamma[0] = 0;
        s->sigma[0] = 1;
        for (int i = 1; i <= k; i++) {
            double temp2 = s->psi[i - 1];
            s->psi[i - 1] = temp1;
            s->beta[i] = s->beta[i - 1] * s->psi[i - 1] / temp2;
            temp1 = temp2 + s->hh;
            s->alpha[i] = s->hh / temp1;
            s->sigma[i] = i * s->sigma[i - 1] * s->alpha[i];
            s->gamma[i] = s->gamma[i - 1] + s->alpha[i - 1] / s->hh;
        }
        s->psi[k] = temp1;
    }
    s->alphas = 0;
    s->alpha0 = 0;
    for (int i = 0; i < k; i++) {
        s->alphas -= 1.0 / (i + 1);
        s->alpha0 -= s->alpha[i];
    }
    s->cjold = s->cj;
    s->cj = -s->alphas / s->hh;
    s->ck = fabs(s->alpha[k] + s->alphas - s->alpha0);
    s->ck = fmax(s->ck, s->alpha[k]);
    /* phi[j] *= beta[j] for j = ns .. k, the history rescaled to the new step, is done by
     * predict as it reads phi[j] */
}

static void restore(dae_solver *s)
{
    for (int j = 1; j <= s->kk; j++)
        s->psi[j - 1] = s->psi[j] - s->hh;
    int n = s->n;
    for (int j = s->ns; j <= s->kk; j++) {
        double *restrict p = s->phi[j], b = s->beta[j];
        DAEI_VFOR(i, n, VAT(p, i) /= b;);
    }
}

/* The prediction's passes over the unknowns, with a difference rescaled to the new step as it
 * is read where sa (sb) is set: phi_j *= beta_j, stored (set_coeffs). Constant flags where
 * inlined: no branch in the loops. */
DAEI_INLINE void pred_first(int n, const double *restrict p0, double *restrict p1, double g1,
                            int sa, double ba, double *restrict y, double *restrict yp)
{
    DAEI_VFOR(i, n, V a = VAT(p1, i);
              if (sa) VAT(p1, i) = a *= ba;
              VAT(y, i) = VAT(p0, i) + a;
              VAT(yp, i) = g1 * a;);
}

DAEI_INLINE void pred_pair(int n, double *restrict pa, double *restrict pb, double ga, double gb,
                           int sa, int sb, double ba, double bb, double *restrict y,
                           double *restrict yp)
{
    DAEI_VFOR(i, n, V a = VAT(pa, i); V b = VAT(pb, i);
              if (sa) VAT(pa, i) = a *= ba;
              if (sb) VAT(pb, i) = b *= bb;
              VAT(y, i) += a + b;
              VAT(yp, i) += ga * a + gb * b;);
}

DAEI_INLINE void pred_one(int n, double *restrict pa, double ga, int sa, double ba,
                          double *restrict y, double *restrict yp)
{
    DAEI_VFOR(i, n, V a = VAT(pa, i);
              if (sa) VAT(pa, i) = a *= ba;
              VAT(y, i) += a;
              VAT(yp, i) += ga * a;);
}

/* y, yp from the history: the predictor, where the Newton iteration starts; y = phi_0 + phi_1 +
 * ... + phi_k and y' = gamma_1 phi_1 + ... + gamma_k phi_k, summed in this order (the
 * differences two at a time: fewer passes over y and y'), with phi_j for j >= ns rescaled to the
 * new step first (set_coeffs). */
static void predict(dae_solver *s)
{
    int n = s->n, k = s->kk, ns = s->ns;
    double *restrict y = s->y, *restrict yp = s->yp, *const *phi = s->phi;
    const double *beta = s->beta, *gamma = s->gamma;
    if (ns <= 1)
        pred_first(n, phi[0], phi[1], gamma[1], 1, beta[1], y, yp);
    else
        pred_first(n, phi[0], phi[1], gamma[1], 0, 1.0, y, yp);
    int j = 2;
    for (; j + 1 <= k; j += 2) {
        double *pa = phi[j], *pb = phi[j + 1], ga = gamma[j], gb = gamma[j + 1];
        if (j >= ns)
            pred_pair(n, pa, pb, ga, gb, 1, 1, beta[j], beta[j + 1], y, yp);
        else if (j + 1 >= ns)
            pred_pair(n, pa, pb, ga, gb, 0, 1, 1.0, beta[j + 1], y, yp);
        else
            pred_pair(n, pa, pb, ga, gb, 0, 0, 1.0, 1.0, y, yp);
    }
    if (j == k) {
        if (j >= ns)
            pred_one(n, phi[j], gamma[j], 1, beta[j], y, yp);
        else
            pred_one(n, phi[j], gamma[j], 0, 1.0, y, yp);
    }
}

/* x += a on distinct arrays */
static void vadd(int n, double *restrict x, const double *restrict a)
{
    DAEI_VFOR(i, n, VAT(x, i) += VAT(a, i););
}

/* a += src, b += a (the new a), and with copy, to = src: one level pair of update_history */
DAEI_INLINE void hist_pair(int copy, int n, double *restrict a, double *restrict b,
                           const double *restrict src, double *restrict to)
{
    DAEI_VFOR(i, n, V e = VAT(src, i);
              if (copy) VAT(to, i) = e;
              V c = VAT(a, i) + e;
              VAT(a, i) = c;
              VAT(b, i) += c;);
}

/* phi after an accepted step of order k = kused: phi[k+1] = ee, phi[k] += ee, then phi[j] +=
 * phi[j+1] for j = k-1 .. 0, two levels per pass over the unknowns (the new phi[j+1] is added
 * to phi[j] while it is at hand; ee copied into phi[k+1] in the first pass). */
static void update_history(dae_solver *s)
{
    int n = s->n, k = s->kused;
    double *const *phi = s->phi;
    if (k < MAXORD) /* k >= 1: the first pair is j = k, k - 1 */
        hist_pair(1, n, phi[k], phi[k - 1], s->ee, phi[k + 1]);
    else
        hist_pair(0, n, phi[k], phi[k - 1], s->ee, NULL);
    int j = k - 2;
    for (; j >= 1; j -= 2) /* phi[j] += phi[j+1]; phi[j-1] += phi[j] */
        hist_pair(0, n, phi[j], phi[j - 1], phi[j + 1], NULL);
    if (j == 0) vadd(n, phi[0], phi[1]);
}

static void complete_step(dae_solver *s)
{
    s->st.steps++;
    s->nst_local++;
    daei_disc_accepted(s);
    s->dn0_last = s->dn0;
    s->since_fail++;
    int kdiff = s->kk - s->kused;
    s->kused = s->kk;
    s->hused = s->hh;
    s->st.steps_at_order[s->kused]++;
    s->st.h_last = s->hh;
    s->st.order_last = s->kused;
    s->st.h_min_used = fmin(s->st.h_min_used, fabs(s->hh));
    s->st.h_max_used = fmax(s->st.h_max_used, fabs(s->hh));
    daei_stab_observe(s);
    if (s->o.method == DAE_MEBDF)
        daei_mebdf_choose_next(s, kdiff);
    else
        daei_choose_next(s, kdiff);
    daei_stab_decide(s);
    update_history(s);
}

/* ------------------------------------------------------------ stops ---- */

double daei_next_stop(const dae_solver *s, double dir, int *is_bkpt)
{
    double ts = NAN;
    *is_bkpt = 0;
    if (dir > 0 && s->ibk < s->nbkpt) {
        ts = s->bkpt[s->ibk];
        *is_bkpt = 1;
    }
    if (s->o.has_t_stop && (s->o.t_stop - s->tn) * dir > 0 &&
        (isnan(ts) || (s->o.t_stop - ts) * dir < 0)) {
        ts = s->o.t_stop;
        *is_bkpt = 0;
    }
    return ts;
}

void daei_clip_to_stop(dae_solver *s)
{
    int isb;
    double ts = daei_next_stop(s, s->hh > 0 ? 1.0 : -1.0, &isb);
    if (!isnan(ts)) {
        if ((s->tn + 1.0001 * s->hh - ts) * s->hh >= 0)
            s->hh = ts - s->tn; /* lands on it */
        else if (!isb && (s->tn + 1.25 * s->hh - ts) * s->hh > 0)
            s->hh = 0.5 * (ts - s->tn); /* two equal steps rather than one and a sliver */
    }
    if (s->o.h_max > 0 && fabs(s->hh) > s->o.h_max) s->hh = copysign(s->o.h_max, s->hh);
}

/* ------------------------------------------------------------ the step ---- */

/* Describes an error-test failure by the unknown with the largest weighted local error. */
static void note_error_test(dae_solver *s, double t)
{
    char nb[32];
    int i = daei_largest_weighted(s, s->ee, s->werr);
    if (i < 0) {
        daei_note(s, "the error test failed at t = %.17g", t);
        return;
    }
    daei_note(s,
              "the error test failed at t = %.17g: the largest weighted local error is in %s "
              "(estimate %.3g against the tolerance %.3g)",
              t, daei_vname(s, i, nb, sizeof nb), s->ck * fabs(s->ee[i]), 1.0 / s->werr[i]);
}

/* Describes what limits a step that is too small although it has not failed: the local error
 * of the last step, or the derivative that sized the first step. */
static void note_step_limit(dae_solver *s)
{
    char nb[32];
    int first = s->nst_local == 0;
    int i = daei_largest_weighted(s, first ? s->phi[1] : s->ee, s->werr);
    if (i < 0) {
        s->note[0] = '\0';
        return;
    }
    if (first)
        daei_note(s, "the first step is sized by the derivative of %s (y' = %.3g, tolerance %.3g)",
                  daei_vname(s, i, nb, sizeof nb), fabs(s->phi[1][i] / s->hh), 1.0 / s->werr[i]);
    else
        daei_note(s,
                  "the step size is limited by the local error of %s (%.3g in the last step, "
                  "tolerance %.3g)",
                  daei_vname(s, i, nb, sizeof nb), s->ck * fabs(s->ee[i]), 1.0 / s->werr[i]);
}

/* What a user can supply when the Newton iteration fails on finite differences. */
static const char *fd_hint(const dae_solver *s)
{
    if (s->p.jac) return "";
    return s->detect ? "; the Jacobian is by finite differences on patterns found from the "
                       "residual: an analytic Jacobian (dae_problem.jac, with its patterns) may "
                       "let the iteration converge"
                     : "; the Jacobian is by finite differences: an analytic one (dae_problem.jac) "
                       "may let the iteration converge";
}

/* What a user can try when the steps collapse on a system with constraints that are not
 * all matched to index-1 algebraic unknowns (index 2): where the index-2 part is not of
 * Hessenberg form, BDF can be unstable on it at every step (bg_dae.h, dae_index2_policy). */
static const char *i2_hint(const dae_solver *s)
{
    if (s->red || s->nalg_rows <= s->na1) return "";
    return "; index 2 not of Hessenberg form (an index-2 unknown in a constraint or "
           "differentiated) can make BDF unstable at every step: try options.index2 = "
           "DAE_I2_REDUCE";
}

/* The checks before a step: h clipped to the next stop, tolerances above round-off, no crawl. */
static int check_before(dae_solver *s)
{
    char nb[32];
    daei_clip_to_stop(s);
    daei_set_weights(s, s->phi[0]);
    /* |y_i| ewt_i <= 1 / rtol, so tolsf <= eps / rtol (times 1 + a few eps): the norm is needed
     * only where rtol < 2 eps */
    double tolsf = s->o.rtol >= 2 * DBL_EPSILON ? 0.0
                                                : DBL_EPSILON * daei_wrms(s, s->phi[0], s->ewt);
    if (tolsf > 1) {
        int i = daei_largest_weighted(s, s->phi[0], s->ewt);
        return bg_error_raise(&s->err, DAE_TOO_MUCH_ACC, "dae_solve_to",
                              "at t = %.17g the tolerances are below round-off: increase them by "
                              "a factor of at least %.3g (the largest weighted value is %s = "
                              "%.3g against the tolerance %.3g)",
                              s->tn, tolsf, daei_vname(s, i, nb, sizeof nb),
                              i >= 0 ? s->phi[0][i] : 0.0, i >= 0 ? 1.0 / s->ewt[i] : 0.0);
    }
    s->note[0] = '\0';
    return daei_crawl_check(s);
}

/* The step floor: 0 to go on; below the floor (and not landing on a stop), STEP_JUMP when the
 * collapse marks an unannounced jump (dae_disc.c), else the failure that stops the run. */
static int check_floor(dae_solver *s, const step_attempt *a, int landing)
{
    const char *w = "dae_solve_to";
    double hmin = fmax(s->o.h_min, daei_roundoff_h(s));
    if (fabs(s->hh) >= hmin || landing) return 0;
    if (a->last_res_fail)
        return bg_error_raise(&s->err, DAE_RES_FAIL, w,
                              "the residual (or Jacobian) kept failing until the step size fell "
                              "to %.3g at t = %.17g: %s",
                              s->hh, s->tn, s->note);
    if (daei_jump_suspected(s, a->nef, a->ncf)) return STEP_JUMP;
    if (a->nef + a->ncf == 0) note_step_limit(s);
    return bg_error_raise(&s->err, DAE_STEP_TOO_SMALL, w,
                          "step size %.3g at t = %.17g is below the minimum %.3g (%d error-test "
                          "and %d Newton failures in this step)%s%s%s%s",
                          s->hh, s->tn, hmin, a->nef, a->ncf, s->note[0] ? ": " : "", s->note,
                          i2_hint(s), a->ncf > 0 ? fd_hint(s) : "");
}

/* The failure policy of a step: after the attempt to tnew ended with nl (NL_OK: the error test
 * failed; the history is restored), RETRY with the h and order set here, or the status (< 0)
 * that stops the run, with its message.
 *   - a fatal callback status, or a linear solver that fails: stop;
 *   - an error-test failure: order and step from the estimates (daei_after_error_fail), at most
 *     MAX_NEF in one step;
 *   - a Newton failure on a Jacobian from an earlier step: a fresh Jacobian at the same step;
 *   - a Newton failure on a current Jacobian (or a failing residual, or a singular matrix): the
 *     step cut by 4, at most MAX_NCF in one step. */
static int handle_failure(dae_solver *s, step_attempt *a, int nl, double tnew)
{
    const char *w = "dae_solve_to";
    if (nl < 0)
        return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, w,
                              "a callback returned the fatal status %d in the step from t = "
                              "%.17g to %.17g: %s",
                              nl, s->tn, tnew, s->note);
    if (nl == NL_LSFAIL)
        return bg_error_raise(&s->err, DAE_LSETUP_FAIL, w, "at t = %.17g, h = %.3g: %s", s->tn,
                              s->hh, s->note);
    s->phase = 1;
    if (nl == NL_OK) { /* the error test failed */
        note_error_test(s, tnew);
        s->st.rejected_error++;
        s->since_fail = -1;
        a->nef++;
        a->last_res_fail = 0;
        if (a->nef >= MAX_NEF)
            return bg_error_raise(&s->err, DAE_ERR_FAIL, w,
                                  "error test failed %d times at t = %.17g, h = %.3g: %s%s",
                                  a->nef, s->tn, s->hh, s->note, i2_hint(s));
        daei_after_error_fail(s, a->nef);
        return RETRY;
    }
    if (nl == NL_RECOVER && !s->jac_current) { /* stale Jacobian: refresh, same step */
        s->st.newton_fails_stale++;
        s->need_setup = 1;
        return RETRY;
    }
    /* a Newton matrix evaluated at this step that does not contract: with finite differences,
     * an entry the pattern lacks would explain it; probe the residual here and rebuild */
    int by_fd = s->red ? daei_red_by_fd(s) : !s->p.jac;
    if (by_fd && nl == NL_RECOVER && s->nreprobe < MAX_REPROBE) {
        s->nreprobe++;
        long added = 0;
        char keep[sizeof s->note];
        snprintf(keep, sizeof keep, "%s", s->note);
        int pr = s->red ? daei_red_probe(s, tnew, s->y, s->yp, &added)
                        : daei_probe_patterns(s, tnew, s->y, s->yp, 1, &added);
        if (pr == BG_OK && added > 0) {
            int rs = BG_OK;
            if (!s->red) { /* daei_red_probe rebuilt its structures itself */
                daei_free_structure(s);
                rs = daei_setup_structure(s, &s->err);
            }
            if (rs != BG_OK)
                return bg_error_raise(&s->err, DAE_LSETUP_FAIL, w,
                                      "at t = %.17g the Jacobian patterns were missing %ld "
                                      "entries (found by probing the residual where the Newton "
                                      "iteration failed), and the new structure failed: %s",
                                      tnew, added, s->err.message);
            s->st.pattern_reprobes++;
            s->st.pattern_added += added;
            s->need_setup = 1;
            return RETRY;
        }
        snprintf(s->note, sizeof s->note, "%s", keep);
    }
    a->ncf++;
    s->st.newton_fails++;
    s->t_fail = tnew;
    snprintf(s->fail_note, sizeof s->fail_note, "%s", s->note);
    a->last_res_fail = nl == NL_RES_RECOVER;
    if (a->ncf >= MAX_NCF) {
        if (nl == NL_SINGULAR)
            return bg_error_raise(&s->err, DAE_LSETUP_FAIL, w,
                                  "Newton matrix singular %d times at t = %.17g, h = %.3g: %s",
                                  a->ncf, s->tn, s->hh, s->note);
        if (a->last_res_fail)
            return bg_error_raise(&s->err, DAE_RES_FAIL, w,
                                  "the residual (or Jacobian) failed %d times at t = %.17g, h = "
                                  "%.3g: %s",
                                  a->ncf, s->tn, s->hh, s->note);
        return bg_error_raise(&s->err, DAE_CONV_FAIL, w,
                              "Newton iteration failed %d times at t = %.17g, h = %.3g: %s%s%s",
                              a->ncf, s->tn, s->hh, s->note, i2_hint(s), fd_hint(s));
    }
    s->hh *= 0.25;
    s->need_setup = 1;
    return RETRY;
}

int daei_step(dae_solver *s)
{
    step_attempt a = {0, 0, 0};
    int r = check_before(s);
    if (r != BG_OK) return r;
    for (int attempt = 0;; attempt++) {
        int isb;
        double ts = daei_next_stop(s, s->hh > 0 ? 1 : -1, &isb);
        int landing = !isnan(ts) && s->tn + s->hh == ts;
        if ((r = check_floor(s, &a, landing)) != 0) return r;
        /* the weights change with h only through the index-2 unknowns' scaling by |h|: for a
         * retry (the first attempt has check_before's, at this h) */
        if (attempt > 0 && s->has_alg2 &&
            (s->o.index2 == DAE_I2_SCALE_H || s->o.newton_index2_scale_h))
            daei_set_weights(s, s->phi[0]);
        set_coeffs(s);
        predict(s);
        double tnew = landing ? ts : s->tn + s->hh;
        /* a step that lands on a breakpoint sees the inputs' left-hand values there (one unit of
         * round-off short), whichever side the model gives the jump to: the restart takes the
         * right-hand ones */
        double teval = landing && isb ? nextafter(ts, s->tn) : tnew;
        int mebdf = s->o.method == DAE_MEBDF;
        int nl = mebdf ? daei_mebdf_correct(s, tnew, teval,
                                            !isnan(ts) && (tnew + s->hh - ts) * s->hh >= 0)
                       : daei_newton(s, teval);
        int fail = nl == NL_OK && !s->o.fixed_step &&
                   (mebdf ? daei_mebdf_error_test(s) : daei_error_test(s));
        if (nl == NL_OK && !fail) {
            complete_step(s);
            s->tn = tnew;
            return landing && isb ? STEP_ON_BREAKPOINT : STEP_TAKEN;
        }
        restore(s);
        if ((r = handle_failure(s, &a, nl, tnew)) != RETRY) return r;
    }
}
