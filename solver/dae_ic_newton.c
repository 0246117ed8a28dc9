/* Consistent initial values, stages B and C (the method: dae_ic.c): the hidden constraints
 * evaluated from the residual, the Newton iteration for y' of the differential and index-1
 * unknowns and y of the index-2 ones, the measurement of the values it returns, and the
 * derivatives of the index-2 unknowns.
 *
 * Differences. Every derivative taken from the residual is a difference extrapolated to step 0
 * by Ridders' method (extrapolate below), which gives an error estimate with the value:
 *   - dF_i/dt of a constraint row (ROW_ALG1), one-sided in t: first a step over which the
 *     residual is smooth in t (hidden_t: an input that changes course shortly after t must not
 *     be differenced across its corner), then the extrapolation from it;
 *   - sum_j dF_i/dy_j y'_j of a constraint row: exact with an analytic Jacobian. With
 *     finite-difference Jacobians, differences of F along v = y' (0 for the index-2 unknowns,
 *     which no constraint row holds), from Y_FIRST times the row's time scale, the time in
 *     which v moves an unknown of the row by its typical size typ_j = |y_j| + atol_j / rtol
 *     (that of the finite-difference Jacobian): central ones, and one-sided ones in the
 *     direction the solution takes; where they disagree beyond their error estimates the
 *     residual has a kink at the state and the one-sided value is taken. The coloured
 *     differences of a Jacobian reach about sqrt(eps) of a row's terms; a constraint such as a
 *     slider crank's velocity constraint at its dead centre, whose terms (22 m/s) cancel to a
 *     derivative of 1e-3, needs the extrapolation;
 *   - stage C's derivatives along (1, v) in (t, y), one-sided: the first (ROW_DIFF, ROW_ALG2
 *     rows) and the second (ROW_ALG1) from the same points.
 * Residuals within what their evaluation can tell from 0 (round-off, and the error estimates of
 * the differences) call for no correction: values given consistent are returned as given.
 * Where the hidden constraints from differences of the residual leave the iteration without a
 * root (a kink of the residual at the state makes them piecewise linear in y'), they are
 * linearised with the Jacobian's entries instead, as with an analytic Jacobian. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dae_ic_impl.h"

#define SAFE 2.0        /* a row stops where its best entry moves by more than SAFE estimates */
#define MEANINGFUL 1e-2 /* once its error estimate is below this part of the row's size */
#define T_FIRST 1e-2    /* the first step in t, relative to the time scale */
#define T_LEVELS 16
#define Y_FIRST 0.1 /* the first step along y', relative to the row's time scale */
#define Y_LEVELS 10 /* steps below the slowest row's scale to the fastest's */
#define C_LEVELS IC_NLEV_C
#define C_MAX_LEVELS 40
#define C_RELIABLE 0.1 /* stage C: y'_A2 kept where its error estimate is below this part */
/* central and one-sided differences that differ by more than KINK times their error
 * estimates: a kink of the residual at the state */
#define KINK 4.0

/* The typical size of unknown j (that of the finite-difference Jacobians). */
static double typ_size(const dae_solver *s, const double *y, int j)
{
    double rt = s->o.rtol > 0 ? s->o.rtol : DBL_EPSILON;
    return fabs(y[j]) + s->atol[j] / rt;
}

/* Per row i (of those with rowsel[rowkind[i]] != 0), the time in which v moves an unknown of
 * the row (through dF/dy, not index 2) by its typical size, times fac, into T (INFINITY where
 * v moves none); the smallest and largest finite ones in *tmin, *tmax (INFINITY, 0 if none). */
static void row_times(const dae_solver *s, const double *y, const double *v, const int *rowsel,
                      double fac, double *T, double *tmin, double *tmax)
{
    int n = s->n;
    for (int i = 0; i < n; i++)
        T[i] = INFINITY;
    for (int j = 0; j < n; j++) {
        if (s->kind[j] == DAE_ALG2 || v[j] == 0) continue;
        double ty = typ_size(s, y, j);
        if (!(ty > 0)) continue;
        double tj = fac * ty / fabs(v[j]);
        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++) {
            int i = s->Jy->rowind[p];
            if (rowsel[s->rowkind[i]]) T[i] = fmin(T[i], tj);
        }
    }
    *tmin = INFINITY;
    *tmax = 0;
    for (int i = 0; i < n; i++)
        if (rowsel[s->rowkind[i]] && isfinite(T[i])) {
            *tmin = fmin(*tmin, T[i]);
            *tmax = fmax(*tmax, T[i]);
        }
}

