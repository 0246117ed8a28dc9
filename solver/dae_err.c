/* Error control of the integrator: the error weights and norms, the local error test, the
 * choice of order and step after an accepted step and after an error-test failure, and the
 * first step.
 *
 * Weights. w_i = 1 / (rtol |y_i| + atol_i). The error test uses them on the differential
 * unknowns and the index-1 algebraic ones (those left out with options.exclude_alg); an index-2
 * unknown lambda is left out (DAE_I2_EXCLUDE) or weighted by |h| (DAE_I2_SCALE_H): BDF applied to
 * an index-2 system converges with order k in the other unknowns, but lambda's local error
 * estimate is O(h^k) only after division by h (Brenan, Campbell and Petzold 1996, sec. 3.3;
 * Hairer and Wanner, Solving ODEs II, sec. VII.3), and h lambda has the units of an impulse and
 * the order of the differential unknowns.
 *
 * Order and step (IDA's published algorithm, after DASSL: Brenan et al. sec. 5.2-5.3). In the
 * initial phase the order is raised and the step doubled after each step; then the scaled error
 * estimates of orders k-1, k, k+1 are compared. The step is kept unless the estimate asks for a
 * ratio >= 2 or <= 1; ratios are bounded to [0.5, 0.9] on decrease and 2 on increase.
 * After an error-test failure the step may double again only after k+1 steps have been
 * accepted since: index-2 problems otherwise cycle (a doubled step shifts the O(h) error of
 * lambda into the differential unknowns' estimate, the step fails, is halved, succeeds,
 * doubles, ...: lin2 at rtol 1e-10 took 10031 steps with 8939 failures without the rule, 246
 * with 2 failures with it; IDA, which has no such rule, takes 10183). */
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

#define TOL_FLOOR 1e-100

/* The weights' vector pass: w = 1 / (rtol |y| + atol + TOL_FLOOR) into ewt, wd, we (masked by
 * m: w or +0, when mask) and wn (when own_wn); the flags constant where it is inlined. */
DAEI_INLINE void weights_pass(int mask, int own_wn, int n, double rtol, const double *restrict y,
                              const double *restrict at, const long long *restrict m,
                              double *restrict ewt, double *restrict wd, double *restrict we,
                              double *restrict wn)
{
    DAEI_VFOR(i, n, V w = 1.0 / (rtol * VABS(VAT(y, i)) + VAT(at, i) + TOL_FLOOR);
              VAT(ewt, i) = w; VAT(wd, i) = w;
              if (mask) VAT(we, i) = VMASK(w, VATI(m, i));
              else VAT(we, i) = w;
              if (own_wn) VAT(wn, i) = w;);
}

void daei_set_weights(dae_solver *s, const double *y)
{
    double h = fabs(s->hh), rtol = s->o.rtol;
    int n = s->n;
    double *ewt = s->ewt, *wd = s->wdiff, *we = s->werr, *wn = s->wnewt;
    const double *at = s->atol;
    /* every weight as that of a differential unknown in one branch-free pass, then the
     * algebraic unknowns through their index lists. TOL_FLOOR added: the weights and their
     * squares in the norms stay finite (atol = 0 with y_i = 0, or a denormal atol) and any
     * other tolerance is unchanged; no branch */
    const long long *m = s->wmask; /* werr 0 for exclude_alg's index-1 unknowns */
    int own_wn = s->wnewt != s->ewt; /* else the Newton weights are ewt itself */
    switch (2 * (m != NULL) + own_wn) {
    case 0: weights_pass(0, 0, n, rtol, y, at, NULL, ewt, wd, we, NULL); break;
    case 1: weights_pass(0, 1, n, rtol, y, at, NULL, ewt, wd, we, s->wnewt); break;
    case 2: weights_pass(1, 0, n, rtol, y, at, m, ewt, wd, we, NULL); break;
    default: weights_pass(1, 1, n, rtol, y, at, m, ewt, wd, we, s->wnewt); break;
    }
    for (int k = 0; k < s->na2; k++) {
        int i = s->a2cols[k];
        double w = ewt[i];
        wd[i] = 0.0;
        we[i] = s->o.index2 == DAE_I2_EXCLUDE ? 0.0 : w * h;
        if (s->o.newton_index2_scale_h) wn[i] = w * h; /* (else wn is ewt) */
    }
}

double daei_wrms(const dae_solver *s, const double *v, const double *w)
{
    /* four partial sums: independent chains the processor overlaps */
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    int n = s->n, i = 0;
    for (; i + 4 <= n; i += 4) {
        double a0 = v[i] * w[i], a1 = v[i + 1] * w[i + 1], a2 = v[i + 2] * w[i + 2],
               a3 = v[i + 3] * w[i + 3];
        s0 += a0 * a0;
        s1 += a1 * a1;
        s2 += a2 * a2;
        s3 += a3 * a3;
    }
    for (; i < n; i++) {
        double a = v[i] * w[i];
        s0 += a * a;
    }
    return sqrt(((s0 + s1) + (s2 + s3)) / (n > 0 ? n : 1));
}


