/* Row classes and consistent initial values for semi-explicit DAEs of index up to 2 (the
 * classification of the unknowns: dae_struct.c).
 *
 * Row classes. ROW_DIFF rows contain y'. An algebraic row is ROW_ALG2 if it contains an index-2
 * unknown, ROW_ALG1 otherwise. ROW_ALG1 rows involve differential and index-1 variables only;
 * they are the constraints (explicit ones, or hidden behind index-1 variables as in bond graphs:
 * f1 - f2 = 0 with f = p/m) whose derivative fixes the index-2 unknowns.
 *
 * Consistent initial values (dae_consistent_init), in two stages.
 *  A. The algebraic rows G(y) = 0 (both classes) are solved for y with the smallest change
 *     (Euclidean norm) of the differential variables: Gauss-Newton steps from the KKT system
 *         [ D   B^T ] [ dy ]   [  0 ]
 *         [ B   0   ] [ mu ] = [ -G ],   B = dG/dy,
 *     D = 1 on differential variables, 0 on index-1 ones (free: the algebraic rows determine
 *     them) and 1e-10 on index-2 ones (free as well, but not determined by these rows: the small
 *     weight keeps the system regular; their values are recomputed in stage B). With no
 *     constraint on the differential variables they do not move, whatever the coefficients.
 *     (A small weight on the index-1 variables instead would move the differential ones by
 *     about weight * coefficient^2: a spring k q - e = 0 with k = 1e4 shifted q by 2 %.)
 *     (The error weights would be the obvious scaling, but they make large components cheap to
 *     move: a pendulum started slightly off its velocity constraint was moved by 0.38 in x.)
 *  B. With y_D and the index-1 variables fixed, Newton on the square system
 *         ROW_DIFF and ROW_ALG2 rows:  F_i(t, y, y') = 0,
 *         ROW_ALG1 rows:               dF_i/dt + sum_j dF_i/dy_j y'_j = 0   (j not index 2),
 *     for the unknowns y' of the differential and index-1 variables and y of the index-2 ones.
 *     dF_i/dt is a one-sided difference in t (forward, or backward where a restart at a
 *     breakpoint takes the left-hand values), second order, with a step that starts at
 *     cbrt(eps) times the time scale (|t|, or at t = 0 the span to the stop time or the first
 *     breakpoint) and is divided by 8 until two successive estimates agree to 1e-3: an input
 *     that is constant for 5 ns and then ramps (the IVP Test Set's pump) must not be
 *     differenced across the ramp. The second derivatives of F are left out of the
 *     Jacobian of the differentiated rows (exact for constraints linear in the algebraic
 *     variables, as junction and velocity constraints are); the Jacobian is evaluated afresh in
 *     each iteration. The index-1 variables get their y' as a by-product, which starts the BDF
 *     predictor well.
 * A model of index higher than 2 leaves stage B singular; the message names the variable. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae_impl.h"

#define KKT_ALG_WEIGHT 1e-10 /* D on algebraic variables in stage A */
#define INIT_MAX_ITER 25

/* ------------------------------------------------------------------- set-up ---- */

void daei_init_free(dae_solver *s)
{
    int **iv[] = {&s->rowkind, &s->rowscaled, &s->srows,    &s->a2cols, &s->a1cols,
                  &s->kslot_yp, &s->kslot_y, &s->arow,     &s->kkt_diag, &s->kkt_b,
                  &s->kkt_bt};
    for (size_t k = 0; k < sizeof iv / sizeof *iv; k++) {
        free(*iv[k]);
        *iv[k] = NULL;
    }
    sp_csc_free(&s->K);
    ls_free(&s->kls);
    sp_csc_free(&s->kkt);
    ls_free(&s->kktls);
    free(s->kkt_rhs);
    s->kkt_rhs = NULL;
}