/* ------------------------------------------------------------- differences ---- */

enum {
    DIFF_T,  /* one-sided in t: (F(te + h, y, y') - F0) / h */
    DIFF_Y,  /* one-sided along v: (F(te, y + h v, y') - F0) / h */
    DIFF_YC, /* central along v: (F(te, y + h v, y') - F(te, y - h v, y')) / (2h) */
    DIFF_TY  /* one-sided along (1, v) at fixed y': (F(h) - F0) / h, and in the constraint rows
                (F(2h) - 2 F(h) + F0) / h^2 */
};

typedef struct ic_diff {
    int mode;
    int all;              /* every row, else the constraint rows */
    int width;            /* table entries a row keeps */
    double h0;            /* the first step (signed) */
    int nlev;             /* steps at most */
    const double *hstart; /* per row: the step from which it takes part (NULL: h0) */
    const double *scale;  /* per row: the size of the terms the derivative balances (NULL: 0) */
} ic_diff;

/* Evaluates the difference of mode at step h into est (rows of the table). f2 holds F(2h) on
 * entry when *have2 (DIFF_TY), and F(h) on return for the next, halved, step. The residual's
 * status (> 0: the point failed). Scratch IC_YK, IC_F1, IC_F2. */
static int diff_point(dae_solver *s, const ic_diff *dd, double te, double h, const double *y,
                      const double *yp, const double *F0, int *have2, double *est)
{
    double *yk = daei_icw(s, IC_YK), *f1 = daei_icw(s, IC_F1), *f2 = daei_icw(s, IC_F2);
    int n = s->n, r;
    switch (dd->mode) {
    case DIFF_T:
        if ((r = daei_ic_res(s, te + h, y, yp, f1)) != 0) return r;
        for (int i = 0; i < n; i++)
            est[i] = (f1[i] - F0[i]) / h;
        return 0;
    case DIFF_Y:
        for (int j = 0; j < n; j++)
            yk[j] = s->kind[j] == DAE_ALG2 ? y[j] : y[j] + h * yp[j];
        if ((r = daei_ic_res(s, te, yk, yp, f1)) != 0) return r;
        for (int i = 0; i < n; i++)
            est[i] = (f1[i] - F0[i]) / h;
        return 0;
    case DIFF_YC:
        for (int sg = 0; sg < 2; sg++) {
            double hh = sg ? -h : h;
            for (int j = 0; j < n; j++)
                yk[j] = s->kind[j] == DAE_ALG2 ? y[j] : y[j] + hh * yp[j];
            if ((r = daei_ic_res(s, te, yk, yp, sg ? f2 : f1)) != 0) return r;
        }
        for (int i = 0; i < n; i++)
            est[i] = (f1[i] - f2[i]) / (2 * h);
        return 0;
    default:
        for (int m = *have2 ? 1 : 2; m >= 1; m--) {
            for (int j = 0; j < n; j++)
                yk[j] = s->kind[j] == DAE_ALG2 ? y[j] : y[j] + m * h * yp[j];
            if ((r = daei_ic_res(s, te + m * h, yk, yp, m == 2 ? f2 : f1)) != 0) {
                *have2 = 0;
                return r;
            }
        }
        for (int i = 0; i < n; i++)
            est[i] = s->rowkind[i] == ROW_ALG1 ? (f2[i] - 2 * f1[i] + F0[i]) / (h * h)
                                               : (f1[i] - F0[i]) / h;
        memcpy(f2, f1, (size_t)n * sizeof *f2);
        *have2 = 1;
        return 0;
    }
}