/* The weighted RMS norm of a - b with the error test's weights werr: the unknowns i = 0, 2, 4,
 * ... summed in one sum and 1, 3, 5, ... in another (two chains the processor overlaps), over
 * tcols only where it lists fewer than all (the terms left out are +0: err_sums says why). */
static double wrms_diff_err(const dae_solver *s, const double *restrict a, const double *restrict b)
{
    int n = s->n;
    const double *restrict w = s->werr;
    double q0 = 0, q1 = 0;
    if (s->tcols && s->ntcols < n) {
        const int *restrict idx = s->tcols;
        for (int t = 0; t < s->ntcols; t++) {
            int i = idx[t];
            double d = (a[i] - b[i]) * w[i];
            if (i & 1)
                q1 += d * d;
            else
                q0 += d * d;
        }
    } else {
        int i = 0;
        for (; i + 2 <= n; i += 2) {
            double d0 = (a[i] - b[i]) * w[i], d1 = (a[i + 1] - b[i + 1]) * w[i + 1];
            q0 += d0 * d0;
            q1 += d1 * d1;
        }
        for (; i < n; i++) {
            double d0 = (a[i] - b[i]) * w[i];
            q0 += d0 * d0;
        }
    }
    return sqrt((q0 + q1) / (n > 0 ? n : 1));
}

/* The sums of squares of the weighted ee, ee + phi[k] (lev >= 1) and ee + phi[k] + phi[k-1]
 * (lev 2) over the unknowns idx[0..m-1] (gather), or 0..m-1, in ascending order. Where werr is
 * 0 a term is +0 (ee and the history are finite), and adding +0 to a sum of squares leaves it
 * as it is: over the list of the unknowns the error test weighs (tcols) the sums are the same
 * bits as over all unknowns. */
DAEI_INLINE void err_sums(int lev, int gather, const int *restrict idx, int m,
                          const double *restrict e, const double *restrict w,
                          const double *restrict pk, const double *restrict pk1, double *q)
{
    double q0 = 0, q1 = 0, q2 = 0;
    for (int t = 0; t < m; t++) {
        int i = gather ? idx[t] : t;
        double a = e[i] * w[i];
        q0 += a * a;
        if (lev >= 1) {
            double b = a + pk[i] * w[i];
            q1 += b * b;
            if (lev >= 2) {
                double c = b + pk1[i] * w[i];
                q2 += c * c;
            }
        }
    }
    q[0] = q0;
    q[1] = q1;
    q[2] = q2;
}

int daei_error_test(dae_solver *s)
{
    int k = s->kk, n = s->n;
    /* the weighted norms of ee, ee + phi[k] and ee + phi[k] + phi[k-1] in one pass */
    double q[3] = {0, 0, 0};
    {
        const double *e = s->ee, *w = s->werr, *pk = s->phi[k], *pk1 = s->phi[k > 1 ? k - 1 : k];
        int lev = k > 2 ? 2 : k - 1, gather = s->tcols && s->ntcols < n;
        const int *idx = s->tcols;
        int m = gather ? s->ntcols : n;
        switch (lev + 3 * gather) {
        case 0: err_sums(0, 0, idx, m, e, w, pk, pk1, q); break;
        case 1: err_sums(1, 0, idx, m, e, w, pk, pk1, q); break;
        case 2: err_sums(2, 0, idx, m, e, w, pk, pk1, q); break;
        case 3: err_sums(0, 1, idx, m, e, w, pk, pk1, q); break;
        case 4: err_sums(1, 1, idx, m, e, w, pk, pk1, q); break;
        default: err_sums(2, 1, idx, m, e, w, pk, pk1, q); break;
        }
        double nn = n > 0 ? n : 1;
        q[0] = sqrt(q[0] / nn);
        q[1] = sqrt(q[1] / nn);
        q[2] = sqrt(q[2] / nn);
    }
    double enorm_k = q[0];
    s->err_k = s->sigma[k] * enorm_k;
    double terr_k = (k + 1) * s->err_k;
    s->knew = k;
    s->err_km1 = 0;
    if (k > 1) {
        s->err_km1 = s->sigma[k - 1] * q[1];
        double terr_km1 = k * s->err_km1;
        if (k > 2) {
            double terr_km2 = (k - 1) * s->sigma[k - 2] * q[2];
            if (fmax(terr_km1, terr_km2) <= terr_k) s->knew = k - 1;
        } else if (terr_km1 <= 0.5 * terr_k) {
            s->knew = k - 1;
        }
    }
    return s->ck * enorm_k > 1.0;
}

