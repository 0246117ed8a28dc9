/* Static equilibrium of a DAE by pseudo-transient and load continuation with a damped Newton
 * iteration (the method and its reasons are in bg_static.h). */
#include "bg_static.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bg_frame.h"
#include "bg_jaceval.h"

int dae_static_options_default(dae_static_options *o)
{
    if (!o) return BG_ERR_ARGUMENT;
    memset(o, 0, sizeof *o);
    o->rtol = 1e-8;
    o->atol = 1e-8;
    o->max_newton = 12;
    o->max_steps = 400;
    o->continuation = 1;
    o->dlambda = 1.0;
    o->dlambda_min = 1e-5;
    o->h0 = 1e3;
    o->h_max = 1e9;
    o->linsol = LS_KLU;
    return BG_OK;
}

typedef struct st_ctx {
    const dae_problem *p;
    const dae_static_options *o;
    int n;
    double t;
    bg_jaceval J;
    sp_union *u;
    ls_solver *ls;
    double *r0;        /* F(t, y_start, yp_s): the homotopy's offset (NULL with a load callback) */
    double *yps;       /* yp_s */
    double *ypw;       /* yp of the current evaluation */
    double *yprev;     /* last accepted state */
    double *G, *Gt, *d, *dt, *yt, *w;
    double lambda_set; /* the load factor the callback was last given (NAN: none yet) */
    dae_static_result *r;
    bg_error *err;
    int singular_col;
    int fatal;        /* a callback's fatal status */
    int load_status;  /* options.load's status when it failed (0: it did not) */
    int have_mat;     /* a factored Newton matrix is kept (newton) */
    double alpha_min; /* the smallest damping factor before newton gives up */
    int newton_scale; /* newton's iteration limit in units of max_newton */
    double H_mat;     /* the pseudo-time step it was formed with */
    /* position constraints of the problem (dae_problem.cons): kept at their starting values */
    aat_solver *aat;
    sp_csc *Gc;
    double *g0, *gv, *gw;
} st_ctx;

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void weights(st_ctx *c, const double *y)
{
    const double *nom = c->p->nominal;
    for (int i = 0; i < c->n; i++)
        c->w[i] = c->o->rtol * fabs(y[i]) + c->o->atol * (nom ? nom[i] : 1.0);
}

/* Weighted max norm of v; *arg (may be NULL) the index of the largest entry. */
static double wnorm(const st_ctx *c, const double *v, int *arg)
{
    double m = 0;
    int k = -1;
    for (int i = 0; i < c->n; i++) {
        double a = fabs(v[i]) / c->w[i];
        if (!(a <= m)) { /* NaN wins */
            m = a;
            k = i;
            if (isnan(a)) break;
        }
    }
    if (arg) *arg = k;
    return m;
}

/* G(y) for the load factor lam and pseudo-time step H from c->yprev (H = INFINITY: yp = yp_s).
 * 0, > 0 (recoverable failure or a value not finite), < 0 fatal (c->fatal). */
static int geval(st_ctx *c, const double *y, double lam, double H, double *G)
{
    const dae_static_options *o = c->o;
    for (int i = 0; i < c->n; i++)
        c->ypw[i] = c->yps[i] + (isinf(H) ? 0.0 : (y[i] - c->yprev[i]) / H);
    if (o->load && lam != c->lambda_set) {
        int st = o->load(o->load_user, lam);
        if (st != 0) { /* any status but 0 (the regimes' rule): the load's callback failed */
            c->load_status = st;
            return c->fatal = st < 0 ? st : -1;
        }
        c->lambda_set = lam;
    }
    int st = bg_jaceval_res(&c->J, c->t, y, c->ypw, G);
    if (st < 0) return c->fatal = st;
    if (st > 0) return st;
    if (c->r0)
        for (int i = 0; i < c->n; i++)
            G[i] -= (1.0 - lam) * c->r0[i];
    for (int i = 0; i < c->n; i++)
        if (!isfinite(G[i])) return 1;
    return 0;
}

/* The Newton matrix dF/dy + dF/dy'/H factored: with eval, the Jacobian evaluated at y first
 * (c->ypw set by the last geval at y), else formed again from the saved one (another H). */