/* The derivatives of dd's difference, extrapolated (Ridders, "Accurate computation of F'(x)
 * and F'(x) F''(x)", Advances in Engineering Software 4 (1982) 75-76): the differences at the
 * steps h0 / 2^k are the first column of a Neville table per row whose column m removes the
 * term h^m (one-sided: factor 2^m) or h^(2m) (central: 4^m). Each row keeps the entry with
 * the smallest error estimate (the larger of its distances to the entry left of it and to the
 * one above that) and, once that estimate is below MEANINGFUL of the row's size (the
 * derivative and the terms it balances), stops at the step where its highest-order entry moves
 * by more than SAFE times the estimate: from there on round-off rules, and its differences can
 * agree by accident. Large steps lose to the truncation error (and to a corner of an input: the
 * estimates beyond it disagree with those before), small ones to round-off; the table finds
 * the steps between. A row takes part from its hstart on. A point where the residual fails
 * starts the tables anew at the next step. D: the derivative, E: its error estimate
 * (INFINITY where only one step was taken), per row; F0 = F(te, y, y'). DAE_INIT_FAIL when no
 * step worked. Scratch IC_F3, s->ic_tab, s->ic_run and diff_point's. */
static int extrapolate(dae_solver *s, const ic_diff *dd, double te, const double *y,
                       const double *yp, const double *F0, double *D, double *E)
{
    int nr = dd->all ? s->n : s->nalg1_rows, W = dd->width, any = 0, r = 0, active = nr;
    int have2 = 0, *run = s->ic_run;
    double c = dd->mode == DIFF_YC ? 4.0 : 2.0, h = dd->h0, *est = daei_icw(s, IC_F3);
    double *prev = s->ic_tab, *cur = s->ic_tab + (size_t)W * (size_t)nr;
    for (int k = 0; k < nr; k++) {
        int i = dd->all ? k : s->ic_rows[k];
        D[i] = NAN;
        E[i] = INFINITY;
        run[k] = 0;
    }
    for (int lev = 0; lev < dd->nlev && active > 0; lev++, h /= 2) {
        r = diff_point(s, dd, te, h, y, yp, F0, &have2, est);
        if (r < 0) return daei_ic_cb_fail(s, r, "residual (differences)");
        int bad = r > 0 ? -1 : daei_first_nonfinite(est, s->n);
        if (bad >= 0) { /* the residual worked (else its failure is in s->note) */
            char eb[192];
            daei_note(s, "the difference of %.160s at the step %.3g is %g",
                      daei_ename(s, bad, eb, sizeof eb), h, est[bad]);
        }
        if (r > 0 || bad >= 0) {
            for (int k = 0; k < nr; k++)
                if (run[k] > 0) run[k] = 0;
            continue;
        }
        any = 1;
        for (int k = 0; k < nr; k++) {
            int i = dd->all ? k : s->ic_rows[k], rk = run[k];
            if (rk < 0 || (dd->hstart && fabs(h) > fabs(dd->hstart[i]))) continue;
            cur[k] = est[i];
            if (!(E[i] < INFINITY)) D[i] = est[i];
            double fac = 1;
            for (int m = 1; m <= rk; m++) {
                fac *= c;
                double l = cur[(size_t)(m - 1) * nr + k], u = prev[(size_t)(m - 1) * nr + k];
                double a = (fac * l - u) / (fac - 1);
                cur[(size_t)m * nr + k] = a;
                double e = fmax(fabs(a - l), fabs(a - u));
                if (e < E[i]) {
                    E[i] = e;
                    D[i] = a;
                }
            }
            double sc = fabs(D[i]) + (dd->scale ? dd->scale[i] : 0.0);
            if (rk > 0 && E[i] <= MEANINGFUL * sc &&
                fabs(cur[(size_t)rk * nr + k] - prev[(size_t)(rk - 1) * nr + k]) >= SAFE * E[i]) {
                run[k] = -1; /* round-off from here on */
                active--;
            } else if (rk + 1 < W) {
                run[k] = rk + 1;
            } else {
                run[k] = -1; /* its table is full */
                active--;
            }
        }
        double *sw = prev;
        prev = cur;
        cur = sw;
    }
    if (any) return BG_OK;
    char tb[96];
    return bg_error_raise(&s->err, DAE_INIT_FAIL, "dae_consistent_init",
                          "the residual failed at every point of the differences %s at %s: %s",
                          dd->mode == DIFF_T   ? "of the constraints in t"
                          : dd->mode == DIFF_Y ? "of the constraints along y'"
                                               : "for the derivatives of the index-2 unknowns",
                          daei_when(s, s->tn, tb, sizeof tb),
                          s->note[0] ? s->note : "no step was taken");
}