/* K: column j is y'_j (differential, index 1) or y_j (index 2). */
static int build_k(dae_solver *s)
{
    int n = s->n, ok = 0;
    sp_builder *b = sp_builder_create(n, n, s->Jy->nnz + s->Jyp->nnz);
    int *sy = malloc(((size_t)s->Jy->nnz + 1) * sizeof *sy);
    int *syp = malloc(((size_t)s->Jyp->nnz + 1) * sizeof *syp);
    int *slot = NULL;
    if (!b || !sy || !syp) goto done;
    for (int j = 0; j < n; j++) {
        int i2 = s->kind[j] == DAE_ALG2;
        for (int p = s->Jyp->colptr[j]; p < s->Jyp->colptr[j + 1]; p++) /* ROW_DIFF rows */
            syp[p] = s->kind[j] == DAE_DIFF ? sp_builder_add(b, s->Jyp->rowind[p], j, 0.0) : -1;
        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++) {
            int rk = s->rowkind[s->Jy->rowind[p]];
            int use = rk == ROW_ALG1 ? !i2 : i2;
            sy[p] = use ? sp_builder_add(b, s->Jy->rowind[p], j, 0.0) : -1;
        }
    }
    slot = malloc(((size_t)sp_builder_count(b) + 1) * sizeof *slot);
    if (!slot || !(s->K = sp_builder_finish(b, slot))) goto done;
    for (int p = 0; p < s->Jy->nnz; p++)
        s->kslot_y[p] = sy[p] >= 0 ? slot[sy[p]] : -1;
    for (int p = 0; p < s->Jyp->nnz; p++)
        s->kslot_yp[p] = syp[p] >= 0 ? slot[syp[p]] : -1;
    ok = 1;
done:
    sp_builder_free(&b);
    free(sy);
    free(syp);
    free(slot);
    return ok;
}

/* KKT matrix of stage A: n + nalg_rows square. */
static int build_kkt(dae_solver *s)
{
    int n = s->n, N = n + s->nalg_rows, ok = 0;
    sp_builder *b = sp_builder_create(N, N, n + 2 * s->Jy->nnz);
    int *slot = NULL;
    if (!b) goto done;
    for (int j = 0; j < n; j++)
        s->kkt_diag[j] = sp_builder_add(b, j, j, 0.0);
    for (int j = 0; j < n; j++)
        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++) {
            int a = s->arow[s->Jy->rowind[p]];
            s->kkt_b[p] = a >= 0 ? sp_builder_add(b, n + a, j, 0.0) : -1;
            s->kkt_bt[p] = a >= 0 ? sp_builder_add(b, j, n + a, 0.0) : -1;
        }
    slot = malloc(((size_t)sp_builder_count(b) + 1) * sizeof *slot);
    if (!slot || !(s->kkt = sp_builder_finish(b, slot))) goto done;
    for (int j = 0; j < n; j++)
        s->kkt_diag[j] = slot[s->kkt_diag[j]];
    for (int p = 0; p < s->Jy->nnz; p++) {
        if (s->kkt_b[p] >= 0) s->kkt_b[p] = slot[s->kkt_b[p]];
        if (s->kkt_bt[p] >= 0) s->kkt_bt[p] = slot[s->kkt_bt[p]];
    }
    ok = 1;
done:
    sp_builder_free(&b);
    free(slot);
    return ok;
}