static int newton_matrix(st_ctx *c, const double *y, double H, int eval)
{
    if (eval) {
        int st = bg_jaceval_eval(&c->J, c->t, y, c->ypw, NULL);
        if (st < 0) return c->fatal = st;
        if (st > 0) return st;
    }
    c->have_mat = 0;
    sp_union_combine(c->u, c->J.Jy, 1.0, c->J.Jyp, isinf(H) ? 0.0 : 1.0 / H);
    c->r->factorizations++;
    int st = ls_factor(c->ls, c->u->M);
    if (st == BG_ERR_SINGULAR) {
        c->singular_col = ls_singular_col(c->ls);
        return st;
    }
    if (st == BG_ERR_NONFINITE) return 1;
    if (st == BG_OK) {
        c->have_mat = 1;
        c->H_mat = H;
    }
    return st;
}

/* One continuation step: modified Newton on G from y (in place). 0 converged, 1 not converged,
 * < 0 a fatal error (BG_ERR_SINGULAR, a callback's, the linear solver's). *iters: the
 * iterations.
 *
 * The factored matrix is kept across iterations and steps, with the integrator's refresh rules
 * (dae_nls.c, after CVODE and IDA): formed again from the saved Jacobian when H has moved by
 * more than STATIC_DGMAX from the H it was factored with (CVODE's dgmax on gamma); the Jacobian
 * evaluated again at the current iterate, and the iteration continued from there, when a matrix
 * of an earlier iterate contracts at a rate worse than STATIC_RATE_REFRESH, would need more
 * iterations at its rate than the budget has left, fails the damping test
 * at the full step, or follows a damped step (a failure on a stale matrix is redone with a fresh
 * one, never reported). exact: a fresh matrix at every iterate (a step without a predictor:
 * the first, and every step of continuation = 0, where a kept matrix can lead the iteration away).
 * The iteration fails when the damping factor goes below c->alpha_min (Deuflhard's test, on a
 * fresh matrix), or after lim = max_newton c->newton_scale iterations unless the last rate says
 * it converges within the budget (2 lim; dae_nls.c's extension at a good rate). */