/* ------------------------------------------------------- hidden constraints ---- */

static const int ALG1_ONLY[3] = {0, 1, 0}; /* row classes ROW_DIFF, ROW_ALG1, ROW_ALG2 */
static const int ALL_ROWS[3] = {1, 1, 1};

#define DT_SHRINK 8.0
#define DT_MAX_SHRINKS 14
#define DT_AGREE 1e-3

/* The one-sided second-order difference (-3 F0 + 4 F(te + d) - F(te + 2d)) / (2d) of the
 * constraint rows into D. Scratch IC_F1, IC_F2. */
static int rows_dt2(dae_solver *s, double te, double d, const double *y, const double *yp,
                    const double *F0, double *D)
{
    double *fp = daei_icw(s, IC_F1), *fm = daei_icw(s, IC_F2);
    int r;
    if ((r = daei_ic_res(s, te + d, y, yp, fp)) != 0 ||
        (r = daei_ic_res(s, te + 2 * d, y, yp, fm)) != 0)
        return daei_ic_cb_fail(s, r, "residual (differences of the constraints in t)");
    for (int i = 0; i < s->n; i++)
        D[i] = s->rowkind[i] == ROW_ALG1 ? (-3 * F0[i] + 4 * fp[i] - fm[i]) / (2 * d) : 0.0;
    return BG_OK;
}

/* A step in t over which the residual is smooth at (te, y, yp), into *d (signed): from side
 * T_FIRST times the time scale, divided by DT_SHRINK until two successive second-order
 * differences of the constraint rows agree to DT_AGREE in every one, relative to the estimate
 * plus sc (the size of the terms dF_i/dt balances) and the round-off of the difference (an
 * input that is constant for 5 ns and then ramps, the IVP Test Set's pump, must not be
 * differenced across the ramp); the larger of the two steps, whose points the agreement
 * covered. F0 holds F(te). Scratch IC_HA, IC_DEN, Db (n values) and rows_dt2's. */
static int smooth_step(dae_solver *s, double te, double side, double tscale, const double *y,
                       const double *yp, const double *F0, const double *sc, double *Db, double *d)
{
    double *Da = daei_icw(s, IC_HA), *den = daei_icw(s, IC_DEN);
    *d = side * T_FIRST * tscale;
    int r = rows_dt2(s, te, *d, y, yp, F0, Da);
    if (r != BG_OK) return r;
    daei_ic_row_scales(s, y, yp, den);
    for (int k = 0; k < DT_MAX_SHRINKS; k++) {
        double dn = *d / DT_SHRINK;
        if ((r = rows_dt2(s, te, dn, y, yp, F0, Db)) != BG_OK) return r;
        int agree = 1;
        for (int q = 0; q < s->nalg1_rows && agree; q++) {
            int i = s->ic_rows[q];
            double noise = 10 * DBL_EPSILON * den[i] / fabs(dn);
            if (!(fabs(Db[i] - Da[i]) <= DT_AGREE * (fabs(Db[i]) + sc[i]) + noise)) agree = 0;
        }
        if (agree) break;
        *d = dn;
        memcpy(Da, Db, (size_t)s->n * sizeof *Da);
    }
    return BG_OK;
}

/* dF_i/dt of the constraint rows at (te, y, yp) into Ht, its error estimate into Et; F0 holds
 * F(te), sc the size of the terms dF_i/dt balances (sum_j |dF_i/dy_j y'_j|): the extrapolation
 * from the step smooth_step finds (*tstep). */
static int hidden_t(dae_solver *s, double te, double side, double tscale, const double *y,
                    const double *yp, const double *F0, const double *sc, double *Ht, double *Et,
                    double *tstep)
{
    int r = smooth_step(s, te, side, tscale, y, yp, F0, sc, Ht, tstep);
    if (r != BG_OK) return r;
    ic_diff dd = {DIFF_T, 0, IC_NLEV, *tstep, T_LEVELS, NULL, sc};
    return extrapolate(s, &dd, te, y, yp, F0, Ht, Et);
}

