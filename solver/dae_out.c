/* Output of the integrator: dense output from the history's interpolating polynomial, roots of
 * the event functions located on it by the Illinois variant of regula falsi, and the drift from
 * the position constraints g(y) = 0 after each step with, if asked, the projection of y back
 * onto them by the minimum-norm correction. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "bg_dae_impl.h"

int dae_dense(const dae_solver *s, double t, double *y, double *yp)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!s->initialized) return BG_ERR_STATE;
    int n = s->n;
    if (s->first || s->hused == 0) {
        /* no step taken since the (re)start: phi[1] holds y', scaled by the first step's
         * psi[0] once that step is chosen */
        if (y) memcpy(y, s->phi[0], (size_t)n * sizeof *y);
        if (yp && s->first)
            memcpy(yp, s->phi[1], (size_t)n * sizeof *yp);
        else if (yp)
            for (int i = 0; i < n; i++)
                yp[i] = s->phi[1][i] / s->psi[0];
        return t == s->tn ? BG_OK : BG_ERR_ARGUMENT;
    }
    double tfuzz = 100 * DBL_EPSILON * (fabs(s->tn) + fabs(s->hh));
    if (s->hused < 0) tfuzz = -tfuzz;
    if ((t - (s->tn - s->hused - tfuzz)) * s->hused < 0 || (t - (s->tn + tfuzz)) * s->hused > 0)
        return BG_ERR_ARGUMENT;
    daei_interpolate(s, t, y, yp);
    return BG_OK;
}

void daei_interpolate(const dae_solver *s, double t, double *y, double *yp)
{
    int n = s->n;
    double delt = t - s->tn, c = 1, d = 0, gam = delt / s->psi[0];
    int kord = s->kused > 0 ? s->kused : 1;
    if (y) memcpy(y, s->phi[0], (size_t)n * sizeof *y);
    if (yp) memset(yp, 0, (size_t)n * sizeof *yp);
    for (int j = 1; j <= kord; j++) {
        d = d * gam + c / s->psi[j - 1];
        c = c * gam;
        gam = (delt + s->psi[j - 1]) / s->psi[j];
        /* branch-free loops that vectorise (the tests for y and yp kept out of them): dense
         * output runs at every output time, often several per step */
        const double *restrict pj = s->phi[j];
        if (y && yp) {
            double *restrict a = y, *restrict b = yp;
            for (int i = 0; i < n; i++) {
                a[i] += c * pj[i];
                b[i] += d * pj[i];
            }
        } else if (y) {
            for (int i = 0; i < n; i++)
                y[i] += c * pj[i];
        } else if (yp) {
            for (int i = 0; i < n; i++)
                yp[i] += d * pj[i];
        }
    }
}

/* Minimum-norm Gauss-Newton correction of y onto g(t, y) = 0 (at most 3 iterations). */
int daei_project_vec(dae_solver *s, double t, double *y)
{
    for (int it = 0; it < 3; it++) {
        int r = s->p.cons(s->p.user, t, y, s->gv, s->G);
        if (r != 0)
            return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, "dae_solve_to",
                                  "constraint function returned %d at t = %g", r, t);
        double t0 = daei_clock(s);
        r = aat_factor(s->aat_proj, s->G, 0.0);
        if (r == BG_OK) r = aat_solve(s->aat_proj, s->gv, s->gw);
        s->st.t_linalg += daei_clock(s) - t0;
        if (r != BG_OK)
            return bg_error_raise(&s->err, DAE_LSETUP_FAIL, "dae_solve_to",
                                  "projection at t = %g: %s", t,
                                  aat_get_error(s->aat_proj)->message);
        sp_matvec_t(s->G, -1.0, s->gw, 0.0, s->tmp);
        for (int i = 0; i < s->n; i++)
            y[i] += s->tmp[i];
        s->st.projections++;
        if (daei_wrms(s, s->tmp, s->ewt) < 1e-6) break;
    }
    return BG_OK;
}

/* Drift after an accepted step, and projection of y_n if asked. */
int daei_project_step(dae_solver *s)
{
    int r = s->p.cons(s->p.user, s->tn, s->phi[0], s->gv, NULL);
    if (r != 0)
        return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, "dae_solve_to",
                              "constraint function returned %d at t = %g", r, s->tn);
    double g = 0;
    for (int i = 0; i < s->p.ncons; i++)
        g = fmax(g, fabs(s->gv[i]));
    s->st.max_drift = fmax(s->st.max_drift, g);
    return s->o.projection ? daei_project_vec(s, s->tn, s->phi[0]) : BG_OK;
}

