/* The stability guard: order control that sees the stability limits of BDF orders 3 to 5 on
 * lightly damped oscillatory components.
 *
 * The problem. BDF of order 1 and 2 is A-stable; orders 3 to 5 are not: on an undamped mode
 * y' = i omega y they amplify by more than 1 + 1e-4 per step for h omega in
 *     order 3: (0.15, 1.94),  order 4: (0.25, 4.72),  order 5: (0.72, 9.4)
 * (the roots of sum_j (1/j) nabla^j = h lambda on the imaginary axis, computed; Hairer and
 * Wanner, Solving ODEs II, sec. V.2, show the stability regions). A flexible structure or a
 * hydraulic line whose fast modes are excited and undamped puts the integrator in a trap: at
 * order 5 the step is held just below 0.72 / omega (a larger one lets the mode grow until the
 * error test cuts the step), the mode stays resolved and dominates the local error estimate, and
 * the usual order selection (the estimates of orders k-1, k, k+1 at this step) keeps order 5,
 * since the estimates of the lower orders at the same step are larger. Loosening the tolerance
 * does not help. CVODE meets the same trap with STALD (Hindmarsh's stability limit detection,
 * which fits the characteristic root of the scaled derivatives of the last steps and lowers the
 * order when it lies at the stability boundary); IDA has nothing of the kind.
 *
 * Detection. At constant h and order, the local error estimates e_n (weighted as in the error
 * test) of a component that oscillates with one frequency obey a two-term recurrence
 *     e_{n+1} = a e_n + b e_{n-1},   with roots xi = r exp(+-i theta) of xi^2 = a xi + b,
 * where theta = h omega (for theta < pi) and r the amplification per step (1 undamped). After
 * each accepted step at the same h and order as the two before, a and b are fitted by least
 * squares over all unknowns and over every triple of the last STAB_WIN estimates taken at this
 * h and order (a Prony fit of the error sequence, the same idea as STALD's fit of a
 * characteristic root; several triples keep the fit overdetermined when the error lies in two or
 * three unknowns, where one triple fits any a, b). The fit says "one dominant oscillation" when
 * its residual is below STAB_RESIDUAL of the fitted norm, the roots are complex with
 * STAB_R_MIN <= r <= STAB_R_MAX (lightly damped) and STAB_THETA_MIN <= theta <= STAB_THETA_MAX
 * (an oscillation the steps follow), and STAB_HITS fits in a row agree on theta within 25 %.
 * Its omega is then remembered (and updated by later detections) until the next restart.
 *
 * Action. With omega known, an order q >= 3 is kept only while h omega lies outside its
 * unstable band above; otherwise the order of the next step is lowered to 2 (A-stable):
 *  - when h omega lies in the band and the error estimate is below STAB_ERR_HELD of the
 *    tolerance (the step is set by stability: an error estimate near the tolerance means the
 *    error test holds the step, the oscillation is resolved to accuracy, and the usual order
 *    selection decides);
 *  - when the step cannot grow at its order: the error estimate is below STAB_ERR_FREE of the
 *    tolerance and twice the step would fall in the band.
 * BDF2 then damps the mode (by e^-1 in 15 steps at h omega = 1, in 4 at 2), the mode leaves the
 * error estimate, and the step grows to what the remaining components need; the order rises
 * again, by the usual selection, where h omega allows it.
 *   Order 2 is also the floor while lowering holds a known oscillation: after a step at order 2
 * or more the next one is not taken at order 1. The usual selection drops to order 1 there
 * because BDF1's heavier damping makes the oscillation smaller in its error estimate, not
 * because order 1 is more accurate; it is first-order accurate, its steps must then be far
 * smaller, and its error accumulates in the slow motion. Dissipating the unresolved modes is
 * BDF2's task, and a dissipative method is to keep second-order accuracy (the design rule of
 * the dissipative schemes of structural dynamics: Hilber, Hughes and Taylor, Earthquake Eng.
 * Struct. Dyn. 5 (1977) 283-292; Chung and Hulbert, J. Appl. Mech. 60 (1993) 371-375). Order 1
 * stays available after error-test failures and at restarts. This is numerical dissipation of the
 * unresolved high frequencies, as structural dynamics practises it on purpose (HHT-alpha,
 * generalized-alpha): the fast mode's amplitude is not resolved beyond that point.
 *
 * Measured, not assumed. Lowering pays only if the mode then decays faster than the error test
 * holds the step: a free mode (a structure's vibration after a transient) does, a mode forced
 * by the motion or large against the tolerance stays in the error estimate at order 2 and the
 * steps shrink instead. So once an oscillation is known, the two policies (lowering, and the
 * usual order selection) are run in phases and compared by their pace, the time covered per
 * step attempt (accepted and rejected steps and Newton failures): each is measured over
 * STAB_PHASE accepted steps, then the faster one is used for a phase of 4 STAB_PHASE steps,
 * doubled (up to STAB_EXPLOIT_MAX) each time the comparison chooses it again, after which the
 * other one is measured again (the choice between two arms by measured reward, as in an
 * explore-then-exploit bandit with doubling epochs). Lowering is kept unless the usual orders
 * are STAB_BIAS times faster: a phase of the usual orders that follows lowering starts with the
 * mode damped and regrows it only later, which favours it over a phase of STAB_PHASE steps.
 *
 * Whether the dissipation is acceptable is the analyst's choice, as the amount of numerical
 * dissipation is in structural dynamics, hence an option (options.stability_guard, off by
 * default): where the answer is the slow motion and the fast modes are not resolved anyway, it
 * costs nothing measurable in that answer; where the fast modes are part of the answer (the IVP
 * Test Set's crank, whose elastic modes are scored), it costs up to a digit: leave it off
 * there. */
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