/* Adds sum_j dF_i/dy_j yp_j (j not index 2) to H in the constraint rows: the Jacobian's entries
 * if it is analytic, else the extrapolated one-sided difference along side yp (the direction
 * the solution takes: a kink of the residual in y is differenced on the side the integration
 * goes), whose error estimate
 * goes to Ey (0 elsewhere). hs_i gets the size sum_j |dF_i/dy_j yp_j| (the finite-difference
 * Jacobian's entries: a scale only). */
static int hidden_along(dae_solver *s, double te, double side, int by_jac, const double *y,
                        const double *yp, double *H, double *hs, double *Ey)
{
    int n = s->n;
    for (int i = 0; i < n; i++)
        Ey[i] = 0.0;
    for (int j = 0; j < n; j++)
        if (s->kind[j] != DAE_ALG2)
            for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++) {
                int i = s->Jy->rowind[p];
                if (s->rowkind[i] != ROW_ALG1) continue;
                if (by_jac) H[i] += s->Jy->val[p] * yp[j];
                hs[i] += fabs(s->Jy->val[p] * yp[j]);
            }
    if (by_jac) return BG_OK;
    double *hst = daei_icw(s, IC_TY), *Hy = daei_icw(s, IC_HA), tmin, tmax;
    row_times(s, y, yp, ALG1_ONLY, Y_FIRST, hst, &tmin, &tmax);
    if (!isfinite(tmin) || !(tmin > 0)) return BG_OK; /* yp moves no unknown of a constraint row */
    /* from the slowest row's first step down to 2^-Y_LEVELS of the fastest's */
    tmax = fmin(tmax, ldexp(tmin, IC_NLEV - Y_LEVELS));
    /* central, and one-sided in the direction the solution takes: they agree within their
     * error estimates where the residual is smooth along yp, and the central one is then the
     * more accurate; where they do not, a kink of the residual lies at y (a switch of a
     * model's regime at the state), and the one-sided one is the derivative the solution sees */
    double *Hc = daei_icw(s, IC_YC), *Ec = daei_icw(s, IC_EC);
    ic_diff dd = {DIFF_YC, 0, IC_NLEV, tmax, Y_LEVELS + (int)ceil(log2(tmax / tmin)), hst, hs};
    int r = extrapolate(s, &dd, te, y, yp, s->res, Hc, Ec);
    if (r != BG_OK) return r;
    dd.mode = DIFF_Y;
    dd.h0 = side * tmax;
    if ((r = extrapolate(s, &dd, te, y, yp, s->res, Hy, Ey)) != BG_OK) return r;
    for (int k = 0; k < s->nalg1_rows; k++) {
        int i = s->ic_rows[k];
        if (!isfinite(hst[i])) {
            Ey[i] = 0.0; /* a row that yp does not move: no change */
            continue;
        }
        if (fabs(Hc[i] - Hy[i]) <= KINK * (Ec[i] + Ey[i])) {
            Hy[i] = Hc[i];
            Ey[i] = Ec[i];
        }
        H[i] += Hy[i];
    }
    return BG_OK;
}

/* ------------------------------------------------------------------ stage B ---- */

/* Largest weighted component of a correction u of (y'_D, y'_A1, y_A2) at (y, yp). */
static double corr_norm(const dae_solver *s, const double *u, const double *y, const double *yp)
{
    double m = 0;
    for (int j = 0; j < s->n; j++) {
        double v = s->kind[j] == DAE_ALG2 ? y[j] : yp[j];
        m = fmax(m, fabs(u[j]) / (s->o.rtol * fabs(v) + s->atol[j] + 1e-100));
    }
    return m;
}

/* K^-1 v with the factorization s->kls holds, in place; BG_OK or the solver's status. */
static int k_solve(dae_solver *s, double *v)
{
    double t0 = daei_clock(s);
    int r = ls_solve(s->kls, v, 1);
    s->st.t_linalg += daei_clock(s) - t0;
    return r;
}