int daei_init_setup(dae_solver *s, bg_error *err)
{
    const char *w = "dae_create";
    int n = s->n;
    char nb[32], eb[192];
    s->rowkind = calloc((size_t)n, sizeof *s->rowkind);
    s->rowscaled = calloc((size_t)n, sizeof *s->rowscaled);
    s->arow = malloc((size_t)n * sizeof *s->arow);
    s->kslot_y = malloc(((size_t)s->Jy->nnz + 1) * sizeof *s->kslot_y);
    s->kslot_yp = malloc(((size_t)s->Jyp->nnz + 1) * sizeof *s->kslot_yp);
    if (!s->rowkind || !s->rowscaled || !s->arow || !s->kslot_y || !s->kslot_yp) goto nomem;
    /* the kinds must fit the patterns */
    for (int j = 0; j < n; j++) {
        int has_yp = s->Jyp->colptr[j + 1] > s->Jyp->colptr[j];
        if (s->kind[j] == DAE_DIFF && !has_yp)
            return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                                  "%s is declared differential, but no equation contains its "
                                  "derivative (empty column of dF/dy')",
                                  daei_vname(s, j, nb, sizeof nb));
        if (s->kind[j] == DAE_ALG && has_yp)
            return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                                  "%s is declared algebraic, but %s contains its derivative "
                                  "(declare it index 2 if the system is not semi-explicit)",
                                  daei_vname(s, j, nb, sizeof nb),
                                  daei_ename(s, s->Jyp->rowind[s->Jyp->colptr[j]], eb, sizeof eb));
        if (s->kind[j] == DAE_ALG2 && has_yp) s->not_semi_explicit = 1;
    }
    /* row classes */
    int *touched = calloc((size_t)n, sizeof *touched);
    if (!touched) goto nomem;
    for (int p = 0; p < s->Jyp->nnz; p++)
        touched[s->Jyp->rowind[p]] = 1;
    for (int i = 0; i < n; i++)
        s->rowkind[i] = touched[i] ? ROW_DIFF : ROW_ALG1;
    for (int j = 0; j < n; j++)
        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++) {
            int i = s->Jy->rowind[p];
            touched[i] = 1;
            if (s->kind[j] == DAE_ALG2 && s->rowkind[i] == ROW_ALG1) s->rowkind[i] = ROW_ALG2;
        }
    for (int i = 0; i < n; i++)
        if (!touched[i]) {
            free(touched);
            return bg_error_raise(err, BG_ERR_PATTERN, w,
                                  "%s depends on no variable (empty row of both Jacobian "
                                  "patterns)",
                                  daei_ename(s, i, eb, sizeof eb));
        }
    free(touched);
    s->nalg_rows = s->nalg1_rows = 0;
    s->srows = malloc(((size_t)n + 1) * sizeof *s->srows);
    s->a2cols = malloc(((size_t)n + 1) * sizeof *s->a2cols);
    s->a1cols = malloc(((size_t)n + 1) * sizeof *s->a1cols);
    if (!s->srows || !s->a2cols || !s->a1cols) goto nomem;
    s->nsrows = s->na2 = s->na1 = 0;
    for (int j = 0; j < n; j++) {
        if (s->kind[j] == DAE_ALG2) s->a2cols[s->na2++] = j;
        if (s->kind[j] == DAE_ALG) s->a1cols[s->na1++] = j;
    }
    for (int i = 0; i < n; i++) {
        s->rowscaled[i] = s->rowkind[i] != ROW_ALG1;
        if (s->rowscaled[i]) s->srows[s->nsrows++] = i;
        s->arow[i] = s->rowkind[i] == ROW_DIFF ? -1 : s->nalg_rows++;
        s->nalg1_rows += s->rowkind[i] == ROW_ALG1;
    }
    if (!build_k(s)) goto nomem;
    if (!(s->kls = ls_create(s->o.linsol, s->K, err))) return BG_ERR_LIBRARY;
    if (s->nalg_rows > 0) {
        s->kkt_diag = malloc((size_t)n * sizeof *s->kkt_diag);
        s->kkt_b = malloc(((size_t)s->Jy->nnz + 1) * sizeof *s->kkt_b);
        s->kkt_bt = malloc(((size_t)s->Jy->nnz + 1) * sizeof *s->kkt_bt);
        s->kkt_rhs = malloc(((size_t)n + s->nalg_rows) * sizeof *s->kkt_rhs);
        if (!s->kkt_diag || !s->kkt_b || !s->kkt_bt || !s->kkt_rhs || !build_kkt(s)) goto nomem;
        if (!(s->kktls = ls_create(s->o.linsol, s->kkt, err))) return BG_ERR_LIBRARY;
    }
    return BG_OK;
nomem:
    return bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory (n = %d)", n);
}

/* ------------------------------------------------------ consistent values ---- */

/* Scaled residual of row i: |F_i| / (1 + sum_j |Jy_ij y_j| + |Jyp_ij yp_j|), into den. */
static void row_scales(dae_solver *s, const double *y, const double *yp, double *den)
{
    for (int i = 0; i < s->n; i++)
        den[i] = 1.0;
    for (int j = 0; j < s->n; j++) {
        for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
            den[s->Jy->rowind[p]] += fabs(s->Jy->val[p] * y[j]);
        for (int p = s->Jyp->colptr[j]; p < s->Jyp->colptr[j + 1]; p++)
            den[s->Jyp->rowind[p]] += fabs(s->Jyp->val[p] * yp[j]);
    }
}

