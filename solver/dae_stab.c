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
 * squares over all unknowns (a Prony fit of the error sequence, the same idea as STALD's fit of
 * a characteristic root). The fit says "one dominant oscillation" when its residual is below
 * STAB_RESIDUAL of |e_{n+1}|, the roots are complex with r >= STAB_R_MIN (lightly damped, or
 * growing) and STAB_THETA_MIN <= theta <= STAB_THETA_MAX (an oscillation the steps follow),
 * and STAB_HITS fits in a row agree on theta within 25 %.
 * Its omega is then remembered.
 *
 * Action. With omega known, an order q >= 3 is allowed only while h omega lies outside its
 * unstable band above; the order chosen for the next step is lowered until it is allowed
 * (order 2 always is). The order is also lowered to 2 when the step cannot grow at its order:
 * the error estimate is below STAB_ERR_FREE of the tolerance (the step is not held by accuracy)
 * and twice the step would fall in the band. BDF2 then damps the mode (by e^-1 in 15 steps at
 * h omega = 1, in 4 at 2), the mode leaves the error estimate, and the step grows to what the
 * remaining components need; the order rises again where h omega allows it. This is numerical
 * dissipation of the unresolved high frequencies, as structural dynamics practises it on
 * purpose (HHT-alpha, generalized-alpha): the fast mode's amplitude is not resolved beyond that
 * point, which is why the guard is an option (options.stability_guard, off by default), as the
 * amount of numerical dissipation is the analyst's choice in structural dynamics: on the IVP
 * Test Set's crank, whose elastic modes are part of the scored answer, it costs a digit at rtol
 * 1e-6; on the crane, whose answer is the slow motion, it costs nothing measurable.
 *
 * Trial. Lowering the order pays only if the step then grows: the mode must be damped faster
 * than the error test holds the step, which depends on its amplitude. The time covered after
 * the lowering is compared with what the step it was lowered at would have covered: below half
 * of it after STAB_CHECK steps, or below all of it after STAB_TRIAL steps, the guard forgets
 * omega, lets the usual order selection act, and lowers no order for the next STAB_QUIET
 * steps (the IVP Test Set's crank, whose elastic modes are large against its tolerance, ends
 * there; the crane's paper scene passes the trial after about 200 steps). */
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

#define STAB_RESIDUAL 0.3  /* fit residual / |e_{n+1}| below which one oscillation dominates */
#define STAB_R_MIN 0.9     /* amplification per step at least this: lightly damped or growing */
#define STAB_R_MAX 1.1     /* and at most this (faster growth is a transient, not a mode) */
#define STAB_THETA_MIN 0.2 /* h omega at least this (30 steps a period): slower ones are resolved
                              at any order, and a smooth solution fits them too */
#define STAB_THETA_MAX 1.05 /* and at most this (6 steps a period): a sign that alternates from
                               step to step (theta near pi) is the error estimate of a stiff
                               decaying component, not an oscillation the steps follow */
#define STAB_HITS 6        /* consecutive fits that must agree */
#define STAB_ERR_FREE 0.25 /* error estimate (in tolerances) below which the step is free */
#define STAB_CHECK 200     /* steps after which the lowered order must cover half the time the
                              step it was lowered at would have */
#define STAB_TRIAL 1000    /* and after which it must cover more */
#define STAB_QUIET 5000    /* steps without a new lowering after a trial that did not pay */

/* h omega bands where BDF of order q amplifies an undamped mode (see above) */
static const double band_lo[MAXORD + 1] = {0, 0, 0, 0.15, 0.25, 0.72};
static const double band_hi[MAXORD + 1] = {0, 0, 0, 1.94, 4.72, 9.4};

static int unstable(int q, double hw)
{
    return q >= 3 && hw > band_lo[q] && hw < band_hi[q];
}

void daei_stab_reset(dae_solver *s)
{
    s->stab_ns = 0;
    s->stab_hits = 0;
    s->stab_w = 0;
    s->stab_active = 0;
    s->stab_since = 0;
    s->stab_quiet = 0;
}

/* Least-squares fit of c = a x + b y over the unknowns: 1 and theta, r when the roots of
 * xi^2 = a xi + b are complex and the residual is small, else 0. */
static int fit(int n, const double *restrict y, const double *restrict x,
               const double *restrict c, double *theta, double *r)
{
    double xx = 0, yy = 0, xy = 0, cx = 0, cy = 0, cc = 0;
    for (int i = 0; i < n; i++) {
        xx += x[i] * x[i];
        yy += y[i] * y[i];
        xy += x[i] * y[i];
        cx += c[i] * x[i];
        cy += c[i] * y[i];
        cc += c[i] * c[i];
    }
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
    double *v = s->tmp2; /* the weighted error estimate of this step */
    for (int i = 0; i < n; i++)
        v[i] = s->ee[i] * s->werr[i];
    if (h != s->stab_hs || k != s->stab_ks) s->stab_ns = 0;
    if (s->stab_ns >= 2) {
        double theta, r;
        if (fit(n, s->stab_e[1], s->stab_e[0], v, &theta, &r) && r >= STAB_R_MIN && r <= STAB_R_MAX &&
            theta >= STAB_THETA_MIN && theta <= STAB_THETA_MAX) {
            if (s->stab_hits > 0 && fabs(theta - s->stab_theta) > 0.25 * theta) s->stab_hits = 0;
            s->stab_hits++;
            s->stab_theta = theta;
            if (s->stab_hits >= STAB_HITS) s->stab_w = theta / fabs(h);
        } else {
            s->stab_hits = 0;
        }
    }
    double *old = s->stab_e[1]; /* shift: e[1] <- e[0] <- v */
    s->stab_e[1] = s->stab_e[0];
    s->stab_e[0] = old;
    memcpy(s->stab_e[0], v, (size_t)n * sizeof *v);
    if (s->stab_ns < 2) s->stab_ns++;
    s->stab_hs = h;
    s->stab_ks = k;
}

void daei_stab_decide(dae_solver *s)
{
    if (!s->o.stability_guard || s->o.fixed_step || s->phase == 0 || !(s->stab_w > 0)) return;
    double h = fabs(s->hh), hw = h * s->stab_w;
    int k = s->kk;
    if (s->stab_active) { /* the trial: the lowered order must cover time faster */
        s->stab_since++;
        s->stab_tsum += fabs(s->hused);
        double pace = s->stab_tsum / (s->stab_since * s->stab_hleft);
        int end = s->stab_since >= STAB_TRIAL;
        if ((s->stab_since == STAB_CHECK && pace < 0.5) || (end && pace < 1)) {
            s->stab_active = 0; /* it does not pay: forget the oscillation for a while */
            s->stab_w = 0;
            s->stab_hits = 0;
            s->stab_quiet = s->st.steps + STAB_QUIET;
            return;
        }
        if (end) s->stab_active = 0;
    }
    int lower = 0;
    if (unstable(k, hw))
        lower = 1; /* in the band */
    else if (k > 2 && s->err_next < STAB_ERR_FREE && unstable(k, 2 * hw))
        lower = 1; /* held below the band although the error would let the step grow */
    if (!lower) return;
    if (!s->stab_active) {
        if (s->st.steps < s->stab_quiet) return;
        s->stab_active = 1;
        s->stab_hleft = fabs(s->hused);
        s->stab_since = 0;
        s->stab_tsum = 0;
        s->st.stab_lowered++;
    }
    s->kk = 2;
}