#define STATIC_DGMAX 0.3
#define STATIC_RATE_REFRESH 0.5
#define STATIC_STEADY_TOL 1e-4 /* bg_jaceval_steadiness's ratio of a steady motion, at most */
enum { STATIC_NEWTON_FULL = 5, STATIC_MAX_NEWTON = 10000 };
static int newton(st_ctx *c, double *y, double lam, double H, int exact, int *iters)
{
    const int n = c->n, lim = c->o->max_newton * c->newton_scale, budget = exact ? lim : 2 * lim;
    dae_static_result *r = c->r;
    *iters = 0;
    int st = geval(c, y, lam, H, c->G);
    if (st) return st < 0 ? st : 1;
    int at_y = 0; /* the matrix's Jacobian was evaluated at the current iterate */
    if (!c->have_mat) {
        if ((st = newton_matrix(c, y, H, 1)) != 0) return st < 0 ? st : 1;
        at_y = 1;
    } else if (!exact && fabs(c->H_mat / H - 1.0) > STATIC_DGMAX) {
        if ((st = newton_matrix(c, y, H, 0)) != 0) return st < 0 ? st : 1;
    }
    double nd_prev = 0; /* the last correction */
    int refresh = exact;
    while (*iters < budget) {
        if (refresh && !at_y) { /* the Jacobian at the current iterate (c->ypw of its G) */
            if ((st = geval(c, y, lam, H, c->G)) != 0) return st < 0 ? st : 1;
            if ((st = newton_matrix(c, y, H, 1)) != 0) return st < 0 ? st : 1;
            at_y = 1;
            nd_prev = 0;
        }
        refresh = 0;
        (*iters)++;
        r->newton_iters++;
        weights(c, y);
        for (int i = 0; i < n; i++)
            c->d[i] = -c->G[i];
        if ((st = ls_solve(c->ls, c->d, 1)) != BG_OK) return st;
        double nd = wnorm(c, c->d, &r->worst_var);
        r->correction = nd;
        double rate = nd_prev > 0 ? nd / nd_prev : 0;
        if (!at_y && (!isfinite(nd) || rate > STATIC_RATE_REFRESH ||
                      (rate > 0 && nd > 1 && *iters + ceil(log(nd) / -log(rate)) > budget))) {
            refresh = 1;
            continue;
        }
        if (!isfinite(nd)) return 1;
        /* beyond max_newton only while the rate says it converges within the budget */
        const double tol = 1.0;
        if (*iters >= lim && nd > tol &&
            !(rate > 0 && *iters + ceil(log(nd / tol) / -log(rate)) <= budget))
            return 1;
        if (nd <= tol) {
            for (int i = 0; i < n; i++)
                y[i] += c->d[i];
            return 0;
        }
        /* damping: the simplified correction at the trial point must shrink */
        double alpha = 1.0, ndt = INFINITY;
        for (;;) {
            for (int i = 0; i < n; i++)
                c->yt[i] = y[i] + alpha * c->d[i];
            st = geval(c, c->yt, lam, H, c->Gt);
            if (st < 0) return st;
            if (st == 0) {
                for (int i = 0; i < n; i++)
                    c->dt[i] = -c->Gt[i];
                if ((st = ls_solve(c->ls, c->dt, 1)) != BG_OK) return st;
                ndt = wnorm(c, c->dt, NULL);
                if (ndt <= (1.0 - 0.25 * alpha) * nd) break;
            }
            if (!at_y) { /* a stale matrix does not damp: a fresh one first */
                refresh = 1;
                break;
            }
            alpha *= 0.5;
            if (alpha < c->alpha_min) return 1;
        }
        if (refresh) continue;
        memcpy(y, c->yt, (size_t)n * sizeof *y);
        memcpy(c->G, c->Gt, (size_t)n * sizeof *c->G);
        if (alpha == 1.0 && ndt <= tol && (at_y || ndt <= STATIC_RATE_REFRESH * nd)) {
            /* the simplified correction finishes it */
            for (int i = 0; i < n; i++)
                y[i] += c->dt[i];
            r->correction = ndt;
            return 0;
        }
        at_y = 0; /* the iterate moved */
        nd_prev = alpha == 1.0 ? nd : 0;
        refresh = exact || alpha < 1.0; /* a damped step: the global phase, a fresh matrix each
                                           time */
    }
    return 1;
}