static int cb_fail(dae_solver *s, int r, const char *what, double t)
{
    return bg_error_raise(&s->err, r < 0 ? DAE_CALLBACK_FAIL : DAE_INIT_FAIL, "dae_consistent_init",
                          "the %s failed (status %d) at t = %.17g: %s", what, r, t, s->note);
}

/* dF_i/dt of the differentiated rows (ROW_ALG1) at (t, y, yp) into D, by the one-sided second-
 * order difference (-3 F(t) + 4 F(t + d) - F(t + 2d)) / (2d); F holds F(t). Scratch: tmp, delta
 * (D must be neither). */
static int rows_dt(dae_solver *s, double t, double d, const double *y, const double *yp,
                   const double *F, double *D)
{
    double *fp = s->tmp, *fm = s->delta;
    int r;
    if ((r = daei_call_res(s, t + d, y, yp, fp, 0)) != 0 ||
        (r = daei_call_res(s, t + 2 * d, y, yp, fm, 0)) != 0)
        return cb_fail(s, r, "residual", t + d);
    for (int i = 0; i < s->n; i++)
        D[i] = s->rowkind[i] == ROW_ALG1 ? (-3 * F[i] + 4 * fp[i] - fm[i]) / (2 * d) : 0.0;
    return BG_OK;
}

#define DT_SHRINK 8.0
#define DT_MAX_SHRINKS 10
#define DT_AGREE 1e-3

/* The step of rows_dt: from d0 (signed), divided by DT_SHRINK until two successive estimates
 * agree to DT_AGREE in every differentiated row, relative to the estimate plus the row's other
 * terms (sum_j |dF_i/dy_j y'_j|, the size that dF_i/dt balances) and the round-off of the
 * difference; at most DT_MAX_SHRINKS times (8^10 = 1e9). The step is returned in *d, the
 * estimate at it in D. Scratch: ypred (D: not tmp, delta or ypred). */
static int choose_dt(dae_solver *s, double t, double d0, const double *y, const double *yp,
                     const double *F, double *D, double *d)
{
    double *Da = s->ypred, *sc = s->yppred;
    int r = rows_dt(s, t, d0, y, yp, F, Da);
    if (r != BG_OK) return r;
    /* the row's other terms, and the size of its residual terms for the round-off */
    for (int i = 0; i < s->n; i++)
        sc[i] = 0.0;
    for (int j = 0; j < s->n; j++)
        if (s->kind[j] != DAE_ALG2)
            for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
                sc[s->Jy->rowind[p]] += fabs(s->Jy->val[p] * yp[j]);
    row_scales(s, y, yp, s->tmp2);
    *d = d0;
    for (int k = 0; k < DT_MAX_SHRINKS; k++) {
        double dn = *d / DT_SHRINK;
        if ((r = rows_dt(s, t, dn, y, yp, F, D)) != BG_OK) return r;
        *d = dn;
        int agree = 1;
        for (int i = 0; i < s->n && agree; i++) {
            if (s->rowkind[i] != ROW_ALG1) continue;
            double noise = 10 * DBL_EPSILON * s->tmp2[i] / fabs(dn);
            if (!(fabs(D[i] - Da[i]) <= DT_AGREE * (fabs(D[i]) + sc[i]) + noise)) agree = 0;
        }
        if (agree) return BG_OK;
        memcpy(Da, D, (size_t)s->n * sizeof *D);
    }
    return BG_OK; /* no agreement: the smallest step's estimate */
}

/* F and the Jacobians at (t, y, yp). */
static int eval_all(dae_solver *s, double t, const double *y, const double *yp)
{
    int r = daei_call_res(s, t, y, yp, s->res, 0);
    if (r != 0) return cb_fail(s, r, "residual", t);
    r = daei_eval_jac(s, t, y, yp, s->res);
    if (r != 0) return cb_fail(s, r, "Jacobian", t);
    return BG_OK;
}

static int factor_solve(dae_solver *s, ls_solver *ls, const sp_csc *M, double *rhs)
{
    double t0 = daei_clock(s);
    int r = ls_factor(ls, M);
    if (r == BG_OK) r = ls_solve(ls, rhs, 1);
    s->st.t_linalg += daei_clock(s) - t0;
    return r;
}

