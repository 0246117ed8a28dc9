/* Row classes and consistent initial values for semi-explicit DAEs of index up to 2 (the
 * classification of the unknowns: dae_struct.c; the Newton iteration for y' and the index-2
 * unknowns, the hidden constraints and the derivatives of the index-2 unknowns:
 * dae_ic_newton.c; their interface: dae_ic_impl.h).
 *
 * Row classes. ROW_DIFF rows contain y'. An algebraic row is ROW_ALG2 if it contains an index-2
 * unknown, ROW_ALG1 otherwise. ROW_ALG1 rows involve differential and index-1 variables only;
 * they are the constraints (explicit ones, or hidden behind index-1 variables as in bond graphs:
 * f1 - f2 = 0 with f = p/m) whose derivative fixes the index-2 unknowns. With the kinds found by
 * dae_classify every index-1 unknown is matched to a ROW_ALG1 row (a row that holds an index-2
 * unknown makes the unknown matched to it index 2).
 *
 * Consistent initial values (dae_consistent_init), in three stages. The equations are evaluated
 * one rounding unit past t (the right-hand limits of inputs that jump at t0 or at a breakpoint;
 * the left-hand ones where a restart says so), and every difference in t is one-sided.
 *  A. The constraint rows G(y) = 0 (ROW_ALG1) are solved for y with the smallest change
 *     (Euclidean norm) of the differential variables: Gauss-Newton steps from the KKT system
 *         [ D   B^T ] [ dy ]   [  0 ]
 *         [ B   0   ] [ mu ] = [ -r ],   B = dG/dy,
 *     D = 1 on differential variables and 0 on index-1 ones (free: the constraint rows
 *     determine them). With no constraint on the differential variables they do not move,
 *     whatever the coefficients. (A small weight on the index-1 variables instead would move
 *     the differential ones by about weight * coefficient^2: a spring k q - e = 0 with k = 1e4
 *     shifted q by 2 %. The error weights would be the obvious scaling, but they make large
 *     components cheap to move: a pendulum started slightly off its velocity constraint was
 *     moved by 0.38 in x.) The rows that hold index-2 unknowns (ROW_ALG2) are solved in stage
 *     B, where those are the unknowns; here they take part with r = 0 and the weight 1e-10 on
 *     the index-2 unknowns: a change of the differential variables that would change the
 *     forces (the index-2 unknowns) much costs more than one that does not, so that a velocity
 *     constraint is met by the velocities rather than by stiff positions. Solving them here
 *     (r = their residual) would let them be met by moving differential variables wherever
 *     their coefficients (stiffnesses) are larger than the index-2 unknowns' (masses): from
 *     multipliers guessed 0, a consistent state, but not the one given. Only where declared
 *     kinds leave an index-1 unknown that no maximum matching of the constraint rows covers
 *     are the ROW_ALG2 rows solved here as well (ic_a_alg2). The iteration ends when the
 *     constraint rows hold to round-off or the correction is negligible (IC_NEGLIGIBLE of the
 *     tolerance in the error weights; it is then not applied, so that values given consistent
 *     are returned unchanged).
 *  B. With y_D and the index-1 variables fixed, Newton on the square system
 *         ROW_DIFF and ROW_ALG2 rows:  F_i(t, y, y') = 0,
 *         ROW_ALG1 rows:               dF_i/dt + sum_j dF_i/dy_j y'_j = 0   (j not index 2),
 *     for the unknowns y' of the differential and index-1 variables and y of the index-2 ones.
 *     The differentiated rows (the hidden constraints) are evaluated from the residual by
 *     extrapolated differences (dae_ic_newton.c: dF_i/dt one-sided in t; the sum over y' with
 *     the entries of an analytic Jacobian, or by differences of F along y' when the Jacobian is
 *     by finite differences, whose entries reach only about sqrt(eps) of a row's terms). The
 *     Jacobian (evaluated afresh in each iteration; the second derivatives of F left out,
 *     exact for constraints linear in the algebraic variables) only steers the iteration: where
 *     it ends is decided by the residual, so that finite-difference Jacobians give consistent
 *     values to the tolerance as well. The iteration stops when the correction is negligible,
 *     when only residuals within their evaluation's noise call for it, or when it stalls below
 *     the tolerance (none of them applied), or when the scaled residual is at round-off; every
 *     stop follows an evaluation at the values returned, so that what is reported is measured
 *     there: stats.init_residual, the largest residual of a row or a hidden constraint scaled
 *     by the size of its terms, and stats.init_error, the correction those residuals call for
 *     (the matrix of the last iteration) in the error weights of y and y' (<= 1: consistent to
 *     the tolerance).
 *  C. The derivatives of the index-2 unknowns. Differentiating stage B's equations along the
 *     solution gives a linear system with the same matrix K (dF/dy' in the differential
 *     columns, dF/dy in the others):
 *         K [y''_D, y''_A1, y'_A2] = -[ d/ds F_i(t + s, y + s v, y')      (ROW_DIFF, ROW_ALG2)
 *                                       d2/ds2 F_i(t + s, y + s v) ]      (ROW_ALG1),
 *     v = y' with 0 for the index-2 unknowns, at s = 0. The right-hand side is taken by
 *     extrapolated one-sided differences along (1, v), each row from its own time scale (the
 *     time in which v moves an unknown of the row by its size) and within the step over which
 *     stage B found the residual smooth in t. y'_A2 is kept where the error estimates, through
 *     the same matrix, are below a tenth of it, else left 0. The y' given for the index-2
 *     unknowns enter no equation and are not used. The index-1 unknowns get their y' from
 *     stage B.
 * A model of index higher than 2 leaves stage B singular; the message names the variable.
 *
 * Another solution. The algebraic equations and the constraints may have several solutions (a
 * mechanism's other assembly, a constraint force of the other sign). dae_consistent_init warns
 * (and returns DAE_WARNING) when unknowns ended far from the values given, by more than half
 * their size and 100 tolerances: algebraic unknowns given a value other than 0 (0 is taken as
 * "not known": an index-2 multiplier guessed 0 has no "far"), and differential unknowns that
 * stage A moved along a path that was not straight (the first Gauss-Newton step and the final
 * change differ by more than a tenth of the change: a linear constraint has one nearest
 * solution, a nonlinear one may have been left for another). Not where an equation jumps at t
 * (its value at t and one rounding unit past t differ at the values given): the values given
 * are then taken as left-hand values, and the right-hand ones may lie far from them. The
 * message names the unknowns that moved most, with the values given and found. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dae_ic_impl.h"

#define KKT_ALG_WEIGHT 1e-10 /* D on the index-2 variables in stage A */

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
    free(s->tcols);
    s->tcols = NULL;
    free(s->wmask);
    s->wmask = NULL;
    sp_csc_free(&s->K);
    ls_free(&s->kls);
    sp_csc_free(&s->kkt);
    ls_free(&s->kktls);
    free(s->kkt_rhs);
    s->kkt_rhs = NULL;
    free(s->ic_w);
    s->ic_w = NULL;
    free(s->ic_tab);
    s->ic_tab = NULL;
    free(s->ic_rows);
    s->ic_rows = NULL;
    free(s->ic_run);
    s->ic_run = NULL;
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