/* The scaled residual of F(t, y, yp_s) at the end (or at the last state on failure). */
static void final_residual(st_ctx *c, const double *y)
{
    dae_static_result *r = c->r;
    int n = c->n;
    r->residual = NAN;
    r->residual_eq = -1;
    r->residual_abs = NAN;
    if (geval(c, y, 1.0, INFINITY, c->G) < 0) return; /* lambda = 1: F itself */
    weights(c, y);
    if (bg_jaceval_eval(&c->J, c->t, y, c->ypw, NULL) != 0) return;
    /* sum_j |M_ij| w_j with M = dF/dy (at rest) */
    double *s = c->Gt;
    memset(s, 0, (size_t)n * sizeof *s);
    const sp_csc *A = c->J.Jy;
    for (int j = 0; j < n; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            s[A->rowind[p]] += fabs(A->val[p]) * c->w[j];
    double best = -1;
    for (int i = 0; i < n; i++) {
        double v = fabs(c->G[i]) / (s[i] > 0 ? s[i] : 1e-300);
        if (!(v <= best)) {
            best = v;
            r->residual_eq = i;
            if (isnan(v)) break;
        }
    }
    r->residual = best;
    r->residual_abs = r->residual_eq >= 0 ? fabs(c->G[r->residual_eq]) : NAN;
}

/* Minimum-norm Gauss-Newton correction of y onto g(t, y) = g(t, y_start) (3 iterations at
 * most): the invariants the pseudo-time steps keep only to second order in the rotations,
 * restored for the problems that declare them. 0, or a status. */
static int project_cons(st_ctx *c, double *y)
{
    const dae_problem *p = c->p;
    for (int it = 0; it < 3; it++) {
        int st = p->cons(p->user, c->t, y, c->gv, c->Gc);
        if (st != 0) return st < 0 ? (c->fatal = st) : st;
        double gmax = 0;
        for (int k = 0; k < p->ncons; k++) {
            c->gv[k] -= c->g0[k];
            gmax = fmax(gmax, fabs(c->gv[k]));
        }
        if (gmax == 0) break;
        if ((st = aat_factor(c->aat, c->Gc, 0.0)) != BG_OK) return st;
        if ((st = aat_solve(c->aat, c->gv, c->gw)) != BG_OK) return st;
        sp_matvec_t(c->Gc, -1.0, c->gw, 0.0, c->dt);
        for (int i = 0; i < c->n; i++)
            y[i] += c->dt[i];
        weights(c, y);
        if (wnorm(c, c->dt, NULL) < 1e-3) break;
    }
    return 0;
}

static void ctx_free(st_ctx *c)
{
    aat_free(&c->aat);
    sp_csc_free(&c->Gc);
    free(c->g0);
    free(c->gv);
    free(c->gw);
    bg_jaceval_free(&c->J);
    sp_union_free(&c->u);
    ls_free(&c->ls);
    free(c->r0);
    free(c->yps);
    free(c->ypw);
    free(c->yprev);
    free(c->G);
    free(c->Gt);
    free(c->d);
    free(c->dt);
    free(c->yt);
    free(c->w);
}

/* Every check of dae_static_solve's options and problem data, in one place: the options, then
 * the problem's nominal magnitudes and the starting state (bg_check_nominal, bg_check_state:
 * the integrator's rules and words). BG_OK or the status, with a message naming the value. */
static int check_options(const dae_problem *p, const dae_static_options *o, const double *y,
                         bg_error *err)
{
    const char *w = "dae_static_solve";
    if (!(o->rtol >= 0 && o->rtol < 1) || !(o->atol >= 0 && isfinite(o->atol)) ||
        !(o->rtol > 0 || o->atol > 0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "tolerances rtol in [0, 1) and atol >= 0, not both 0 (got %g, %g)",
                              o->rtol, o->atol);
    if (o->max_newton < 1 || o->max_newton > STATIC_MAX_NEWTON || o->max_steps < 1)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "max_newton in [1, %d] and max_steps >= 1 (got %d, %ld)",
                              STATIC_MAX_NEWTON, o->max_newton, o->max_steps);
    if (o->continuation != 0 && o->continuation != 1)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "continuation is 0 or 1 (got %d)",
                              o->continuation);
    if (!(o->dlambda > 0 && o->dlambda <= 1) || !(o->dlambda_min > 0 && o->dlambda_min <= o->dlambda))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "dlambda in (0, 1] and dlambda_min in (0, dlambda] (got %g, %g)",
                              o->dlambda, o->dlambda_min);
    if (!(o->h0 > 0) || !(o->h_max >= o->h0) || isinf(o->h_max) || isinf(o->h0))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "pseudo-time steps 0 < h0 <= h_max, finite (got %g, %g)", o->h0,
                              o->h_max);
    if (o->linsol != LS_KLU && o->linsol != LS_DENSE)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "linsol is %d: expected a linear solver, 0 (LS_KLU) or 1 (LS_DENSE)",
                              (int)o->linsol);
    int st = o->yp_steady ? bg_check_state(p, o->yp_steady, "steady rate (yp_steady)",
                                           BG_ERR_ARGUMENT, w, err)
                          : BG_OK;
    if (st == BG_OK) st = bg_check_nominal(p, w, err);
    if (st == BG_OK) st = bg_check_state(p, y, "starting value", BG_ERR_NONFINITE, w, err);
    return st;
}

/* A steady state in a co-moving frame (bg_static.h, "Co-moving frames"): the state at rest of
 * the problem in the frame, G(t, z, z') = F(t, z, S z + c + z') with c = yp_steady, then the
 * check that it stays a solution along the frame's flow. */