static int stage_b(dae_solver *s, double te, double side, double tscale, int by_jac, double *y,
                   double *yp, ic_outcome *out)
{
    const char *w = "dae_consistent_init";
    int n = s->n, r, factored = 0;
    double *F = s->res, *H = daei_icw(s, IC_H), *R = daei_icw(s, IC_R), *u = daei_icw(s, IC_U);
    double *den = daei_icw(s, IC_DEN), *hs = daei_icw(s, IC_SC), *Ht = daei_icw(s, IC_HT);
    double *Et = daei_icw(s, IC_HTE), *Ey = daei_icw(s, IC_HE), *ud = daei_icw(s, IC_UD);
    double uprev = INFINITY;
    char nb[32], tb[96];
    memset(out, 0, sizeof *out);
    out->rworst = -1;
    out->tstep = side * T_FIRST * tscale;
    for (int it = 0;; it++) {
        if ((r = daei_ic_eval_all(s, te, y, yp)) != BG_OK) return r;
        if (s->nalg1_rows > 0) { /* the hidden constraints; their part in t stays (y_D, y_A1
                                    do not change here) */
            if (it == 0) {
                double *sc = daei_icw(s, IC_TY);
                for (int i = 0; i < n; i++)
                    sc[i] = 0.0;
                for (int j = 0; j < n; j++)
                    if (s->kind[j] != DAE_ALG2)
                        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
                            sc[s->Jy->rowind[p]] += fabs(s->Jy->val[p] * yp[j]);
                r = hidden_t(s, te, side, tscale, y, yp, F, sc, Ht, Et, &out->tstep);
                if (r != BG_OK) return r;
            }
            for (int i = 0; i < n; i++) {
                H[i] = s->rowkind[i] == ROW_ALG1 ? Ht[i] : 0.0;
                hs[i] = 1.0 + fabs(H[i]);
            }
            if ((r = hidden_along(s, te, side, by_jac, y, yp, H, hs, Ey)) != BG_OK) return r;
        }
        /* the residual, each row scaled by the size of its terms, and what its evaluation
         * cannot tell from 0: round-off, and the error estimates of the differences */
        daei_ic_row_scales(s, y, yp, den);
        out->rnorm = 0;
        for (int i = 0; i < n; i++) {
            int hid = s->rowkind[i] == ROW_ALG1;
            R[i] = hid ? H[i] : F[i];
            double q = fabs(R[i]) / (hid ? hs[i] : den[i]);
            if (q > out->rnorm || out->rworst < 0) {
                out->rnorm = fmax(out->rnorm, q);
                out->rworst = i;
                out->rhidden = hid;
            }
            double noise = 4 * DBL_EPSILON * (hid ? hs[i] : den[i]);
            if (hid) noise += (isfinite(Et[i]) ? Et[i] : 0) + (isfinite(Ey[i]) ? Ey[i] : 0);
            ud[i] = fabs(R[i]) <= noise ? 0.0 : R[i];
        }
        memcpy(u, R, (size_t)n * sizeof *u);
        /* at round-off, or out of iterations: measured with the last matrix, not applied */
        int roundoff = out->rnorm <= 1e-13;
        if (factored && (roundoff || it == IC_MAX_ITER)) {
            out->unorm = k_solve(s, u) == BG_OK ? corr_norm(s, u, y, yp) : INFINITY;
            out->converged = roundoff;
            return BG_OK;
        }
        sp_csc_zero(s->K);
        for (int p = 0; p < s->Jy->nnz; p++)
            if (s->kslot_y[p] >= 0) s->K->val[s->kslot_y[p]] = s->Jy->val[p];
        for (int p = 0; p < s->Jyp->nnz; p++)
            if (s->kslot_yp[p] >= 0) s->K->val[s->kslot_yp[p]] = s->Jyp->val[p];
        if ((r = daei_ic_factor_solve(s, s->kls, s->K, u)) != BG_OK) {
            int c = ls_singular_col(s->kls);
            return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                                  "the equations for the derivatives and the index-2 unknowns are "
                                  "singular at %s: nothing determines %s%s%s (%s)",
                                  daei_when(s, s->tn, tb, sizeof tb),
                                  c >= 0 && s->kind[c] != DAE_ALG2 ? "the derivative of " : "",
                                  daei_vname(s, c, nb, sizeof nb),
                                  c >= 0 && s->kind[c] == DAE_ALG2
                                      ? "; is it really index 2, and is the index at most 2?"
                                      : "",
                                  ls_get_error(s->kls)->message);
        }
        factored = 1;
        double unorm = corr_norm(s, u, y, yp);
        out->unorm = unorm; /* the measure: from the residual as evaluated */
        /* converged: a negligible correction; one that only residuals within their noise call
         * for; one that no longer decreases (round-off, the noise of the differences: below
         * the tolerance, it counts as converged). None of them is applied */
        if (unorm <= IC_NEGLIGIBLE) {
            out->converged = 1;
            return BG_OK;
        }
        const double *step = u;
        if (memcmp(ud, R, (size_t)n * sizeof *ud) != 0) {
            if (k_solve(s, ud) == BG_OK && corr_norm(s, ud, y, yp) <= IC_NEGLIGIBLE) {
                out->converged = 1;
                return BG_OK;
            }
            step = ud;
        }
        if (unorm < 1 && unorm > 0.5 * uprev) {
            out->converged = 1;
            return BG_OK;
        }
        if (it == IC_MAX_ITER) return BG_OK;
        for (int j = 0; j < n; j++) {
            if (s->kind[j] == DAE_ALG2)
                y[j] -= step[j];
            else
                yp[j] -= step[j];
        }
        uprev = unorm;
    }
}