#define STAB_RESIDUAL 0.3  /* fit residual / fitted norm below which one oscillation dominates */
#define STAB_R_MIN 0.9     /* amplification per step at least this: lightly damped or growing */
#define STAB_R_MAX 1.1     /* and at most this (faster growth is a transient, not a mode) */
#define STAB_THETA_MIN 0.2 /* h omega at least this (30 steps a period): slower ones are resolved
                              at any order, and a smooth solution fits them too */
#define STAB_THETA_MAX 1.05 /* and at most this (6 steps a period): a sign that alternates from
                               step to step (theta near pi) is the error estimate of a stiff
                               decaying component, not an oscillation the steps follow */
#define STAB_HITS 3        /* consecutive fits that must agree */
#define STAB_ERR_HELD 0.5  /* error estimate (in tolerances) above which the error test holds
                              the step */
#define STAB_ERR_FREE 0.25 /* and below which the step is free to grow */
#define STAB_PHASE 200     /* accepted steps of a phase that measures a policy */
#define STAB_BIAS 2.0      /* lowering is kept unless the usual orders cover time this much faster */
#define STAB_EXPLOIT_MAX (32 * STAB_PHASE) /* the longest phase that uses the faster one */

/* h omega bands where BDF of order q amplifies an undamped mode (see above) */
static const double band_lo[MAXORD + 1] = {0, 0, 0, 0.15, 0.25, 0.72};
static const double band_hi[MAXORD + 1] = {0, 0, 0, 1.94, 4.72, 9.4};

static int unstable(int q, double hw)
{
    return q >= 3 && hw > band_lo[q] && hw < band_hi[q];
}

static long attempts(const dae_solver *s)
{
    return s->st.steps + s->st.rejected_error + s->st.newton_fails;
}

void daei_stab_reset(dae_solver *s)
{
    s->stab_ns = 0;
    s->stab_hits = 0;
    s->stab_w = 0;
    s->stab_on = 0;
    s->stab_len = 0;
    s->stab_cnt = 0;
    s->stab_pace[0] = s->stab_pace[1] = 0;
    s->stab_win[0] = s->stab_win[1] = 0;
    s->stab_probe = 0;
    s->stab_last = -1;
}

/* Starts a phase of policy on (1: lowering) of len accepted steps. */
static void phase(dae_solver *s, int on, long len, int probe)
{
    s->stab_on = on;
    s->stab_len = len;
    s->stab_probe = probe;
    s->stab_cnt = 0;
    s->stab_tmark = s->tn;
    s->stab_amark = attempts(s);
}

/* The comparison of the two policies (see the header): called after each accepted step once an
 * oscillation is known. */
static void compare(dae_solver *s)
{
    if (s->stab_len == 0) { /* the oscillation has just been found: measure lowering first */
        phase(s, 1, STAB_PHASE, 1);
        return;
    }
    if (++s->stab_cnt < s->stab_len) return;
    long da = attempts(s) - s->stab_amark;
    s->stab_pace[s->stab_on] = da > 0 ? fabs(s->tn - s->stab_tmark) / (double)da : 0;
    int other = !s->stab_on;
    if (!(s->stab_pace[other] > 0)) {
        phase(s, other, STAB_PHASE, 1); /* the other policy has no measurement yet */
    } else if (s->stab_probe) { /* both measured: use the faster one */
        int win = STAB_BIAS * s->stab_pace[1] > s->stab_pace[0];
        if (win == s->stab_last)
            s->stab_win[win] = s->stab_win[win] < STAB_EXPLOIT_MAX ? 2 * s->stab_win[win]
                                                                  : STAB_EXPLOIT_MAX;
        else
            s->stab_win[win] = 4 * STAB_PHASE;
        s->stab_last = win;
        phase(s, win, s->stab_win[win], 0);
    } else {
        phase(s, other, STAB_PHASE, 1); /* measure the other policy again */
    }
}

/* The six sums of products of the fit over the triples (e[j], e[j+1], e[j+2]), j < m, and over
 * the nt packed unknowns, in ascending order; sum[0..5] = xx, yy, xy, cx, cy, cc. */