static int static_in_frame(const dae_problem *p, const dae_static_options *o, double t, double *y,
                           double *yp, dae_static_result *r, bg_error *err)
{
    const char *where = "dae_static_solve";
    bg_frame f;
    int st = bg_frame_init(&f, p, o->frame, o->yp_steady, where, err);
    if (st != BG_OK) return r->status = st;
    dae_static_options oi = *o;
    oi.frame = NULL;
    oi.yp_steady = NULL;
    st = dae_static_solve(&f.q, &oi, t, y, NULL, r, err);
    double *ys = NULL;
    if (st == BG_OK) { /* y' = S y + c, steady along the frame's flow? */
        ys = malloc((size_t)p->n * sizeof *ys);
        if (!ys) {
            st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
            goto done;
        }
        memcpy(ys, f.c, (size_t)p->n * sizeof *ys);
        sp_matvec(o->frame, 1.0, y, 1.0, ys);
        double ratio = 0;
        int row = -1;
        st = bg_frame_steadiness(p, o->frame, t, y, ys, &ratio, &row, where, err);
        if (st != BG_OK) goto done;
        if (ratio > STATIC_STEADY_TOL) {
            char eb[256];
            st = bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                "the frame gives no steady motion: the state found is at rest in "
                                "the frame at this instant, but %s changes along the frame's "
                                "motion (%.3g of its terms): the model is not invariant under "
                                "the frame's motion (a load or a support that does not turn "
                                "with it), or the generator S does not follow the kinds of its "
                                "unknowns",
                                bg_eq_label(p, row, eb, sizeof eb), ratio);
            goto done;
        }
        if (yp) memcpy(yp, ys, (size_t)p->n * sizeof *yp);
    }
done:
    free(ys);
    bg_frame_free(&f);
    return r->status = st;
}