/* Stage A: the algebraic rows, moving the differential variables as little as possible. */
static int stage_a(dae_solver *s, double t, double *y, const double *yp)
{
    const char *w = "dae_consistent_init";
    int n = s->n, r;
    double *den = s->tmp2, *z = s->kkt_rhs;
    for (int it = 0;; it++) {
        if ((r = eval_all(s, t, y, yp)) != BG_OK) return r;
        row_scales(s, y, yp, den);
        double gmax = 0;
        int imax = -1;
        for (int i = 0; i < n; i++)
            if (s->arow[i] >= 0 && fabs(s->res[i]) / den[i] > gmax) {
                gmax = fabs(s->res[i]) / den[i];
                imax = i;
            }
        if (gmax <= 10 * DBL_EPSILON) return BG_OK;
        if (it == INIT_MAX_ITER) {
            char eb[192];
            return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                                  "the algebraic equations could not be satisfied at t = %.17g: "
                                  "%s keeps a scaled residual of %.3g",
                                  s->tn, daei_ename(s, imax, eb, sizeof eb), gmax);
        }
        sp_csc_zero(s->kkt);
        for (int j = 0; j < n; j++)
            s->kkt->val[s->kkt_diag[j]] = s->kind[j] == DAE_DIFF   ? 1.0
                                          : s->kind[j] == DAE_ALG2 ? KKT_ALG_WEIGHT
                                                                   : 0.0;
        for (int j = 0; j < n; j++)
            for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
                if (s->kkt_b[p] >= 0) {
                    s->kkt->val[s->kkt_b[p]] = s->Jy->val[p];
                    s->kkt->val[s->kkt_bt[p]] = s->Jy->val[p];
                }
        for (int j = 0; j < n; j++)
            z[j] = 0.0;
        for (int i = 0; i < n; i++)
            if (s->arow[i] >= 0) z[n + s->arow[i]] = -s->res[i];
        if ((r = factor_solve(s, s->kktls, s->kkt, z)) != BG_OK)
            return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                                  "the algebraic equations are dependent or contradict each other "
                                  "at t = %.17g (%s)",
                                  s->tn, ls_get_error(s->kktls)->message);
        for (int j = 0; j < n; j++)
            y[j] += z[j];
    }
}

/* A warning when algebraic unknowns given a value (not 0) ended far from it: by more than half
 * their size and 100 tolerances. The algebraic equations may have several solutions (a
 * mechanism's other assembly, a constraint force of the other sign), and the one found may not
 * be the one meant; the message names the unknown that moved most and says how many did. */
static void warn_moved(dae_solver *s, const double *guess, const double *y)
{
    int count = 0, worst = -1;
    double wrel = 0;
    for (int i = 0; i < s->n; i++) {
        if (s->kind[i] == DAE_DIFF || guess[i] == 0) continue;
        double d = fabs(y[i] - guess[i]), size = fmax(fabs(guess[i]), fabs(y[i]));
        if (d > 0.5 * size && d > 100 * (s->o.rtol * fabs(guess[i]) + s->atol[i])) {
            count++;
            if (d / fabs(guess[i]) > wrel) {
                wrel = d / fabs(guess[i]);
                worst = i;
            }
        }
    }
    if (count > 0) {
        char nb[32];
        daei_warn(s, "dae_consistent_init",
                  "%d algebraic unknown%s ended far from the values given (another solution of "
                  "the algebraic equations?): %s went from %.6g to %.6g",
                  count, count > 1 ? "s" : "", daei_vname(s, worst, nb, sizeof nb), guess[worst],
                  y[worst]);
    }
}

