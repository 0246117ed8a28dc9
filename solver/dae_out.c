/* Output of the integrator: dense output from the history's interpolating polynomial, roots of
 * the event functions located on it by the Illinois variant of regula falsi, and the drift from
 * the position constraints g(y) = 0 after each step with, if asked, the projection of y back
 * onto them by the minimum-norm correction. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae_impl.h"

/* t within the last step [tn - hused, tn] up to round-off (hused != 0). */
static int in_last_step(const dae_solver *s, double t)
{
    double tfuzz = 100 * DBL_EPSILON * (fabs(s->tn) + fabs(s->hh));
    if (s->hused < 0) tfuzz = -tfuzz;
    return !((t - (s->tn - s->hused - tfuzz)) * s->hused < 0 ||
             (t - (s->tn + tfuzz)) * s->hused > 0);
}

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
    if (!in_last_step(s, t)) return BG_ERR_ARGUMENT;
    daei_interpolate(s, t, y, yp);
    return BG_OK;
}

/* The interpolant at one unknown, its terms in the order of the difference: y = phi_0 + c_1
 * phi_1 + ... + c_K phi_K, y' = 0 + d_1 phi_1 + ... + d_K phi_K (the 0 kept: -0 + 0 = +0, as
 * the sum started from zero gives). K is a constant where it is inlined: one pass over the
 * unknowns, each difference read once, no sweep of y or y' per order. */
/* (orders above 5, MEBDF only, take the generic loop of daei_interpolate) */
DAEI_INLINE void interp_pass(int K, int n, const double *const *phi, const double *cc,
                             const double *dd, double *restrict y, double *restrict yp)
{
    const double *restrict p0 = phi[0], *restrict p1 = phi[1], *restrict p2 = phi[2],
                           *restrict p3 = phi[3], *restrict p4 = phi[4], *restrict p5 = phi[5];
    const double c1 = cc[1], c2 = cc[2], c3 = cc[3], c4 = cc[4], c5 = cc[5];
    const double d1 = dd[1], d2 = dd[2], d3 = dd[3], d4 = dd[4], d5 = dd[5];
    for (int i = 0; i < n; i++) {
        double a = p0[i], b = 0.0;
        if (y) a += c1 * p1[i];
        if (yp) b += d1 * p1[i];
        if (K >= 2 && y) a += c2 * p2[i];
        if (K >= 2 && yp) b += d2 * p2[i];
        if (K >= 3 && y) a += c3 * p3[i];
        if (K >= 3 && yp) b += d3 * p3[i];
        if (K >= 4 && y) a += c4 * p4[i];
        if (K >= 4 && yp) b += d4 * p4[i];
        if (K >= 5 && y) a += c5 * p5[i];
        if (K >= 5 && yp) b += d5 * p5[i];
        if (y) y[i] = a;
        if (yp) yp[i] = b;
    }
}

/* interp_pass for y and y' (both given), y alone or y' alone, with K a constant. */
DAEI_INLINE void interp_order(int K, int n, const double *const *phi, const double *cc,
                              const double *dd, double *y, double *yp)
{
    if (y && yp)
        interp_pass(K, n, phi, cc, dd, y, yp);
    else if (y)
        interp_pass(K, n, phi, cc, dd, y, NULL);
    else
        interp_pass(K, n, phi, cc, dd, NULL, yp);
}

/* The coefficients of the differences at t: y(t) = phi_0 + sum c_j phi_j, y'(t) = sum d_j phi_j,
 * j = 1 .. K (Brenan et al. sec. 5.2: DASSL's DDATRP). K, the order of the last step. */
static int coefficients(const dae_solver *s, double t, double *cc, double *dd)
{
    double delt = t - s->tn, c = 1, d = 0, gam = delt / s->psi[0];
    int kord = s->kused > 0 ? s->kused : 1;
    for (int j = 1; j <= MAXORD; j++)
        cc[j] = dd[j] = 0;
    for (int j = 1; j <= kord; j++) {
        d = d * gam + c / s->psi[j - 1];
        c = c * gam;
        gam = (delt + s->psi[j - 1]) / s->psi[j];
        cc[j] = c;
        dd[j] = d;
    }
    return kord;
}

void daei_interpolate(const dae_solver *s, double t, double *y, double *yp)
{
    int n = s->n;
    double cc[MAXORD + 1], dd[MAXORD + 1];
    int kord = coefficients(s, t, cc, dd);
    if (!y && !yp) return;
    const double *phi[MAXORD + 1];
    for (int j = 0; j <= MAXORD; j++)
        phi[j] = j <= kord ? s->phi[j] : NULL;
    /* dense output runs at every output time, often several per step: the loops with the order
     * a constant, branch-free, vectorise */
    switch (kord) {
    case 1: interp_order(1, n, phi, cc, dd, y, yp); break;
    case 2: interp_order(2, n, phi, cc, dd, y, yp); break;
    case 3: interp_order(3, n, phi, cc, dd, y, yp); break;
    case 4: interp_order(4, n, phi, cc, dd, y, yp); break;
    case 5: interp_order(5, n, phi, cc, dd, y, yp); break;
    default: /* MEBDF's k = 6, 7: the same terms in the same order, unknown by unknown */
        for (int i = 0; i < n; i++) {
            double a = s->phi[0][i], b = 0.0;
            for (int j = 1; j <= kord; j++) {
                a += cc[j] * s->phi[j][i];
                b += dd[j] * s->phi[j][i];
            }
            if (y) y[i] = a;
            if (yp) yp[i] = b;
        }
        break;
    }
}

void daei_interpolate_some(const dae_solver *s, double t, const int *idx, int m, double *y,
                           double *yp)
{
    double cc[MAXORD + 1], dd[MAXORD + 1];
    int kord = coefficients(s, t, cc, dd);
    /* the differences' addresses at hand: stores into y and yp could otherwise change s->phi
     * for all the compiler knows, and it would read them again for every term */
    const double *ph[MAXORD + 1];
    for (int j = 0; j <= kord; j++)
        ph[j] = s->phi[j];
    for (int k = 0; k < m; k++) { /* each term in interp_pass's order */
        int i = idx[k];
        double a = ph[0][i], b = 0.0;
        for (int j = 1; j <= kord; j++) {
            a += cc[j] * ph[j][i];
            b += dd[j] * ph[j][i];
        }
        if (y) y[i] = a;
        if (yp) yp[i] = b;
    }
}

int dae_set_output_unknowns(dae_solver *s, const int *idx, int m)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (m < 0 || (m > 0 && !idx))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_set_output_unknowns",
                              "%d unknowns given%s", m, m > 0 ? " without their indices" : "");
    for (int k = 0; k < m; k++)
        if (idx[k] < 0 || idx[k] >= s->n)
            return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_set_output_unknowns",
                                  "unknown %d (entry %d) is outside 0 .. %d", idx[k], k, s->n - 1);
    int *c = NULL;
    if (m > 0) {
        c = malloc((size_t)m * sizeof *c);
        if (!c) return bg_error_raise(&s->err, BG_ERR_MEMORY, "dae_set_output_unknowns",
                                      "out of memory");
        memcpy(c, idx, (size_t)m * sizeof *c);
    }
    free(s->out_idx);
    s->out_idx = c;
    s->nout_idx = m;
    return BG_OK;
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
    if (s->nout_idx > 0 && !s->o.projection && s->initialized && !s->first && s->hused != 0 &&
        in_last_step(s, t)) { /* the unknowns asked for (dae_set_output_unknowns) */
        daei_interpolate_some(s, t, s->out_idx, s->nout_idx, y, yp);
        return;
    }
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