int dae_static_solve(const dae_problem *p, const dae_static_options *opt, double t, double *y,
                     double *yp, dae_static_result *res, bg_error *err)
{
    const char *where = "dae_static_solve";
    dae_static_result rloc;
    dae_static_result *r = res ? res : &rloc;
    memset(r, 0, sizeof *r);
    r->residual_eq = r->worst_var = -1;
    r->residual = r->residual_abs = NAN;
    double t_start = now_seconds();
    if (!p || !y)
        return r->status = bg_error_raise(err, BG_ERR_ARGUMENT, where, "%s is NULL",
                                          !p ? "the problem" : "y");
    if (p->n < 1 || !p->res)
        return r->status = bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                          "the problem needs n >= 1 and a residual");
    if (!isfinite(t))
        return r->status = bg_error_raise(err, BG_ERR_ARGUMENT, where, "t is not finite");
    dae_static_options od;
    if (!opt) dae_static_options_default(&od);
    const dae_static_options *o = opt ? opt : &od;
    int st = check_options(p, o, y, err);
    if (st) return r->status = st;
    if (o->frame) return static_in_frame(p, o, t, y, yp, r, err);
    const int n = p->n;

    st_ctx c;
    memset(&c, 0, sizeof c);
    c.p = p;
    c.o = o;
    c.n = n;
    c.t = t;
    c.r = r;
    c.err = err;
    c.lambda_set = NAN;
    c.singular_col = -1;
    if ((st = bg_jaceval_init(&c.J, p, err)) != BG_OK) return r->status = st;
    size_t sz = (size_t)n * sizeof(double);
    c.yps = calloc(1, sz);
    c.ypw = malloc(sz);
    c.yprev = malloc(sz);
    c.G = malloc(sz);
    c.Gt = malloc(sz);
    c.d = malloc(sz);
    c.dt = malloc(sz);
    c.yt = malloc(sz);
    c.w = malloc(sz);
    c.u = sp_union_create(c.J.Jy, c.J.Jyp);
    if (!c.yps || !c.ypw || !c.yprev || !c.G || !c.Gt || !c.d || !c.dt || !c.yt || !c.w || !c.u) {
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
        goto done;
    }
    c.ls = ls_create(o->linsol, c.u->M, err);
    if (!c.ls) {
        st = err && err->status < 0 ? err->status : BG_ERR_LIBRARY;
        goto done;
    }
    if (o->yp_steady) memcpy(c.yps, o->yp_steady, sz);
    memcpy(c.yprev, y, sz);

    if (p->ncons > 0 && p->cons && p->cons_pattern) { /* declared position constraints */
        c.aat = aat_create(p->cons_pattern, err);
        c.Gc = sp_csc_copy(p->cons_pattern);
        c.g0 = malloc((size_t)p->ncons * sizeof *c.g0);
        c.gv = malloc((size_t)p->ncons * sizeof *c.gv);
        c.gw = malloc((size_t)p->ncons * sizeof *c.gw);
        if (!c.aat || !c.Gc || !c.g0 || !c.gv || !c.gw) {
            st = c.aat ? bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory")
                       : (err && err->status < 0 ? err->status : BG_ERR_LIBRARY);
            goto done;
        }
        if ((st = p->cons(p->user, t, y, c.g0, NULL)) != 0) {
            st = bg_error_raise(err, BG_ERR_CALLBACK, where,
                                "the constraint function returned %d at the start", st);
            goto done;
        }
    }
    double lam = o->continuation ? 0.0 : 1.0, dlam = o->dlambda, H = o->h0;
    if (!o->load) { /* the homotopy's offset: the residual at the start */
        c.r0 = malloc(sz);
        if (!c.r0) {
            st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
            goto done;
        }
        memset(c.r0, 0, sz);
        if (o->continuation) {
            st = geval(&c, y, 1.0, INFINITY, c.r0);
            if (st != 0) {
                char nb[256];
                int bad = -1;
                for (int i = 0; i < n && bad < 0; i++)
                    if (!isfinite(c.r0[i])) bad = i;
                st = st < 0 ? BG_ERR_CALLBACK : BG_ERR_NONFINITE;
                bg_error_raise(err, st, where,
                               "the residual cannot be evaluated at the starting state%s%s",
                               bad >= 0 ? ": not finite in " : "",
                               bad >= 0 ? bg_eq_label(p, bad, nb, sizeof nb) : "");
                goto done;
            }
        }
    }
    double *ytry = malloc(sz);
    if (!ytry) {
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
        goto done;
    }
    const double h_min = o->h0 * 1e-8;
    /* The last state at rest (an equilibrium under lam_rest); a step to a larger load factor
     * whose end is still moving (beyond a limit point the pseudo-time steps follow the motion
     * instead of failing) is followed by settling steps at the same load factor, and given up
     * for a smaller increment after SETTLE_MAX of them. */
    enum { SETTLE_MAX = 8 };
    double *yrest = malloc(sz), lam_rest = lam, lam_cur = lam;
    /* the state at rest before it (lam_old < lam_rest: the secant predictor's other point) */
    double *yold = malloc(sz), lam_old = NAN;
    int settling = 0, can_shrink = o->continuation, rejected_since = 0;
    if (!yrest || !yold) {
        free(yrest);
        free(yold);
        free(ytry);
        st = bg_error_raise(err, BG_ERR_MEMORY, where, "out of memory");
        goto done;
    }
    memcpy(yrest, y, sz);
    int ok = 0;
    st = DAE_TOO_MUCH_WORK;
    while (r->steps + r->rejected < o->max_steps) {
        double lt = settling ? lam_cur : (lam_rest < 1.0 ? fmin(1.0, lam_rest + dlam) : 1.0);
        if (!o->continuation) lt = 1.0;
        if (lt > 1.0 - 1e-12) lt = 1.0;
        memcpy(ytry, c.yprev, sz);
        int predicted = !settling && lt > lam_rest && lam_old < lam_rest;
        if (predicted) {
            /* secant predictor along the equilibrium path (Allgower and Georg, Introduction to
             * Numerical Continuation Methods, 2003, sec. 2.2): Newton starts from the
             * extrapolation of the last two states at rest, an error of second order in the
             * increment instead of first */
            double f = (lt - lam_rest) / (lam_rest - lam_old);
            for (int i = 0; i < n; i++)
                ytry[i] += f * (yrest[i] - yold[i]);
        }
        int iters = 0;
        /* a step the continuation can shrink gives up at a damping factor of 0.1 (a smaller
         * increment is cheaper than a long damped iteration) the first time; once a smaller
         * increment has failed too (what is hard is not the load's increment: a kink of a
         * valve's characteristic, a neutral direction), at the full load, and without
         * continuation, the damping goes down to 1e-4 */
        c.alpha_min = can_shrink && lt < 1.0 && !rejected_since ? 0.1 : 1e-4;
        c.newton_scale = o->continuation ? 1 : STATIC_NEWTON_FULL;
        int nst = newton(&c, ytry, lt, H, !predicted, &iters);

        if (nst < 0 && nst != BG_ERR_SINGULAR) { /* fatal */
            st = c.fatal ? BG_ERR_CALLBACK : nst;
            if (c.load_status)
                bg_error_raise(err, st, where, "the load callback (options.load) returned %d at "
                               "load factor %g", c.load_status, lt);
            else if (c.fatal)
                bg_error_raise(err, st, where, "the residual or Jacobian failed (status %d) at "
                               "load factor %g", c.fatal, lt);
            else
                bg_error_raise(err, st, where, "linear solver: %s", ls_get_error(c.ls)->message);
            goto out;
        }
        int back_off = 0;
        if (nst != 0) { /* not converged (or singular): a smaller step */
            r->rejected++;
            back_off = 1;
            rejected_since = 1;
        } else {
            /* accepted */
            if (c.aat) {
                int pst = project_cons(&c, ytry);
                if (pst < 0) {
                    st = c.fatal ? BG_ERR_CALLBACK : pst;
                    bg_error_raise(err, st, where, "projection onto the position constraints: %s",
                                   c.fatal ? "the constraint function failed"
                                           : aat_get_error(c.aat)->message);
                    goto out;
                }
            }
            r->steps++;
            weights(&c, ytry);
            for (int i = 0; i < n; i++)
                c.d[i] = ytry[i] - c.yprev[i];
            r->change = wnorm(&c, c.d, NULL);
            r->h = H;
            /* at rest? the Newton correction towards the equilibrium at this load factor
             * (y' = yp_s exactly) against the step's change */
            double defect = INFINITY;
            if (geval(&c, ytry, lt, INFINITY, c.Gt) == 0) {
                for (int i = 0; i < n; i++)
                    c.dt[i] = -c.Gt[i];
                if (ls_solve(c.ls, c.dt, 1) == BG_OK) defect = wnorm(&c, c.dt, NULL);
            }
            memcpy(c.yprev, ytry, sz);
            memcpy(y, ytry, sz);
            if (defect <= fmax(1.0, 1e-2 * r->change)) { /* at rest */
                settling = 0;
                if (lt > lam_rest) {
                    memcpy(yold, yrest, sz);
                    lam_old = lam_rest;
                }
                lam_rest = lt;
                memcpy(yrest, ytry, sz);
                r->lambda = lam_rest;
                if (lt >= 1.0 && r->change <= 1.0) {
                    ok = 1;
                    st = BG_OK;
                    break;
                }
                /* the next increment from this step's iterations (Crisfield, Comput. Struct.
                 * 13 (1981) 55: the increment times sqrt(I_d / I), I_d = max_newton, within
                 * [1/2, 2]); not grown right after a rejected step */
                double g = sqrt((double)o->max_newton / (iters > 0 ? iters : 1));
                dlam = fmin(1.0, fmax(o->dlambda_min,
                                      dlam * fmin(rejected_since ? 1.0 : 2.0, fmax(0.5, g))));
                rejected_since = 0;
                if (iters <= (o->max_newton + 1) / 2) H = fmin(o->h_max, 10.0 * H);
                continue;
            }
            /* still moving: settle at this load factor with longer pseudo-time steps */
            lam_cur = lt;
            H = fmin(o->h_max, 10.0 * H);
            if (++settling <= SETTLE_MAX) continue;
            back_off = 1; /* no equilibrium near: a smaller increment from the last rest */
            r->rejected++;
        }
        if (back_off) {
            if (settling) { /* back to the last state at rest */
                settling = 0;
                memcpy(c.yprev, yrest, sz);
                memcpy(y, yrest, sz);
            }
            if (can_shrink && lam_rest < 1.0 && dlam > o->dlambda_min) {
                dlam = fmax(0.25 * dlam, o->dlambda_min);
                if (nst == BG_ERR_SINGULAR) H = fmax(0.25 * H, h_min);
                continue;
            }
            if (nst != 0 && H > h_min) {
                H = fmax(0.25 * H, h_min);
                continue;
            }
            if (nst == BG_ERR_SINGULAR) {
                char nb[256];
                st = bg_error_raise(err, BG_ERR_SINGULAR, where,
                                    "the Newton matrix is singular at load factor %g: nothing "
                                    "determines %s at rest (a mechanism, or a free motion under "
                                    "a load)",
                                    lt, bg_var_label(p, c.singular_col, nb, sizeof nb));
                r->worst_var = c.singular_col;
                free(yrest);
                yrest = NULL;
                free(yold);
                yold = NULL;
                goto out;
            }
            st = DAE_CONV_FAIL;
            break;
        }
    }
    if (!ok && settling) { /* the run ended moving: report the last state at rest */
        memcpy(y, yrest, sz);
    }
    free(yrest);
    yrest = NULL;
    free(yold);
    yold = NULL;
    final_residual(&c, y);
    if (ok && o->yp_steady) { /* constant rates: a steady motion only if it stays a solution */
        double ratio;
        int row;
        if (bg_jaceval_steadiness(&c.J, t, y, c.yps, NULL, &ratio, &row) == 0 &&
            ratio > STATIC_STEADY_TOL) {
            char eb[256];
            ok = 0;
            st = bg_error_raise(err, BG_ERR_ARGUMENT, where,
                                "the rates yp_steady give no steady motion: the state found "
                                "solves the equations at this instant, but %s changes along the "
                                "motion (%.3g of its terms), so the motion does not keep it (a "
                                "structure spinning in the inertial frame has no state of "
                                "constant rates: find it at rest in a co-moving frame, "
                                "options.frame)",
                                bg_eq_label(p, row, eb, sizeof eb), ratio);
            goto out;
        }
    }
    if (!ok) {
        char eb[256], vb[256], why[512];
        if (st == DAE_TOO_MUCH_WORK) /* the budget, not the problem */
            snprintf(why, sizeof why,
                     "the step budget ran out: max_steps = %ld continuation steps (%ld accepted, "
                     "%ld rejected)%s",
                     o->max_steps, r->steps, r->rejected,
                     r->lambda < 1 ? "" : " reached the full load, but the state was still moving");
        else if (!o->continuation)
            snprintf(why, sizeof why,
                     "without load continuation (continuation = 0) the full load at once did not "
                     "converge, down to the smallest pseudo-time step %g (continuation = 1 "
                     "ramps the load)",
                     h_min);
        else if (r->lambda < 1)
            snprintf(why, sizeof why,
                     "the load factor could not be raised further, even by the "
                     "smallest increment dlambda_min = %g: the equilibrium path ends there (a "
                     "limit point, a mechanism or a part that cannot carry the load)",
                     o->dlambda_min);
        else
            snprintf(why, sizeof why,
                     "at the full load the pseudo-time steps did not come to rest, down to the "
                     "smallest pseudo-time step %g",
                     h_min);
        bg_error_raise(err, st, where,
                       "no static equilibrium found: %s; load factor reached %.4g%s; the largest "
                       "scaled residual is "
                       "in %s (|F| = %.4g, %.3g tolerance units), the largest Newton correction "
                       "on %s (%.3g tolerance units)",
                       why, r->lambda, st == DAE_TOO_MUCH_WORK ? " (raise max_steps)" : "",
                       r->residual_eq >= 0 ? bg_eq_label(p, r->residual_eq, eb, sizeof eb) : "-",
                       r->residual_abs, r->residual,
                       r->worst_var >= 0 ? bg_var_label(p, r->worst_var, vb, sizeof vb) : "-",
                       r->correction);
    }
out:
    free(ytry);
    free(yrest);
    free(yold);
done:
    if (yp && st == BG_OK) memcpy(yp, c.yps, sz);
    if (c.J.n) {
        r->res_evals = c.J.res_evals;
        r->jac_evals = c.J.jac_evals;
    }
    ctx_free(&c);
    r->seconds = now_seconds() - t_start;
    return r->status = st;
}