int dae_consistent_init(dae_solver *s)
{
    const char *w = "dae_consistent_init";
    if (!s) return BG_ERR_ARGUMENT;
    if (!s->initialized || !s->first)
        return bg_error_raise(&s->err, BG_ERR_STATE, w,
                              "consistent values are found between dae_init (or dae_reinit) and "
                              "the first step: %s",
                              !s->initialized ? "call dae_init first"
                                              : "the integration has started (or dae_set_history "
                                                "set a history); call dae_reinit");
    if (s->busy)
        return bg_error_raise(&s->err, BG_ERR_STATE, w,
                              "called from within a callback of the same solver");
    if (!s->yc && !(s->yc = malloc(2 * (size_t)s->n * sizeof *s->yc)))
        return bg_error_raise(&s->err, BG_ERR_MEMORY, w, "out of memory (n = %d)", s->n);
    memcpy(s->yc, s->phi[0], (size_t)s->n * sizeof *s->yc); /* the guess, compared below */
    s->busy = 1;
    int r = daei_consistent_init(s);
    s->busy = 0;
    if (r != BG_OK) {
        free(s->yc); /* dae_get_consistent: none */
        s->yc = NULL;
        return r;
    }
    warn_moved(s, s->yc, s->phi[0]);
    memcpy(s->yc, s->phi[0], (size_t)s->n * sizeof *s->yc); /* kept for dae_get_consistent */
    memcpy(s->yc + s->n, s->phi[1], (size_t)s->n * sizeof *s->yc);
    return r;
}