/* Interpolated output; with projection on, interpolated values are projected as well. */
void daei_output_state(dae_solver *s, double t, double *tret, double *y, double *yp)
{
    *tret = t;
    if (dae_dense(s, t, y, yp) != BG_OK) {
        if (y) memcpy(y, s->phi[0], (size_t)s->n * sizeof *y);
        if (yp) dae_dense(s, s->tn, NULL, yp);
        *tret = s->tn;
    } else if (y && s->o.projection && t != s->tn) {
        daei_project_vec(s, t, y); /* a failure leaves the interpolated value and the message */
    }
}

int daei_call_roots(dae_solver *s, const char *where, double t, const double *y, const double *yp,
                    double *g)
{
    int r = s->p.roots(s->p.user, t, y, yp, g);
    if (r != 0)
        return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, where,
                              "the event function returned the status %d at t = %.17g", r, t);
    for (int i = 0; i < s->p.nroots; i++)
        if (!isfinite(g[i]))
            return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, where,
                                  "event function %d is %g at t = %.17g: its sign changes "
                                  "cannot be located",
                                  i, g[i], t);
    return BG_OK;
}

/* Illinois search for the earliest sign change of the event functions in (tlo, tn]. */
int daei_find_root(dae_solver *s)
{
    int nr = s->p.nroots, r;
    dae_dense(s, s->tn, s->y, s->yp);
    if ((r = daei_call_roots(s, "dae_solve_to", s->tn, s->y, s->yp, s->ghi)) != BG_OK) return r;
    int any = 0;
    for (int i = 0; i < nr; i++)
        if ((s->glo[i] < 0 && s->ghi[i] >= 0) || (s->glo[i] > 0 && s->ghi[i] <= 0)) any = 1;
    if (!any) {
        s->tlo = s->tn;
        memcpy(s->glo, s->ghi, (size_t)nr * sizeof(double));
        return 0;
    }
    double ta = s->tlo, tb = s->tn;
    double ttol = 100 * DBL_EPSILON * (fabs(s->tn) + fabs(s->hused));
    double *ga = s->glo, *gb = s->ghi, *gm = s->gmid;
    int side = 0;
    for (int it = 0; it < 200 && fabs(tb - ta) > ttol; it++) {
        /* component with the earliest secant crossing */
        double best = -1, frac = 0.5;
        for (int i = 0; i < nr; i++) {
            if (!((ga[i] < 0 && gb[i] >= 0) || (ga[i] > 0 && gb[i] <= 0))) continue;
            double f = fabs(gb[i]) / fabs(gb[i] - ga[i]); /* fraction from tb back */
            if (f > best) {
                best = f;
                frac = 1 - f;
            }
        }
        if (side == 1) frac *= 0.5; /* Illinois: the same end kept twice, weigh it down */
        if (side == -1) frac = 1 - 0.5 * (1 - frac);
        double tm = ta + frac * (tb - ta);
        double lim = 0.5 * ttol;
        if (fabs(tm - ta) < lim) tm = ta + copysign(lim, tb - ta);
        if (fabs(tb - tm) < lim) tm = tb - copysign(lim, tb - ta);
        dae_dense(s, tm, s->y, s->yp);
        if ((r = daei_call_roots(s, "dae_solve_to", tm, s->y, s->yp, gm)) != BG_OK) return r;
        int left = 0;
        for (int i = 0; i < nr; i++)
            if ((ga[i] < 0 && gm[i] >= 0) || (ga[i] > 0 && gm[i] <= 0)) left = 1;
        if (left) {
            tb = tm;
            memcpy(gb, gm, (size_t)nr * sizeof(double));
            side = -1; /* tb moved: ta is the end kept */
        } else {
            ta = tm;
            memcpy(ga, gm, (size_t)nr * sizeof(double));
            side = 1;
        }
    }
    for (int i = 0; i < nr; i++)
        s->rfound[i] = (ga[i] < 0 && gb[i] >= 0) ? 1 : (ga[i] > 0 && gb[i] <= 0) ? -1 : 0;
    s->troot = tb;
    s->root_pending = 1;
    /* the search goes on from tb; glo must hold g(tb) */
    memcpy(s->glo, gb, (size_t)nr * sizeof(double));
    s->tlo = tb;
    return 1;
}

int dae_roots_found(const dae_solver *s, int *found)
{
    if (!s || !found) return BG_ERR_ARGUMENT;
    for (int i = 0; i < s->p.nroots; i++)
        found[i] = s->rfound[i];
    return BG_OK;
}