/* Whether every index-1 unknown is matched to a constraint row (ROW_ALG1) in a maximum matching
 * of those rows and columns: 1 yes, 0 no, or BG_ERR_MEMORY. */
static int alg1_covered(dae_solver *s)
{
    int n = s->n, ok = BG_ERR_MEMORY;
    int *rm = malloc(((size_t)n + 1) * sizeof *rm), *cm = malloc(((size_t)n + 1) * sizeof *cm);
    int *rv = malloc(((size_t)n + 1) * sizeof *rv);
    if (rm && cm && rv) {
        for (int i = 0; i < n; i++) {
            rm[i] = s->rowkind[i] == ROW_ALG1;
            cm[i] = s->kind[i] == DAE_ALG;
        }
        int m = daei_match(s->Jy, rm, cm, rv);
        ok = m < 0 ? m : m == s->na1;
    }
    free(rm);
    free(cm);
    free(rv);
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
    s->ic_w = malloc((size_t)IC_NWORK * (size_t)n * sizeof *s->ic_w);
    if (!s->rowkind || !s->rowscaled || !s->arow || !s->kslot_y || !s->kslot_yp || !s->ic_w)
        goto nomem;
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
    s->tcols = malloc(((size_t)n + 1) * sizeof *s->tcols);
    s->wmask = malloc(((size_t)n + 1) * sizeof *s->wmask);
    if (!s->tcols || !s->wmask) goto nomem;
    s->ntcols = 0;
    s->stab_ns = 0; /* the guard's window is packed by tcols */
    for (int j = 0; j < n; j++) {
        if (s->kind[j] == DAE_ALG2) s->a2cols[s->na2++] = j;
        if (s->kind[j] == DAE_ALG) s->a1cols[s->na1++] = j;
        int out1 = s->o.exclude_alg && s->kind[j] == DAE_ALG;
        s->wmask[j] = out1 ? 0 : ~0LL;
        if (!out1 && !(s->o.index2 == DAE_I2_EXCLUDE && s->kind[j] == DAE_ALG2))
            s->tcols[s->ntcols++] = j;
    }
    int cov = s->na1 > 0 ? alg1_covered(s) : 1;
    if (cov < 0) goto nomem;
    s->ic_a_alg2 = !cov;
    for (int i = 0; i < n; i++) {
        s->rowscaled[i] = s->rowkind[i] != ROW_ALG1;
        if (s->rowscaled[i]) s->srows[s->nsrows++] = i;
        s->arow[i] = s->rowkind[i] == ROW_DIFF ? -1 : s->nalg_rows++;
        s->nalg1_rows += s->rowkind[i] == ROW_ALG1;
    }
    size_t ntab = (size_t)IC_NLEV * (size_t)s->nalg1_rows;
    if (ntab < (size_t)IC_NLEV_C * (size_t)n) ntab = (size_t)IC_NLEV_C * (size_t)n;
    s->ic_rows = malloc(((size_t)s->nalg1_rows + 1) * sizeof *s->ic_rows);
    s->ic_run = malloc(((size_t)n + 1) * sizeof *s->ic_run);
    s->ic_tab = malloc((2 * ntab + 1) * sizeof *s->ic_tab);
    if (!s->ic_rows || !s->ic_run || !s->ic_tab) goto nomem;
    for (int i = 0, k = 0; i < n; i++)
        if (s->rowkind[i] == ROW_ALG1) s->ic_rows[k++] = i;
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

/* ------------------------------------------------------------------ helpers ---- */

int daei_ic_res(dae_solver *s, double t, const double *y, const double *yp, double *F)
{
    int r = daei_call_res(s, t, y, yp, F, 0);
    if (r == 0) return 0;
    /* daei_call_res's note gives the time as evaluated (4.94e-324 for just after 0) */
    char eb[192], tb[96];
    int bad = daei_first_nonfinite(F, s->n);
    daei_when(s, t, tb, sizeof tb);
    if (r != BG_RECOVERABLE || bad < 0)
        daei_note(s, "the residual function returned the %s status %d at %s%s%.160s%s",
                  r < 0 ? "fatal" : "recoverable", r, tb, bad >= 0 ? " (" : "",
                  bad >= 0 ? daei_ename(s, bad, eb, sizeof eb) : "",
                  bad >= 0 ? " not finite)" : "");
    else
        daei_note(s, "the residual of %.160s is %g at %s", daei_ename(s, bad, eb, sizeof eb),
                  F[bad], tb);
    return r;
}

int daei_ic_eval_all(dae_solver *s, double t, const double *y, const double *yp)
{
    int r = daei_ic_res(s, t, y, yp, s->res);
    if (r != 0) return daei_ic_cb_fail(s, r, "residual");
    r = daei_eval_jac(s, t, y, yp, s->res);
    if (r != 0 && s->reg_failed) return daei_ic_cb_fail(s, r, "regimes callback");
    if (r != 0) {
        char tb[96], eb[192], nb[32];
        daei_when(s, t, tb, sizeof tb);
        int bad = -1, m = 0;
        for (m = 0; m < 2 && bad < 0; m++)
            bad = daei_first_nonfinite(m ? s->Jyp->val : s->Jy->val,
                                       m ? s->Jyp->nnz : s->Jy->nnz);
        m--;
        if (s->p.jac && r != BG_RECOVERABLE)
            daei_note(s, "the Jacobian function returned the %s status %d at %s",
                      r < 0 ? "fatal" : "recoverable", r, tb);
        else if (s->p.jac && bad >= 0) {
            const sp_csc *J = m ? s->Jyp : s->Jy;
            int col = 0;
            while (J->colptr[col + 1] <= bad)
                col++;
            daei_note(s, "the Jacobian entry d(%.160s)/d(%s%s) is %g at %s",
                      daei_ename(s, J->rowind[bad], eb, sizeof eb),
                      daei_vname(s, col, nb, sizeof nb), m ? "'" : "", J->val[bad], tb);
        } else if (!s->p.jac)
            daei_note(s, "the residual function failed (status %d) in the finite differences "
                      "of the Jacobian at %s", r, tb);
        return daei_ic_cb_fail(s, r, "Jacobian");
    }
    return BG_OK;
}

int daei_ic_cb_fail(dae_solver *s, int r, const char *what)
{
    return bg_error_raise(&s->err, r < 0 ? DAE_CALLBACK_FAIL : DAE_INIT_FAIL,
                          "dae_consistent_init", "the %s failed (status %d): %s", what, r,
                          s->note);
}

int daei_ic_factor_solve(dae_solver *s, ls_solver *ls, const sp_csc *M, double *rhs)
{
    double t0 = daei_clock(s);
    int r = ls_factor(ls, M);
    if (r == BG_OK) r = ls_solve(ls, rhs, 1);
    s->st.t_linalg += daei_clock(s) - t0;
    return r;
}

void daei_ic_row_scales(dae_solver *s, const double *y, const double *yp, double *den)
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

/* ------------------------------------------------------------------ stage A ---- */

/* Whether stage A solves row i (else a ROW_ALG2 row is kept as it is). */
static int solved_in_a(const dae_solver *s, int i)
{
    return s->rowkind[i] == ROW_ALG1 || (s->ic_a_alg2 && s->rowkind[i] == ROW_ALG2);
}

/* The constraint rows, moving the differential variables as little as possible. *wmove: the
 * weighted size of the correction the last evaluation called for (0 when the rows hold to
 * round-off), measured at the values returned. The first correction goes to IC_DA1. */
static int stage_a(dae_solver *s, double te, double *y, const double *yp, double *wmove)
{
    const char *w = "dae_consistent_init";
    int n = s->n, r;
    double *den = daei_icw(s, IC_DEN), *z = s->kkt_rhs, *da1 = daei_icw(s, IC_DA1);
    char tb[96];
    *wmove = 0;
    for (int it = 0;; it++) {
        if ((r = daei_ic_eval_all(s, te, y, yp)) != BG_OK) return r;
        daei_ic_row_scales(s, y, yp, den);
        double gmax = 0;
        int imax = -1;
        for (int i = 0; i < n; i++)
            if (solved_in_a(s, i) && fabs(s->res[i]) / den[i] > gmax) {
                gmax = fabs(s->res[i]) / den[i];
                imax = i;
            }
        if (gmax <= 10 * DBL_EPSILON) {
            *wmove = 0; /* measured here: round-off */
            return BG_OK;
        }
        if (it == IC_MAX_ITER) {
            char eb[192];
            return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                                  "the algebraic equations could not be satisfied at %s: %.200s "
                                  "keeps a scaled residual of %.3g",
                                  daei_when(s, s->tn, tb, sizeof tb),
                                  daei_ename(s, imax, eb, sizeof eb), gmax);
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
            if (s->arow[i] >= 0) z[n + s->arow[i]] = solved_in_a(s, i) ? -s->res[i] : 0.0;
        if ((r = daei_ic_factor_solve(s, s->kktls, s->kkt, z)) != BG_OK)
            return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                                  "the algebraic equations are dependent or contradict each other "
                                  "at %s (%s)",
                                  daei_when(s, s->tn, tb, sizeof tb),
                                  ls_get_error(s->kktls)->message);
        double wn = 0;
        for (int j = 0; j < n; j++)
            wn = fmax(wn, fabs(z[j]) * s->ewt[j]);
        *wmove = wn;
        if (wn <= IC_NEGLIGIBLE) return BG_OK; /* consistent already: not applied */
        if (it == 0) memcpy(da1, z, (size_t)n * sizeof *da1);
        for (int j = 0; j < n; j++)
            y[j] += z[j];
    }
}