int daei_consistent_init(dae_solver *s)
{
    const char *w = "dae_consistent_init";
    int n = s->n, r;
    double t = s->tn;
    double *y = s->y, *yp = s->yp, *F = s->res, *u = s->ee;
    char nb[32];
    if (s->not_semi_explicit)
        return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                              "the system is not semi-explicit (an index-2 unknown appears "
                              "differentiated); give consistent initial values to dae_init");
    memcpy(y, s->phi[0], (size_t)n * sizeof *y);
    memcpy(yp, s->phi[1], (size_t)n * sizeof *yp);
    for (int j = 0; j < n; j++)
        if (s->kind[j] == DAE_ALG2) yp[j] = 0.0;
    s->hh = 0;
    daei_set_weights(s, y);
    /* the equations are evaluated just past t (right-hand limits of inputs that jump there:
     * at t0 and at breakpoints), with one-sided differences in t; forward unless the restart
     * at a breakpoint says otherwise */
    int side = s->init_side ? s->init_side : 1;
    if (side) t = nextafter(t, side > 0 ? INFINITY : -INFINITY);
    if (s->nalg_rows > 0 && (r = stage_a(s, t, y, yp)) != BG_OK) return r;

    /* stage B */
    /* time step of the differences in t: relative to |t|, or at t = 0 to the span of the run
     * (stop time or first breakpoint) when known, so that short time scales (a 1e-7 s circuit)
     * are not differenced across a whole period */
    double tscale = fabs(s->tn);
    if (tscale == 0) {
        tscale = 1.0;
        if (s->o.has_t_stop && s->o.t_stop != s->tn) tscale = fabs(s->o.t_stop - s->tn);
        if (s->nbkpt > 0 && s->bkpt[0] > s->tn) tscale = fmin(tscale, s->bkpt[0] - s->tn);
    }
    double dt = side * cbrt(DBL_EPSILON) * tscale;
    double unorm = INFINITY, uprev = INFINITY, rnorm = INFINITY;
    for (int it = 0; it < INIT_MAX_ITER; it++) {
        if ((r = eval_all(s, t, y, yp)) != BG_OK) return r;
        if (s->nalg1_rows > 0) { /* differentiated rows: dF_i/dt + sum_j dF_i/dy_j y'_j */
            double *D = s->typ;
            r = it == 0 ? choose_dt(s, t, dt, y, yp, F, D, &dt) : rows_dt(s, t, dt, y, yp, F, D);
            if (r != BG_OK) return r;
            for (int i = 0; i < n; i++)
                if (s->rowkind[i] == ROW_ALG1) F[i] = D[i];
            for (int j = 0; j < n; j++)
                if (s->kind[j] != DAE_ALG2)
                    for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++)
                        if (s->rowkind[s->Jy->rowind[p]] == ROW_ALG1)
                            F[s->Jy->rowind[p]] += s->Jy->val[p] * yp[j];
        }
        sp_csc_zero(s->K);
        for (int p = 0; p < s->Jy->nnz; p++)
            if (s->kslot_y[p] >= 0) s->K->val[s->kslot_y[p]] = s->Jy->val[p];
        for (int p = 0; p < s->Jyp->nnz; p++)
            if (s->kslot_yp[p] >= 0) s->K->val[s->kslot_yp[p]] = s->Jyp->val[p];
        /* the stage-B residual, scaled by the size of its terms: at round-off level the
         * values are consistent whatever the last correction looked like */
        row_scales(s, y, yp, s->tmp2);
        rnorm = 0;
        for (int i = 0; i < n; i++)
            rnorm = fmax(rnorm, fabs(F[i]) / s->tmp2[i]);
        if (it > 0 && rnorm <= 1e-13) break;
        memcpy(u, F, (size_t)n * sizeof *u);
        if ((r = factor_solve(s, s->kls, s->K, u)) != BG_OK) {
            int c = ls_singular_col(s->kls);
            return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                                  "the equations for the derivatives and the index-2 unknowns are "
                                  "singular at t = %.17g: nothing determines %s%s%s (%s)",
                                  s->tn, c >= 0 && s->kind[c] != DAE_ALG2 ? "the derivative of " : "",
                                  daei_vname(s, c, nb, sizeof nb),
                                  c >= 0 && s->kind[c] == DAE_ALG2
                                      ? "; is it really index 2, and is the index at most 2?"
                                      : "",
                                  ls_get_error(s->kls)->message);
        }
        uprev = unorm;
        unorm = 0;
        for (int j = 0; j < n; j++) {
            double *v = s->kind[j] == DAE_ALG2 ? &y[j] : &yp[j];
            *v -= u[j];
            unorm = fmax(unorm, fabs(u[j]) / (s->o.rtol * fabs(*v) + s->atol[j]));
        }
        /* converged: corrections far below the tolerances, or no longer decreasing at the
         * level of round-off */
        if (unorm <= 1e-3 || (unorm < 1 && unorm > 0.5 * uprev)) break;
    }
    if ((r = eval_all(s, t, y, yp)) != BG_OK) return r;
    row_scales(s, y, yp, s->tmp2);
    double m = 0;
    int im = -1, hidden = 0;
    for (int i = 0; i < n; i++)
        if (fabs(F[i]) / s->tmp2[i] > m || im < 0) {
            m = fmax(m, fabs(F[i]) / s->tmp2[i]);
            im = i;
        }
    /* the hidden constraints too, measured at the values returned: the time derivative of each
     * constraint row, dF_i/dt + sum_j dF_i/dy_j y'_j, against the size of its terms */
    if (s->nalg1_rows > 0) {
        double *D = s->typ, *den = s->tmp2;
        if ((r = rows_dt(s, t, dt, y, yp, F, D)) != BG_OK) return r;
        for (int i = 0; i < n; i++)
            den[i] = 1.0 + fabs(D[i]);
        for (int j = 0; j < n; j++)
            if (s->kind[j] != DAE_ALG2)
                for (int p = s->Jy->colptr[j]; p < s->Jy->colptr[j + 1]; p++) {
                    int i = s->Jy->rowind[p];
                    if (s->rowkind[i] != ROW_ALG1) continue;
                    D[i] += s->Jy->val[p] * yp[j];
                    den[i] += fabs(s->Jy->val[p] * yp[j]);
                }
        for (int i = 0; i < n; i++)
            if (s->rowkind[i] == ROW_ALG1 && fabs(D[i]) / den[i] > m) {
                m = fabs(D[i]) / den[i];
                im = i;
                hidden = 1;
            }
        if ((r = eval_all(s, t, y, yp)) != BG_OK) return r; /* F back at the values */
    }
    s->st.init_residual = m;
    daei_sync_stats(s);
    memcpy(s->phi[0], y, (size_t)n * sizeof *y);
    memcpy(s->phi[1], yp, (size_t)n * sizeof *yp);
    s->need_setup = 1;
    /* the derivatives may stay inconsistent at the level the linear algebra reaches on an
     * ill-conditioned system (stiff bars next to tiny rotary inertias: 1e-7 of the terms); the
     * first steps correct that, so only a gross failure is reported */
    if ((unorm >= 1 && rnorm > 1e-6) || m > 1e-8) {
        char eb[192];
        return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                              "Newton iteration for consistent values did not converge at t = "
                              "%.17g: %s keeps a scaled residual of %.3g%s",
                              s->tn, daei_ename(s, im, eb, sizeof eb), m,
                              hidden ? " in its time derivative (a hidden constraint)" : "");
    }
    return BG_OK;
}