static void fit_sums(int nt, double *const *e, int m, double *sum)
{
    double xx = 0, yy = 0, xy = 0, cx = 0, cy = 0, cc = 0;
    for (int j = 0; j < m; j++) {
        const double *restrict c = e[j], *restrict x = e[j + 1], *restrict y = e[j + 2];
        for (int i = 0; i < nt; i++) {
            xx += x[i] * x[i];
            yy += y[i] * y[i];
            xy += x[i] * y[i];
            cx += c[i] * x[i];
            cy += c[i] * y[i];
            cc += c[i] * c[i];
        }
    }
    sum[0] = xx;
    sum[1] = yy;
    sum[2] = xy;
    sum[3] = cx;
    sum[4] = cy;
    sum[5] = cc;
}

/* Least-squares fit of e_{j} = a e_{j+1} + b e_{j+2} over the unknowns and over the m triples of
 * the window e[0..m+1] (newest first): 1 and theta, r when the roots of xi^2 = a xi + b are
 * complex and the residual is small, else 0. Several triples make the fit overdetermined even
 * when the error lies in few unknowns (two unknowns and one triple fit any a, b exactly). The
 * estimates are weighted by werr: where it is 0 every product is +-0, which leaves the sums as
 * they are (they start at +0), so the window holds the unknowns the error test weighs (tcols)
 * alone, packed, where those are fewer than all: the same bits. */
static int packed(const dae_solver *s)
{
    return s->tcols && s->ntcols < s->n;
}

static int fit(const dae_solver *s, double *const *e, int m, double *theta, double *r)
{
    double sum[6];
    fit_sums(packed(s) ? s->ntcols : s->n, e, m, sum);
    double xx = sum[0], yy = sum[1], xy = sum[2], cx = sum[3], cy = sum[4], cc = sum[5];
    double det = xx * yy - xy * xy;
    if (!(cc > 0) || !(det > 1e-12 * xx * yy)) return 0;
    double a = (cx * yy - cy * xy) / det, b = (cy * xx - cx * xy) / det;
    double res2 = cc - a * cx - b * cy;
    double disc = a * a + 4 * b;
    if (res2 > STAB_RESIDUAL * STAB_RESIDUAL * cc || disc >= 0) return 0;
    *r = sqrt(-b);
    *theta = atan2(sqrt(-disc), a);
    return 1;
}

void daei_stab_observe(dae_solver *s)
{
    if (!s->o.stability_guard || s->o.fixed_step) return;
    int n = s->n, k = s->kused;
    double h = s->hused;
    if (h != s->stab_hs || k != s->stab_ks) s->stab_ns = 0;
    double *old = s->stab_e[STAB_WIN - 1]; /* shift the window: e[j+1] <- e[j], e[0] <- v */
    memmove(s->stab_e + 1, s->stab_e, (STAB_WIN - 1) * sizeof *s->stab_e);
    s->stab_e[0] = old;
    { /* v: the weighted error estimate of this step, packed */
        double *restrict v = old;
        const double *restrict e = s->ee, *restrict w = s->werr;
        if (packed(s)) {
            const int *restrict idx = s->tcols;
            for (int t = 0; t < s->ntcols; t++)
                v[t] = e[idx[t]] * w[idx[t]];
        } else {
            DAEI_VFOR(i, n, VAT(v, i) = VAT(e, i) * VAT(w, i););
        }
    }
    if (s->stab_ns < STAB_WIN) s->stab_ns++;
    if (s->stab_ns >= 3) { /* a triple */
        double theta, r;
        if (fit(s, s->stab_e, s->stab_ns - 2, &theta, &r) && r >= STAB_R_MIN && r <= STAB_R_MAX &&
            theta >= STAB_THETA_MIN && theta <= STAB_THETA_MAX) {
            if (s->stab_hits > 0 && fabs(theta - s->stab_theta) > 0.25 * theta) s->stab_hits = 0;
            s->stab_hits++;
            s->stab_theta = theta;
            if (s->stab_hits >= STAB_HITS) s->stab_w = theta / fabs(h);
        } else {
            s->stab_hits = 0;
        }
    }
    s->stab_hs = h;
    s->stab_ks = k;
    if (s->stab_w > 0) compare(s);
}

void daei_stab_decide(dae_solver *s)
{
    if (!s->o.stability_guard || s->o.fixed_step || s->phase == 0 || !(s->stab_w > 0) ||
        !s->stab_on)
        return;
    double hw = fabs(s->hh) * s->stab_w;
    int k = s->kk;
    if (k < 2 && s->kused >= 2) { /* order 2 is the floor (see the header) */
        s->kk = 2;
        return;
    }
    if ((unstable(k, hw) && s->err_next < STAB_ERR_HELD) ||
        (k > 2 && s->err_next < STAB_ERR_FREE && unstable(k, 2 * hw))) {
        s->kk = 2;
        s->st.stab_lowered++;
    }
}