int daei_ic_failed(const ic_outcome *o)
{
    return (!o->converged && o->rnorm > 1e-6) || o->rnorm > 1e-8;
}

int daei_ic_stage_b(dae_solver *s, double te, double side, double tscale, double *y, double *yp,
                    ic_outcome *out)
{
    int n = s->n, by_jac = s->p.jac != NULL;
    double *sy = daei_icw(s, IC_SY), *syp = daei_icw(s, IC_SYP);
    if (!by_jac) {
        memcpy(sy, y, (size_t)n * sizeof *sy);
        memcpy(syp, yp, (size_t)n * sizeof *syp);
    }
    int r = stage_b(s, te, side, tscale, by_jac, y, yp, out);
    if (r != BG_OK || by_jac || !daei_ic_failed(out)) return r;
    /* With finite-difference Jacobians the hidden constraints come from differences of the
     * residual along y'. Where the residual has a kink at the state (a model's regime that
     * switches there) they are piecewise linear in y' and may have no root; the constraints
     * linearised with the Jacobian's entries, as an analytic Jacobian has them, have one */
    memcpy(y, sy, (size_t)n * sizeof *y);
    memcpy(yp, syp, (size_t)n * sizeof *yp);
    return stage_b(s, te, side, tscale, 1, y, yp, out);
}

/* ------------------------------------------------------------------ stage C ---- */

/* One attempt of stage C from the smooth step tstep: the derivatives of the index-2 unknowns
 * that are reliable into yp where todo[k] (the k-th index-2 unknown), whose todo[k] is then
 * cleared. An estimate's error is at least the round-off of its difference at the row's first
 * (largest) step h: the residual's terms T_i = |F_i| + sum_j |dF_i/dy_j y_j| + |dF_i/dy'_j y'_j|
 * carry eps T_i each, so a first difference 2 eps T_i / h and a second one 4 eps T_i / h^2
 * (Dennis and Schnabel, sec. 5.4): where every step of a row is below the resolution of the
 * residual its differences are equal (or 0) and Ridders' estimate, the distance between the
 * table's entries, says 0. That floor applies where floor != 0: to runs shorter than the time
 * unit (daei_ic_alg2_rates). On longer ones Ridders' estimate is taken alone as before: on
 * the crane's stiff rows (terms of 1e9 N from stiffnesses of 1e8 N/m) the floor rejected rates
 * it had taken, and the steps of a 20 s run moved by up to 9 % (31 311 to 34 115), in both
 * directions, not measured as better or worse. */