void daei_choose_next(dae_solver *s, int kdiff)
{
    /* the initial phase ends at the first order decrease or at the highest order */
    if (s->knew == s->kk - 1 || s->kk == s->o.max_order) s->phase = 1;
    double hmax_inv = s->o.h_max > 0 ? 1.0 / s->o.h_max : 0.0;
    s->err_next = s->err_k;
    if (s->o.fixed_step) {
        /* keep h and k */
    } else if (s->phase == 0) {
        if (s->st.steps > 1 || s->nst_local > 1) {
            s->kk++;
            double hnew = 2 * s->hh, tmp;
            if ((tmp = fabs(hnew) * hmax_inv) > 1) hnew /= tmp;
            s->hh = hnew;
        }
    } else {
        enum { LOWER, MAINTAIN, RAISE } action;
        double err_kp1 = 0, err_knew;
        int k = s->kk;
        if (s->knew == k - 1)
            action = LOWER;
        else if (k == s->o.max_order || k + 1 >= s->ns || kdiff == 1)
            action = MAINTAIN;
        else {
            err_kp1 = wrms_diff_err(s, s->ee, s->phi[k + 1]) / (k + 2);
            double terr_k = (k + 1) * s->err_k, terr_kp1 = (k + 2) * err_kp1;
            if (k == 1)
                action = terr_kp1 >= 0.5 * terr_k ? MAINTAIN : RAISE;
            else {
                double terr_km1 = k * s->err_km1;
                if (terr_km1 <= fmin(terr_k, terr_kp1))
                    action = LOWER;
                else
                    action = terr_kp1 >= terr_k ? MAINTAIN : RAISE;
            }
        }
        if (action == RAISE) {
            s->kk++;
            err_knew = err_kp1;
        } else if (action == LOWER) {
            s->kk--;
            err_knew = s->err_km1;
        } else
            err_knew = s->err_k;
        s->err_next = err_knew;
        double hnew = s->hh;
        double rr = pow(2 * err_knew + 1e-4, -1.0 / (s->kk + 1));
        if (rr >= 2 && s->since_fail > s->kk) {
            double tmp;
            hnew = 2 * s->hh;
            if ((tmp = fabs(hnew) * hmax_inv) > 1) hnew /= tmp;
        } else if (rr <= 1) {
            hnew = s->hh * fmax(0.5, fmin(0.9, rr));
        }
        s->hh = hnew;
    }
}

void daei_after_error_fail(dae_solver *s, int nef)
{
    if (nef == 1) {
        double ekn = s->kk == s->knew ? s->err_k : s->err_km1;
        s->kk = s->knew;
        double rr = 0.9 * pow(2 * ekn + 1e-4, -1.0 / (s->kk + 1));
        s->hh *= fmax(0.25, fmin(0.9, rr));
    } else if (nef == 2) {
        s->kk = s->knew;
        s->hh *= 0.25;
    } else {
        s->kk = 1;
        s->hh *= 0.25;
    }
}

/* dir: the direction of the integration, 0 to take it from tout (a restart keeps the direction
 * it had, and tout may then lie at tn). */
int daei_first_step(dae_solver *s, double tout, double hpref, double dir)
{
    if (dir == 0) dir = tout >= s->tn ? 1.0 : -1.0;
    s->hh = 0;
    daei_set_weights(s, s->phi[0]);
    double h;
    if (s->o.h_init > 0)
        h = s->o.h_init;
    else {
        /* tout counts only ahead of tn (a restart may sit on it) */
        double tdist = (tout - s->tn) * dir > 0 ? fabs(tout - s->tn) : HUGE_VAL;
        int isb;
        double ts = daei_next_stop(s, dir, &isb);
        if (!isnan(ts)) tdist = fmin(tdist, fabs(ts - s->tn));
        if (tdist == HUGE_VAL && hpref > 0) tdist = hpref;
        if (tdist == 0 || tdist == HUGE_VAL)
            return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_solve_to",
                                  "tout = %g is too close to t = %g to choose a first step", tout,
                                  s->tn);
        if (hpref > 0) {
            h = fmin(hpref, tdist);
        } else { /* IDA's rule: the first step changes y by at most half a tolerance unit */
            h = 0.001 * tdist;
            double ypnorm = daei_wrms(s, s->phi[1], s->werr);
            if (ypnorm > 0.5 / h) h = 0.5 / ypnorm;
        }
    }
    s->hh = dir * h;
    daei_clip_to_stop(s);
    for (int i = 0; i < s->n; i++)
        s->phi[1][i] *= s->hh;
    s->kk = 1;
    s->kused = 0;
    s->hused = 0;
    s->psi[0] = s->hh;
    s->cj = 1.0 / s->hh;
    s->phase = 0;
    s->ns = 0;
    s->nst_local = 0;
    s->need_setup = 1;
    s->first = 0;
    return BG_OK;
}