/* ----------------------------------------------------------- another solution ---- */

#define WARN_LIST 4 /* unknowns named in the warning */

/* Whether an equation jumps at t: F at (t, guess, guessp) and one rounding unit past t (on the
 * side the equations were evaluated) differ by more than round-off in some row. Then the
 * values given are left-hand values, and the consistent right-hand ones may lie far from them
 * (a reference whose rate jumps at t0 moves a controller's output). */
static int jumps_at_t(dae_solver *s, const double *guess, const double *guessp)
{
    double *a = daei_icw(s, IC_F1), *b = daei_icw(s, IC_F2), *den = daei_icw(s, IC_DEN);
    int side = s->init_side ? s->init_side : 1;
    if (daei_call_res(s, s->tn, guess, guessp, a, 0) != 0 ||
        daei_call_res(s, nextafter(s->tn, side > 0 ? INFINITY : -INFINITY), guess, guessp, b, 0) !=
            0)
        return 0;
    daei_ic_row_scales(s, guess, guessp, den);
    for (int i = 0; i < s->n; i++)
        if (fabs(a[i] - b[i]) > 1e3 * DBL_EPSILON * (den[i] + fabs(a[i]) + fabs(b[i]))) return 1;
    return 0;
}

/* The warning of the header comment; 1 if it was given. */
static int warn_moved(dae_solver *s, const double *guess, const double *guessp, const double *y,
                      const double *da1)
{
    int count = 0, top[WARN_LIST];
    double score[WARN_LIST];
    for (int i = 0; i < s->n; i++) {
        double d = fabs(y[i] - guess[i]), size = fmax(fabs(guess[i]), fabs(y[i]));
        double tol = s->o.rtol * fabs(guess[i]) + s->atol[i];
        if (!(d > 0.5 * size && d > 100 * tol)) continue;
        if (s->kind[i] == DAE_DIFF) {
            if (!(fabs(y[i] - guess[i] - da1[i]) > 0.1 * d)) continue; /* a straight path */
        } else if (guess[i] == 0) {
            continue; /* not known */
        }
        double sc = d / fmax(fabs(guess[i]), tol);
        int k = count < WARN_LIST ? count : WARN_LIST;
        count++;
        while (k > 0 && score[k - 1] < sc) { /* insertion into the list, largest first */
            if (k < WARN_LIST) {
                score[k] = score[k - 1];
                top[k] = top[k - 1];
            }
            k--;
        }
        if (k < WARN_LIST) {
            score[k] = sc;
            top[k] = i;
        }
    }
    if (count == 0 || jumps_at_t(s, guess, guessp)) return 0;
    char list[BG_MESSAGE_SIZE], nb[32];
    size_t len = 0;
    int shown = count < WARN_LIST ? count : WARN_LIST;
    for (int k = 0; k < shown && len < sizeof list; k++) {
        int i = top[k];
        int m = snprintf(list + len, sizeof list - len, "%s%.40s %s %.6g to %.6g", k ? ", " : "",
                         daei_vname(s, i, nb, sizeof nb), k ? "from" : "went from", guess[i],
                         y[i]);
        if (m < 0) break;
        len += (size_t)m;
    }
    char tb[96];
    daei_warn(s, "dae_consistent_init",
              "%d unknown%s ended far from the values given at %s (another solution of the "
              "algebraic equations or constraints?): %.300s%s",
              count, count > 1 ? "s" : "", daei_when(s, s->tn, tb, sizeof tb), list,
              count > shown ? ", ..." : "");
    return 1;
}