static int rates_from(dae_solver *s, double te, double tstep, const double *y, double *yp,
                      double *todo, int floor)
{
    int n = s->n, r;
    double side = te > s->tn ? 1.0 : -1.0, tmin, tmax;
    double *hst = daei_icw(s, IC_TY), *D = daei_icw(s, IC_R), *E = daei_icw(s, IC_HE);
    double *z = daei_icw(s, IC_U), *ze = daei_icw(s, IC_UD), *terms = daei_icw(s, IC_SC);
    /* per row: the first step, the smaller of the row's time scale along (1, v) and of half the
     * step in t over which the residual was found smooth (the points go to twice the step) */
    row_times(s, y, yp, ALL_ROWS, Y_FIRST, hst, &tmin, &tmax);
    double t1 = 0.5 * fabs(tstep), hmax = 0, hmin = INFINITY;
    for (int i = 0; i < n; i++) {
        hst[i] = fmin(hst[i], t1);
        hmax = fmax(hmax, hst[i]);
        hmin = fmin(hmin, hst[i]);
    }
    if (!(hmax > 0) || !(hmin > 0) || !isfinite(hmax)) return BG_OK; /* y'_A2 stays 0 */
    /* the ratio may be NaN or infinite (time scales 0 or not finite from a residual that is
     * not finite near the point): clamp before converting */
    double extra = ceil(log2(hmax / hmin));
    int nlev = isfinite(extra) && extra < C_MAX_LEVELS ? C_LEVELS + (extra > 0 ? (int)extra : 0)
                                                       : C_MAX_LEVELS;
    if (nlev > C_MAX_LEVELS) nlev = C_MAX_LEVELS;
    ic_diff dd = {DIFF_TY, 1, C_LEVELS, side * hmax, nlev, hst, NULL};
    /* s->res holds F at (te, y, yp): stage B's last evaluation */
    for (int i = 0; i < n; i++)
        terms[i] = fabs(s->res[i]);
    for (int j = 0; j < n; j++) {
        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
            terms[s->Jy->rowind[p]] += fabs(s->Jy->val[p] * y[j]);
        for (int p = s->Jyp->colptr[j]; p < s->Jyp->colptr[j + 1]; p++)
            terms[s->Jyp->rowind[p]] += fabs(s->Jyp->val[p] * yp[j]);
    }
    if ((r = extrapolate(s, &dd, te, y, yp, s->res, D, E)) != BG_OK) return r;
    for (int i = 0; i < n; i++) {
        double h = fabs(hst[i]);
        double noise = s->rowkind[i] == ROW_ALG1 ? 4 * DBL_EPSILON * terms[i] / (h * h)
                                                 : 2 * DBL_EPSILON * terms[i] / h;
        z[i] = -D[i];
        ze[i] = isfinite(E[i]) && isfinite(hst[i]) ? fmax(E[i], floor ? noise : 0.0) : INFINITY;
    }
    if (k_solve(s, z) != BG_OK || k_solve(s, ze) != BG_OK) return BG_OK; /* y'_A2 stays 0 */
    for (int k = 0; k < s->na2; k++) {
        int j = s->a2cols[k];
        /* kept where the estimates' error, through the same matrix, is a small part of it */
        if (todo[k] && isfinite(z[j]) && fabs(ze[j]) <= C_RELIABLE * fabs(z[j])) {
            yp[j] = z[j];
            todo[k] = 0;
        }
    }
    return BG_OK;
}

int daei_ic_alg2_rates(dae_solver *s, double te, double tscale, double tstep, const double *y,
                       double *yp)
{
    double *todo = daei_icw(s, IC_YC); /* per index-2 unknown: its rate is still to be found */
    for (int k = 0; k < s->na2; k++)
        todo[k] = 1;
    int floor = tscale < 1.0, r = rates_from(s, te, tstep, y, yp, todo, floor), left = 0;
    for (int k = 0; k < s->na2; k++)
        left += todo[k] != 0;
    if (r != BG_OK || left == 0 || !(tscale < 1.0) || s->nalg1_rows == 0) return r;
    /* Some rates are below what steps within the time scale of the run can resolve (a run of
     * 1e-6 time units of a pendulum swinging in seconds: the second differences of its
     * velocity constraint at 5e-9 are round-off). Those are taken again as for a run of
     * unknown length: the smooth step from the time scale 1, found as in stage B. */
    double *sc = daei_icw(s, IC_HTE), *db = daei_icw(s, IC_HT), side = te > s->tn ? 1.0 : -1.0;
    for (int i = 0; i < s->n; i++)
        sc[i] = 0.0;
    for (int j = 0; j < s->n; j++)
        if (s->kind[j] != DAE_ALG2)
            for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
                sc[s->Jy->rowind[p]] += fabs(s->Jy->val[p] * yp[j]);
    double t1;
    if ((r = smooth_step(s, te, side, 1.0, y, yp, s->res, sc, db, &t1)) != BG_OK) return r;
    if (!(fabs(t1) > fabs(tstep))) return BG_OK;
    return rates_from(s, te, t1, y, yp, todo, 1);
}