/* --------------------------------------------------------------- entry points ---- */

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
    double *guess = daei_icw(s, IC_GUESS), *guessp = daei_icw(s, IC_GUESSP);
    memcpy(guess, s->phi[0], (size_t)s->n * sizeof *guess); /* compared below */
    memcpy(guessp, s->phi[1], (size_t)s->n * sizeof *guessp);
    s->busy = 1;
    int r = daei_consistent_init(s);
    s->busy = 0;
    s->st.init_residual = s->ic_res;
    s->st.init_error = s->ic_err;
    if (r != BG_OK) {
        free(s->yc); /* dae_get_consistent: none */
        s->yc = NULL;
        return r;
    }
    int warned = warn_moved(s, guess, guessp, s->phi[0], daei_icw(s, IC_DA1));
    memcpy(s->yc, s->phi[0], (size_t)s->n * sizeof *s->yc); /* kept for dae_get_consistent */
    memcpy(s->yc + s->n, s->phi[1], (size_t)s->n * sizeof *s->yc);
    return warned ? DAE_WARNING : BG_OK;
}

int daei_consistent_init(dae_solver *s)
{
    const char *w = "dae_consistent_init";
    int n = s->n, r;
    double *y = s->y, *yp = s->yp;
    char tb[96];
    s->ic_res = s->ic_err = NAN;
    if (s->red) return daei_red_consistent_init(s);
    if (s->not_semi_explicit)
        return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                              "the system is not semi-explicit (an index-2 unknown appears "
                              "differentiated); give consistent initial values to dae_init");
    memcpy(y, s->phi[0], (size_t)n * sizeof *y);
    memcpy(yp, s->phi[1], (size_t)n * sizeof *yp);
    for (int j = 0; j < n; j++)
        if (s->kind[j] == DAE_ALG2) yp[j] = 0.0;
    memset(daei_icw(s, IC_DA1), 0, (size_t)n * sizeof(double));
    s->hh = 0;
    daei_set_weights(s, y);
    /* the equations are evaluated just past t (right-hand limits of inputs that jump there:
     * at t0 and at breakpoints), with one-sided differences in t; forward unless the restart
     * at a breakpoint says otherwise */
    int side = s->init_side ? s->init_side : 1;
    double te = nextafter(s->tn, side > 0 ? INFINITY : -INFINITY);
    double ea = 0;
    if (s->nalg_rows > 0 && (r = stage_a(s, te, y, yp, &ea)) != BG_OK) return r;

    /* time scale of the differences in t: |t|, or at t = 0 the span of the run (stop time or
     * first breakpoint) when known, so that short time scales (a 1e-7 s circuit) are not
     * differenced across a whole period; a |t| or a span below IC_TSCALE_MIN is no time scale
     * (dae_ic_impl.h): then the span, or 1 as when the span is not known */
    double tscale = fabs(s->tn) >= IC_TSCALE_MIN ? fabs(s->tn) : 0.0;
    if (tscale == 0) {
        tscale = 1.0;
        if (s->o.has_t_stop && s->o.t_stop != s->tn) tscale = fabs(s->o.t_stop - s->tn);
        if (s->nbkpt > 0 && s->bkpt[0] > s->tn) tscale = fmin(tscale, s->bkpt[0] - s->tn);
        if (tscale < IC_TSCALE_MIN) tscale = 1.0;
    }
    ic_outcome o;
    r = daei_ic_stage_b(s, te, side, tscale, y, yp, &o);
    daei_sync_stats(s);
    if (r != BG_OK) return r;
    s->ic_res = o.rnorm;
    s->ic_err = fmax(ea, o.unorm);
    if (daei_ic_failed(&o)) {
        char eb[192];
        return bg_error_raise(&s->err, DAE_INIT_FAIL, w,
                              "Newton iteration for consistent values did not converge at %s: "
                              "%.160s keeps a scaled residual of %.3g%s%s",
                              daei_when(s, s->tn, tb, sizeof tb),
                              daei_ename(s, o.rworst, eb, sizeof eb), o.rnorm,
                              o.rhidden ? " in its time derivative (a hidden constraint)" : "",
                              s->p.jac ? ""
                                       : "; the Jacobian is by finite differences: an analytic "
                                         "one (dae_problem.jac) may let the iteration converge");
    }
    if (s->na2 > 0 && (r = daei_ic_alg2_rates(s, te, tscale, o.tstep, y, yp)) != BG_OK) return r;
    memcpy(s->phi[0], y, (size_t)n * sizeof *y);
    memcpy(s->phi[1], yp, (size_t)n * sizeof *yp);
    s->need_setup = 1;
    return BG_OK;
}
