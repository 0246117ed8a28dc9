/* Modified BDF for semi-explicit index-2 DAEs F(t, y, y') = 0.
 *
 * Method. Variable-order, variable-step BDF in fixed-leading-coefficient form with the history
 * kept as modified divided differences phi[0..k+1], as in DASSL and IDA (Brenan, Campbell and
 * Petzold 1996, sec. 5.2-5.3; the step/order rules follow IDA's published algorithm: order raised
 * and step doubled in the initial phase, then orders k-1, k, k+1 compared by their scaled error
 * estimates; the step kept unless the estimate asks for a ratio >= 2 or <= 1, ratios bounded to
 * [0.5, 0.9] on decrease and 2 on increase). The corrector is a modified Newton iteration on
 *     G(y) = F(t_n, y, y_pred' + cj (y - y_pred)) = 0,  cj = alpha_s / h,
 * with the iteration matrix M = dF/dy + cj dF/dy' kept across steps while cj stays within
 * [0.6, 1.67] of the value it was factored with (corrections rescaled by 2/(1 + cj/cj_f)),
 * refreshed after a convergence failure, and refactored by KLU with the symbolic analysis reused.
 * At most max_newton iterations per attempt, or up to twice that on a matrix evaluated at the
 * step itself while the rate (0.5 or better) says it will converge within them
 * (newton_extends).
 *
 * Index 2 (Brenan et al. sec. 3.3; Hairer and Wanner, Solving ODEs II, sec. VII.3): BDF applied to
 * an index-2 system converges with order k in the differential and index-1 variables, but the
 * local error estimate of an index-2 variable lambda does not tend to zero with h in the usual
 * way: its error is O(h^k) only after division by h. Two policies are offered:
 *   DAE_I2_EXCLUDE: lambda's weight in the error norm is 0 (IDA's "suppress algebraic" applied
 *     to the index-2 variables only; index-1 algebraic variables stay in the test);
 *   DAE_I2_SCALE_H: lambda's weight is multiplied by |h| (the estimate of h*lambda, which has the
 *     units of an impulse and the order of the differential variables).
 * The Newton convergence norm weighs lambda in full by default: its Newton error enters the
 * differential variables within the same step (through dF/dlambda) and with them the error
 * estimate, so stopping early on lambda shows up as spurious error-test failures. (Option
 * newton_index2_scale_h scales lambda's Newton weight by |h| instead; on the index-2 pendulum at
 * rtol 1e-10 it took 510 steps against 189 with full weight, bench/ida_compare.)
 * The convergence-rate estimate is reset (to IDA's cautious 100) whenever cj changes, since a
 * rate measured with one iteration matrix says little about the next; without this the solver
 * accepted one-iteration corrections on a stale rate and the pendulum needed 161 steps instead of
 * 67 at rtol 1e-6.
 * Step growth after an error-test failure: the step may double again only after k+1 steps have
 * been accepted since the failure. Index-2 problems otherwise cycle: a doubled step shifts the
 * O(h) error of lambda into the differential variables' error estimate, the step fails, is
 * halved, succeeds, doubles, ... (lin2 at rtol 1e-10: 10031 steps with 8939 failures before,
 * 246 steps with 2 failures after; IDA, which has no such rule, takes 10183).
 * Conditioning: the unscaled M has rows of size cj ~ 1/h (rows containing y') and rows of size 1
 * (constraints) and its condition grows like h^-2. We factor R M C instead, with R = h/alpha on
 * rows that contain y' and 1 elsewhere, C = cj on index-2 columns and 1 elsewhere; every block is
 * then O(1). The solution is mapped back by delta = C z.
 * Consistent initial values and the structural classification of the unknowns: bg_dae_init.c.
 * Drift: with position constraints g(y) given, the maximum |g| after each step is recorded and,
 * if asked, y is projected back by the same minimum-norm correction.
 * Breakpoints: steps are clipped to land exactly on each breakpoint, where the method restarts at
 * order 1 from consistent values (the left value of y, the right value of y').
 * Roots of event functions are located on the interpolant by the Illinois variant of regula
 * falsi. */
#include "bg_dae.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bg_fdjac.h"

#include "bg_dae_impl.h"

double daei_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

const char *daei_vname(const dae_solver *s, int i, char *buf, size_t sz)
{
    if (i < 0 || i >= s->n) return "(none)";
    if (s->names && s->names[i]) return s->names[i];
    snprintf(buf, sz, "y[%d]", i);
    return buf;
}

const char *daei_ename(const dae_solver *s, int i, char *buf, size_t sz)
{
    if (i < 0 || i >= s->n) return "(no equation)";
    if (s->enames && s->enames[i]) return s->enames[i];
    char nb[32];
    int v = s->rowvar ? s->rowvar[i] : -1;
    if (v >= 0)
        snprintf(buf, sz, "equation %d (the row of %s)", i, daei_vname(s, v, nb, sizeof nb));
    else
        snprintf(buf, sz, "equation %d", i);
    return buf;
}

void daei_note(dae_solver *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->note, sizeof s->note, fmt, ap);
    va_end(ap);
}

int dae_options_default(dae_options *o)
{
    if (!o) return BG_ERR_ARGUMENT;
    memset(o, 0, sizeof *o);
    o->rtol = 1e-6;
    o->atol = 1e-8;
    o->max_order = 5;
    o->max_steps = 100000;
    o->index2 = DAE_I2_EXCLUDE;
    o->linsol = LS_KLU;
    o->max_newton = 4;
    return BG_OK;
}

const char *dae_return_name(int code)
{
    switch (code) {
    case DAE_SUCCESS:
        return "DAE_SUCCESS";
    case DAE_TSTOP_RETURN:
        return "DAE_TSTOP_RETURN";
    case DAE_ROOT_RETURN:
        return "DAE_ROOT_RETURN";
    case DAE_TOO_MUCH_WORK:
        return "DAE_TOO_MUCH_WORK";
    case DAE_TOO_MUCH_ACC:
        return "DAE_TOO_MUCH_ACC";
    case DAE_ERR_FAIL:
        return "DAE_ERR_FAIL";
    case DAE_CONV_FAIL:
        return "DAE_CONV_FAIL";
    case DAE_LSETUP_FAIL:
        return "DAE_LSETUP_FAIL";
    case DAE_RES_FAIL:
        return "DAE_RES_FAIL";
    case DAE_CALLBACK_FAIL:
        return "DAE_CALLBACK_FAIL";
    case DAE_INIT_FAIL:
        return "DAE_INIT_FAIL";
    case DAE_STEP_TOO_SMALL:
        return "DAE_STEP_TOO_SMALL";
    default:
        return bg_status_name(code);
    }
}

/* ---------------------------------------------------------------- callbacks ---- */

/* First entry of v[0..n) that is not finite, -1 if none. */
static int first_nonfinite(const double *v, int n)
{
    /* Inf and NaN have all exponent bits set: one branch-free pass in integers, which the
     * compiler vectorizes, then the search only when something is not finite */
    const uint64_t expo = 0x7ff0000000000000u;
    uint64_t bad = 0;
    for (int i = 0; i < n; i++) {
        uint64_t b;
        memcpy(&b, &v[i], sizeof b);
        bad |= (b & expo) == expo;
    }
    if (!bad) return -1;
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i])) return i;
    return -1;
}

/* Residual with timing, counting and NaN detection: 0, > 0 recoverable, < 0 fatal. A failure
 * is described in s->note: the status, the time and the first equation that is NaN or Inf. */
int daei_call_res(dae_solver *s, double t, const double *y, const double *yp, double *F, int fd)
{
    memset(F, 0, (size_t)s->n * sizeof *F); /* rows left NaN by a failing residual name it */
    double t0 = daei_clock(s);
    int r = s->p.res(s->p.user, t, y, yp, F);
    s->st.t_res += daei_clock(s) - t0;
    if (fd)
        s->st.res_evals_fd++;
    else
        s->st.res_evals++;
    int bad = first_nonfinite(F, s->n);
    if (r == 0 && bad < 0) return 0;
    char eb[192];
    if (r != 0 && bad >= 0)
        daei_note(s, "the residual function returned the %s status %d at t = %.17g, %s is %g",
                  r < 0 ? "fatal" : "recoverable", r, t, daei_ename(s, bad, eb, sizeof eb), F[bad]);
    else if (r != 0)
        daei_note(s, "the residual function returned the %s status %d at t = %.17g",
                  r < 0 ? "fatal" : "recoverable", r, t);
    else
        daei_note(s, "the residual of %s is %g at t = %.17g", daei_ename(s, bad, eb, sizeof eb),
                  F[bad], t);
    return r != 0 ? r : BG_RECOVERABLE;
}

/* Column of entry p of A (binary search in colptr). */
static int column_of(const sp_csc *A, int p)
{
    int lo = 0, hi = A->ncol - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo + 1) / 2;
        if (A->colptr[mid] <= p)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

static int fd_res_y(void *u, const double *x, double *f)
{
    dae_solver *s = u;
    return daei_call_res(s, s->fd_t, x, s->fd_yp, f, 1);
}

static int fd_res_yp(void *u, const double *x, double *f)
{
    dae_solver *s = u;
    return daei_call_res(s, s->fd_t, s->fd_y, x, f, 1);
}

/* Jy, Jyp at (t, y, yp); F = F(t, y, yp) must be given (used by finite differences). */
int daei_eval_jac(dae_solver *s, double t, const double *y, const double *yp, const double *F)
{
    double t0 = daei_clock(s);
    int r;
    s->st.jac_evals++;
    if (s->p.jac) {
        r = s->p.jac(s->p.user, t, y, yp, s->Jy, s->Jyp);
    } else {
        s->fd_t = t;
        s->fd_y = y;
        s->fd_yp = yp;
        for (int j = 0; j < s->n; j++)
            s->typ[j] = 1.0 / (s->ewt[j] * s->o.rtol);
        r = sp_fdjac_eval(s->fdy, fd_res_y, s, y, F, s->typ, s->Jy);
        if (r == 0) {
            double hs = fabs(s->hh) > 0 ? fabs(s->hh) : 1.0;
            for (int j = 0; j < s->n; j++)
                s->typ[j] = 1.0 / (s->ewt[j] * s->o.rtol * hs);
            r = sp_fdjac_eval(s->fdyp, fd_res_yp, s, yp, F, s->typ, s->Jyp);
        }
    }
    s->st.t_jac += daei_clock(s) - t0;
    if (r != 0 && s->p.jac)
        daei_note(s, "the Jacobian function returned the %s status %d at t = %.17g",
                  r < 0 ? "fatal" : "recoverable", r, t);
    if (r == 0) {
        for (int m = 0; m < 2 && r == 0; m++) {
            const sp_csc *J = m ? s->Jyp : s->Jy;
            int p = first_nonfinite(J->val, J->nnz);
            if (p >= 0) {
                char eb[192], nb[32];
                daei_note(s, "the Jacobian entry d(%s)/d(%s%s) is %g at t = %.17g",
                          daei_ename(s, J->rowind[p], eb, sizeof eb),
                          daei_vname(s, column_of(J, p), nb, sizeof nb), m ? "'" : "", J->val[p],
                          t);
                r = BG_RECOVERABLE;
            }
        }
    }
    return r;
}

/* ------------------------------------------------------------------- norms ---- */

#define TOL_FLOOR 1e-100

void daei_set_weights(dae_solver *s, const double *restrict y)
{
    double h = fabs(s->hh), rtol = s->o.rtol;
    int n = s->n;
    double *restrict ewt = s->ewt, *restrict wd = s->wdiff, *restrict we = s->werr,
                     *restrict wn = s->wnewt;
    const double *restrict at = s->atol;
    /* every weight as that of a differential unknown in one branch-free pass, then the
     * algebraic unknowns through their index lists */
    for (int i = 0; i < n; i++) {
        /* TOL_FLOOR added: the weights and their squares in the norms stay finite (atol = 0
         * with y_i = 0, or a denormal atol) and any other tolerance is unchanged; no branch,
         * so that the loop vectorizes */
        double w = 1.0 / (rtol * fabs(y[i]) + at[i] + TOL_FLOOR);
        ewt[i] = w;
        wd[i] = w;
        we[i] = w;
        wn[i] = w;
    }
    if (s->o.exclude_alg)
        for (int k = 0; k < s->na1; k++)
            we[s->a1cols[k]] = 0.0;
    for (int k = 0; k < s->na2; k++) {
        int i = s->a2cols[k];
        double w = ewt[i];
        wd[i] = 0.0;
        we[i] = s->o.index2 == DAE_I2_EXCLUDE ? 0.0 : w * h;
        wn[i] = s->o.newton_index2_scale_h ? w * h : w;
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

/* --------------------------------------------------------------- creation ---- */

/* Dense n x n pattern; with kind, only the columns of differential variables. */
static sp_csc *dense_pattern(int n, const int *kind)
{
    sp_builder *b = sp_builder_create(n, n, n * n);
    if (!b) return NULL;
    for (int j = 0; j < n; j++)
        if (!kind || kind[j] == DAE_DIFF)
            for (int i = 0; i < n; i++)
                sp_builder_add(b, i, j, 0.0);
    sp_csc *P = sp_builder_finish(b, NULL);
    sp_builder_free(&b);
    return P;
}

void dae_free(dae_solver **sp)
{
    if (!sp || !*sp) return;
    dae_solver *s = *sp;
    free(s->kind);
    if (s->names) {
        for (int i = 0; i < s->n; i++)
            free(s->names[i]);
        free(s->names);
    }
    if (s->enames) {
        for (int i = 0; i < s->n; i++)
            free(s->enames[i]);
        free(s->enames);
    }
    free(s->rowvar);
    free(s->atol);
    free(s->bkpt);
    sp_csc_free(&s->Jy);
    sp_csc_free(&s->Jyp);
    sp_union_free(&s->U);
    sp_fdjac_free(&s->fdy);
    sp_fdjac_free(&s->fdyp);
    ls_free(&s->ls);
    daei_init_free(s);
    sp_csc_free(&s->G);
    aat_free(&s->aat_proj);
    free(s->gv);
    free(s->gw);
    for (int j = 0; j < NPHI; j++)
        free(s->phi[j]);
    free(s->ewt);
    free(s->werr);
    free(s->wnewt);
    free(s->wdiff);
    free(s->y);
    free(s->yp);
    free(s->ypred);
    free(s->yppred);
    free(s->ee);
    free(s->delta);
    free(s->res);
    free(s->tmp);
    free(s->tmp2);
    free(s->typ);
    free(s->glo);
    free(s->ghi);
    free(s->gmid);
    free(s->rfound);
    free(s);
    *sp = NULL;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The checks of dae_create that need no allocation: sizes, options, patterns. */
static int check_problem(const dae_problem *p, const dae_options *o, bg_error *err)
{
    const char *w = "dae_create";
    int n = p->n;
    bg_error perr = {0};
    const char *hname[3] = {"h_init", "h_min", "h_max"};
    const double hval[3] = {o->h_init, o->h_min, o->h_max};
    for (int k = 0; k < 3; k++)
        if (!(hval[k] >= 0) || !isfinite(hval[k]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, w, "%s = %g: must be finite and >= 0",
                                  hname[k], hval[k]);
    if (o->index2 != DAE_I2_EXCLUDE && o->index2 != DAE_I2_SCALE_H)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "index2 = %d is not a dae_index2_policy",
                              (int)o->index2);
    if (o->linsol != LS_KLU && o->linsol != LS_DENSE)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "linsol = %d is not LS_KLU or LS_DENSE",
                              (int)o->linsol);
    if (o->has_t_stop && !isfinite(o->t_stop))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "t_stop = %g is not finite", o->t_stop);
    if (o->nbreakpoints < 0 || (o->nbreakpoints > 0 && !o->breakpoints))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "nbreakpoints = %d needs that many breakpoints (array %s)",
                              o->nbreakpoints, o->breakpoints ? "given" : "NULL");
    for (int k = 0; k < o->nbreakpoints; k++)
        if (!isfinite(o->breakpoints[k]))
            return bg_error_raise(err, BG_ERR_ARGUMENT, w, "breakpoint %d is %g", k,
                                  o->breakpoints[k]);
    if (p->ncons < 0 || p->nroots < 0)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "ncons = %d and nroots = %d must be >= 0",
                              p->ncons, p->nroots);
    if (p->ncons > 0 && (!p->cons || !p->cons_pattern))
        return bg_error_raise(err, BG_ERR_ARGUMENT, w,
                              "ncons = %d needs a constraint function and its pattern (cons %s, "
                              "cons_pattern %s)",
                              p->ncons, p->cons ? "given" : "NULL",
                              p->cons_pattern ? "given" : "NULL");
    if (p->nroots > 0 && !p->roots)
        return bg_error_raise(err, BG_ERR_ARGUMENT, w, "nroots = %d but no root function",
                              p->nroots);
    const sp_csc *pat[2] = {p->jac_y_pattern, p->jac_yp_pattern};
    for (int k = 0; k < 2; k++) {
        if (!pat[k]) continue;
        if (sp_csc_check(pat[k], &perr) != BG_OK)
            return bg_error_raise(err, BG_ERR_PATTERN, w, "the pattern of dF/dy%s: %s",
                                  k ? "'" : "", perr.message);
        if (pat[k]->nrow != n || pat[k]->ncol != n)
            return bg_error_raise(err, BG_ERR_PATTERN, w,
                                  "the pattern of dF/dy%s is %d x %d, the problem has n = %d",
                                  k ? "'" : "", pat[k]->nrow, pat[k]->ncol, n);
    }
    if (p->ncons > 0) {
        if (sp_csc_check(p->cons_pattern, &perr) != BG_OK)
            return bg_error_raise(err, BG_ERR_PATTERN, w, "the constraint pattern: %s",
                                  perr.message);
        if (p->cons_pattern->nrow != p->ncons || p->cons_pattern->ncol != n)
            return bg_error_raise(err, BG_ERR_PATTERN, w,
                                  "the constraint pattern is %d x %d, expected ncons x n = %d x %d",
                                  p->cons_pattern->nrow, p->cons_pattern->ncol, p->ncons, n);
    }
    return BG_OK;
}

/* rowvar[i]: the unknown matched to equation i in a maximum matching of the rows and columns of
 * the pattern M: diagonal entries first, then any free row of each column, then augmenting paths
 * (depth first, explicit stack); -1 for rows left unmatched. Only for naming equations in
 * messages. */
static int match_rows(const sp_csc *M, int *rowvar)
{
    int n = M->ncol, ok = 0;
    int *colrow = malloc(((size_t)n + 1) * sizeof *colrow);
    int *stamp = calloc((size_t)n + 1, sizeof *stamp);
    int *svar = malloc(((size_t)n + 1) * sizeof *svar), *sp = malloc(((size_t)n + 1) * sizeof *sp);
    int *srow = malloc(((size_t)n + 1) * sizeof *srow);
    if (!colrow || !stamp || !svar || !sp || !srow) goto done;
    for (int i = 0; i < n; i++)
        rowvar[i] = colrow[i] = -1;
    for (int j = 0; j < n; j++)
        if (sp_csc_find(M, j, j) >= 0) rowvar[j] = colrow[j] = j;
    for (int j = 0; j < n; j++) /* cheap pass: any free row of the column */
        for (int p = M->colptr[j]; colrow[j] < 0 && p < M->colptr[j + 1]; p++)
            if (rowvar[M->rowind[p]] < 0) {
                rowvar[M->rowind[p]] = j;
                colrow[j] = M->rowind[p];
            }
    for (int j0 = 0; j0 < n; j0++) {
        if (colrow[j0] >= 0) continue;
        int top = 0, found = 0;
        svar[0] = j0;
        sp[0] = M->colptr[j0];
        while (top >= 0 && !found) {
            int v = svar[top], pushed = 0;
            while (sp[top] < M->colptr[v + 1]) {
                int i = M->rowind[sp[top]++];
                if (stamp[i] == j0 + 1) continue;
                stamp[i] = j0 + 1;
                srow[top] = i;
                if (rowvar[i] < 0) {
                    found = 1;
                } else {
                    svar[top + 1] = rowvar[i];
                    sp[top + 1] = M->colptr[rowvar[i]];
                    top++;
                    pushed = 1;
                }
                break;
            }
            if (found) break;
            if (!pushed && sp[top] >= M->colptr[v + 1]) top--;
        }
        if (found)
            for (int k = top; k >= 0; k--) {
                rowvar[srow[k]] = svar[k];
                colrow[svar[k]] = srow[k];
            }
    }
    ok = 1;
done:
    free(colrow);
    free(stamp);
    free(svar);
    free(sp);
    free(srow);
    return ok;
}

dae_solver *dae_create(const dae_problem *p, const dae_options *o, bg_error *err)
{
    const char *w = "dae_create";
    dae_options def;
    if (!o) {
        dae_options_default(&def);
        o = &def;
    }
    if (!p || p->n < 1 || !p->res) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "problem needs n >= 1 and a residual function");
        return NULL;
    }
    int n = p->n;
    if (check_problem(p, o, err) != BG_OK) return NULL;
    if (!(o->rtol >= 0) || (!o->atol_vec && !(o->atol >= 0)) ||
        (o->rtol == 0 && o->atol == 0 && !o->atol_vec)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "tolerances must be >= 0 and not both zero (rtol %g, atol %g)", o->rtol,
                       o->atol);
        return NULL;
    }
    if (!(o->rtol < 1) || (!o->atol_vec && !isfinite(o->atol))) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "rtol must be below 1 and atol finite (rtol %g, atol %g)", o->rtol, o->atol);
        return NULL;
    }
    if (o->max_order < 1 || o->max_order > MAXORD) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "max_order must be 1..5 (got %d)", o->max_order);
        return NULL;
    }
    if (o->projection && (!p->cons || p->ncons < 1 || !p->cons_pattern)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w,
                       "projection needs position constraints (cons, ncons, cons_pattern)");
        return NULL;
    }
    if (o->h_max > 0 && o->h_min > o->h_max) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "h_min = %g exceeds h_max = %g", o->h_min,
                       o->h_max);
        return NULL;
    }
    if (o->fixed_step && !(o->h_init > 0)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "fixed_step needs h_init > 0");
        return NULL;
    }
    if (p->jac && (!p->jac_y_pattern) != (!p->jac_yp_pattern)) {
        bg_error_raise(err, BG_ERR_ARGUMENT, w, "give both Jacobian patterns or neither");
        return NULL;
    }
    dae_solver *s = calloc(1, sizeof *s);
    if (!s) goto nomem;
    s->n = n;
    s->p = *p;
    s->o = *o;
    s->o.atol_vec = NULL;
    s->o.breakpoints = NULL;
    if (s->o.max_newton < 1) s->o.max_newton = 4;
    if (s->o.max_steps < 1) s->o.max_steps = 100000;
    s->kind = malloc((size_t)n * sizeof *s->kind);
    s->atol = malloc((size_t)n * sizeof *s->atol);
    if (!s->kind || !s->atol) goto nomem;
    for (int i = 0; i < n; i++) {
        s->kind[i] = p->kind ? p->kind[i] : DAE_DIFF;
        if (p->kind && (s->kind[i] < DAE_DIFF || s->kind[i] > DAE_ALG2)) {
            bg_error_raise(err, BG_ERR_ARGUMENT, w, "kind[%d] = %d is not a dae_var_kind", i,
                           s->kind[i]);
            dae_free(&s);
            return NULL;
        }
        s->atol[i] = o->atol_vec ? o->atol_vec[i] : o->atol;
        if (!(s->atol[i] >= 0) || !isfinite(s->atol[i]) || (s->atol[i] == 0 && o->rtol == 0)) {
            bg_error_raise(err, BG_ERR_ARGUMENT, w,
                           "atol[%d] = %g: must be >= 0 (and > 0 if rtol = 0)", i, s->atol[i]);
            dae_free(&s);
            return NULL;
        }
    }
    if (p->names) {
        s->names = calloc((size_t)n, sizeof *s->names);
        if (!s->names) goto nomem;
        for (int i = 0; i < n; i++)
            if (p->names[i] && !(s->names[i] = strdup(p->names[i]))) goto nomem;
    }
    if (p->eq_names) {
        s->enames = calloc((size_t)n, sizeof *s->enames);
        if (!s->enames) goto nomem;
        for (int i = 0; i < n; i++)
            if (p->eq_names[i] && !(s->enames[i] = strdup(p->eq_names[i]))) goto nomem;
    }
    if (o->nbreakpoints > 0) {
        s->bkpt = malloc((size_t)o->nbreakpoints * sizeof *s->bkpt);
        if (!s->bkpt) goto nomem;
        memcpy(s->bkpt, o->breakpoints, (size_t)o->nbreakpoints * sizeof *s->bkpt);
        qsort(s->bkpt, (size_t)o->nbreakpoints, sizeof *s->bkpt, cmp_double);
        s->nbkpt = o->nbreakpoints;
    }
    /* Jacobian patterns: dense where not given (dF/dy' in the differential columns only) */
    s->Jy = p->jac_y_pattern ? sp_csc_copy(p->jac_y_pattern) : dense_pattern(n, NULL);
    s->Jyp = p->jac_yp_pattern ? sp_csc_copy(p->jac_yp_pattern) : dense_pattern(n, p->kind);
    if (!s->Jy || !s->Jyp) goto nomem;
    /* no kinds given: classify from the structure */
    if (!p->kind && dae_classify(s->Jy, s->Jyp, s->kind) < 0) goto nomem;
    sp_csc_zero(s->Jy);
    sp_csc_zero(s->Jyp);
    s->U = sp_union_create(s->Jy, s->Jyp);
    if (!s->U) goto nomem;
    s->rowvar = malloc((size_t)n * sizeof *s->rowvar);
    if (!s->rowvar || !match_rows(s->U->M, s->rowvar)) goto nomem;
    if (!p->jac) {
        s->fdy = sp_fdjac_create(s->Jy);
        s->fdyp = sp_fdjac_create(s->Jyp);
        if (!s->fdy || !s->fdyp) goto nomem;
    }
    s->ls = ls_create(o->linsol, s->U->M, err);
    if (!s->ls) {
        dae_free(&s);
        return NULL;
    }
    for (int i = 0; i < n; i++)
        s->has_alg2 |= s->kind[i] == DAE_ALG2;
    if (daei_init_setup(s, err) != BG_OK) {
        dae_free(&s);
        return NULL;
    }
    if (p->cons && p->ncons > 0) {
        s->G = sp_csc_copy(p->cons_pattern);
        s->gv = malloc((size_t)p->ncons * sizeof *s->gv);
        s->gw = malloc((size_t)p->ncons * sizeof *s->gw);
        if (!s->G || !s->gv || !s->gw) goto nomem;
        s->aat_proj = aat_create(s->G, err);
        if (!s->aat_proj) {
            dae_free(&s);
            return NULL;
        }
    }
    for (int j = 0; j < NPHI; j++)
        if (!(s->phi[j] = calloc((size_t)n, sizeof(double)))) goto nomem;
    double **vecs[] = {&s->ewt,    &s->werr, &s->wnewt, &s->wdiff, &s->y,   &s->yp,   &s->ypred,
                       &s->yppred, &s->ee,   &s->delta, &s->res,   &s->tmp, &s->tmp2, &s->typ};
    for (size_t v = 0; v < sizeof vecs / sizeof *vecs; v++)
        if (!(*vecs[v] = calloc((size_t)n, sizeof(double)))) goto nomem;
    if (p->nroots > 0) {
        s->glo = calloc((size_t)p->nroots, sizeof(double));
        s->ghi = calloc((size_t)p->nroots, sizeof(double));
        s->gmid = calloc((size_t)p->nroots, sizeof(double));
        s->rfound = calloc((size_t)p->nroots, sizeof(int));
        if (!s->glo || !s->ghi || !s->gmid || !s->rfound) goto nomem;
    }
    return s;
nomem:
    dae_free(&s);
    bg_error_raise(err, BG_ERR_MEMORY, w, "out of memory (n = %d)", n);
    return NULL;
}

bg_error *dae_get_error(dae_solver *s)
{
    return s ? &s->err : NULL;
}
double dae_current_time(const dae_solver *s)
{
    return s && s->initialized ? s->tn : NAN;
}
const dae_stats *dae_get_stats(const dae_solver *s)
{
    return s ? &s->st : NULL;
}

void daei_sync_stats(dae_solver *s)
{
    ls_solver *all[3] = {s->ls, s->kls, s->kktls};
    s->st.factor_symbolic = s->st.factor_full = s->st.factor_refactor = 0;
    for (int k = 0; k < 3; k++) {
        if (!all[k]) continue;
        const ls_stats *a = ls_get_stats(all[k]);
        s->st.factor_symbolic += a->symbolic;
        s->st.factor_full += a->factor;
        s->st.factor_refactor += a->refactor;
    }
}

/* ----------------------------------------------------------- initial values ---- */

int dae_init(dae_solver *s, double t0, const double *y0, const double *yp0)
{
    if (!s) return BG_ERR_ARGUMENT;
    if (!y0) return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_init", "y0 is NULL");
    if (!isfinite(t0))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_init", "t0 = %g is not finite", t0);
    char nb[32];
    for (int i = 0; i < s->n; i++)
        if (!isfinite(y0[i]) || (yp0 && !isfinite(yp0[i])))
            return bg_error_raise(&s->err, BG_ERR_NONFINITE, "dae_init",
                                  "initial value of %s is not finite",
                                  daei_vname(s, i, nb, sizeof nb));
    memset(&s->st, 0, sizeof s->st);
    s->st.h_min_used = INFINITY;
    s->st.rcond_min = INFINITY;
    s->st.t_last_restart = NAN;
    memcpy(s->phi[0], y0, (size_t)s->n * sizeof *y0);
    if (yp0)
        memcpy(s->phi[1], yp0, (size_t)s->n * sizeof *yp0);
    else
        memset(s->phi[1], 0, (size_t)s->n * sizeof *yp0);
    s->tn = t0;
    s->first = 1;
    s->hh = 0;
    s->hused = 0;
    s->kused = 0;
    s->kk = 1;
    s->ibk = 0;
    while (s->ibk < s->nbkpt && s->bkpt[s->ibk] <= t0)
        s->ibk++;
    s->root_pending = 0;
    s->restart_pending = 0;
    s->nautorestart = 0;
    s->ncrawl = 0;
    s->fail_note[0] = '\0';
    s->dn0_last = HUGE_VAL;
    s->t_fail = NAN;
    s->init_side = 0;
    s->tlo = t0;
    s->need_setup = 1;
    s->initialized = 1;
    s->failed = 0;
    s->note[0] = '\0';
    bg_error_clear(&s->err);
    if (s->p.nroots > 0) {
        int r = s->p.roots(s->p.user, t0, y0, s->phi[1], s->glo);
        if (r < 0)
            return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, "dae_init",
                                  "root function returned %d at t = %g", r, t0);
    }
    return BG_OK;
}

int dae_reinit(dae_solver *s, double t, const double *y, const double *yp)
{
    if (!s) return BG_ERR_ARGUMENT;
    dae_stats keep = s->st;
    int r = dae_init(s, t, y, yp);
    if (r == BG_OK) s->st = keep;
    return r;
}

int dae_set_history(dae_solver *s, double t0, double h, int k, const double *Y)
{
    if (!s || !Y || k < 1 || k > MAXORD || !(h > 0))
        return s ? bg_error_raise(&s->err, BG_ERR_ARGUMENT, "dae_set_history",
                                  "needs 1 <= k <= 5 and h > 0 (k = %d, h = %g)", k, h)
                 : BG_ERR_ARGUMENT;
    int n = s->n;
    for (size_t i = 0; i < (size_t)(k + 1) * n; i++)
        if (!isfinite(Y[i]))
            return bg_error_raise(&s->err, BG_ERR_NONFINITE, "dae_set_history",
                                  "history value %zu (y(t0 - %zu h) of unknown %zu) is not finite",
                                  i, i / (size_t)n, i % (size_t)n);
    int r = dae_init(s, t0, Y, NULL);
    if (r != BG_OK) return r;
    /* at constant step the modified divided differences are backward differences:
     * phi_j = nabla^j y_n */
    for (int j = 0; j <= k; j++) {
        for (int i = 0; i < n; i++) {
            double d = 0, c = 1; /* sum_m (-1)^m C(j,m) y_{n-m} */
            for (int m = 0; m <= j; m++) {
                d += c * Y[(size_t)m * n + i];
                c = -c * (double)(j - m) / (double)(m + 1);
            }
            s->phi[j][i] = d;
        }
    }
    for (int j = 0; j <= MAXORD; j++)
        s->psi[j] = (j + 1) * h;
    s->hh = h;
    s->hused = h;
    s->kk = k;
    s->kused = k;
    s->ns = 0; /* the first set_coeffs computes the (constant-step) coefficients */
    s->phase = 1;
    s->first = 0;
    s->o.h_init = h;
    s->o.max_order = k;
    return BG_OK;
}

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
    for (int j = s->ns; j <= k; j++) {
        double *restrict p = s->phi[j], b = s->beta[j];
        for (int i = 0; i < s->n; i++)
            p[i] *= b;
    }
}

static void restore(dae_solver *s)
{
    for (int j = 1; j <= s->kk; j++)
        s->psi[j - 1] = s->psi[j] - s->hh;
    for (int j = s->ns; j <= s->kk; j++) {
        double *restrict p = s->phi[j], b = s->beta[j];
        for (int i = 0; i < s->n; i++)
            p[i] /= b;
    }
}

/* ypred, yppred from the history; y and yp start there (the Newton iteration's initial
 * values). */
static void predict(dae_solver *s)
{
    int n = s->n;
    double *restrict yq = s->ypred, *restrict ypq = s->yppred;
    const double *restrict p0 = s->phi[0], *restrict p1 = s->phi[1];
    double g1 = s->gamma[1];
    for (int i = 0; i < n; i++) {
        yq[i] = p0[i] + p1[i];
        ypq[i] = g1 * p1[i];
    }
    /* the remaining differences two at a time: fewer passes over yq and ypq */
    int j = 2;
    for (; j + 1 <= s->kk; j += 2) {
        const double *restrict pa = s->phi[j], *restrict pb = s->phi[j + 1];
        double ga = s->gamma[j], gb = s->gamma[j + 1];
        for (int i = 0; i < n; i++) {
            yq[i] += pa[i] + pb[i];
            ypq[i] += ga * pa[i] + gb * pb[i];
        }
    }
    double *restrict y = s->y, *restrict yp = s->yp;
    if (j == s->kk) {
        const double *restrict pa = s->phi[j];
        double ga = s->gamma[j];
        for (int i = 0; i < n; i++) {
            y[i] = yq[i] += pa[i];
            yp[i] = ypq[i] += ga * pa[i];
        }
    } else {
        memcpy(y, yq, (size_t)n * sizeof *y);
        memcpy(yp, ypq, (size_t)n * sizeof *yp);
    }
}

enum { SU_OK = 0, SU_RECOVER = 1, SU_SINGULAR = 2, SU_LSFAIL = 3 };

/* Jacobian, scaled Newton matrix, factorization: SU_*, or the fatal (< 0) status of a callback.
 * A failure is described in s->note. */
static int setup(dae_solver *s, double t, const double *F)
{
    int r = daei_eval_jac(s, t, s->y, s->yp, F);
    if (r < 0) return r;
    if (r > 0) return SU_RECOVER;
    double t0 = daei_clock(s);
    double cj = s->cj;
    sp_union_combine(s->U, s->Jy, 1.0, s->Jyp, cj);
    sp_csc *M = s->U->M;
    for (int j = 0; j < s->n; j++) {
        double cs = s->kind[j] == DAE_ALG2 ? cj : 1.0;
        for (int p = M->colptr[j]; p < M->colptr[j + 1]; p++)
            M->val[p] *= cs * (s->rowscaled[M->rowind[p]] ? 1.0 / cj : 1.0);
    }
    r = ls_factor(s->ls, M);
    s->st.t_linalg += daei_clock(s) - t0;
    if (r == BG_OK) s->st.rcond_min = fmin(s->st.rcond_min, ls_get_stats(s->ls)->rcond);
    s->cjf = cj;
    s->jac_current = 1;
    s->need_setup = 0;
    s->ss = 20.0;
    if (r == BG_OK) return SU_OK;
    if (r == BG_ERR_SINGULAR) {
        char nb[32];
        int c = ls_singular_col(s->ls);
        daei_note(s,
                  "the Newton matrix is singular at t = %.17g: nothing determines %s (column %d; "
                  "%s)",
                  t, daei_vname(s, c, nb, sizeof nb), c, ls_get_error(s->ls)->message);
        return SU_SINGULAR;
    }
    daei_note(s, "the Newton matrix could not be factored at t = %.17g: %s", t,
              ls_get_error(s->ls)->message);
    return r == BG_ERR_NONFINITE ? SU_RECOVER : SU_LSFAIL;
}

/* delta = M^-1 F with the scaling of the factored matrix. */
static int lsolve(dae_solver *s, double *v)
{
    double t0 = daei_clock(s);
    double cj = s->cjf, rcj = 1.0 / cj;
    for (int k = 0; k < s->nsrows; k++)
        v[s->srows[k]] *= rcj;
    int r = ls_solve(s->ls, v, 1);
    for (int k = 0; k < s->na2; k++)
        v[s->a2cols[k]] *= cj;
    if (s->cj != cj) {
        double f = 2.0 / (1.0 + s->cj / cj);
        for (int j = 0; j < s->n; j++)
            v[j] *= f;
    }
    s->st.linear_solves++;
    s->st.t_linalg += daei_clock(s) - t0;
    return r;
}

enum { NL_OK = 0, NL_RECOVER = 1, NL_RES_RECOVER = 2, NL_SINGULAR = 3, NL_LSFAIL = 4 };

/* The unknown with the largest |v_i w_i|, -1 if all are zero. */
static int largest_weighted(const dae_solver *s, const double *v, const double *w)
{
    int im = -1;
    double m = 0;
    for (int i = 0; i < s->n; i++) {
        double e = fabs(v[i] * w[i]);
        if (e > m || (im < 0 && isnan(e))) {
            m = e;
            im = i;
        }
    }
    return im;
}

/* Describes a Newton failure by the unknown with the largest weighted correction. */
static void note_newton(dae_solver *s, double t, double rate)
{
    char nb[32];
    int i = largest_weighted(s, s->delta, s->wnewt);
    if (i < 0) {
        daei_note(s, "the Newton iteration did not converge at t = %.17g", t);
        return;
    }
    daei_note(s,
              "the Newton iteration did not converge at t = %.17g (rate %.3g): the largest "
              "weighted correction is in %s (%.3g against the tolerance %.3g)",
              t, rate, daei_vname(s, i, nb, sizeof nb), fabs(s->delta[i]), 1.0 / s->wnewt[i]);
}

/* Whether the iteration goes on past max_newton after iteration m (0-based) with correction
 * norm dn at rate: only on a Newton matrix evaluated at this step (a stale one is refreshed
 * instead, at the same h), while it contracts at RATE_EXTEND or better, and while the rate says
 * it will pass the test within NEWTON_EXTEND * max_newton iterations in all. Failing there
 * instead cuts the step by 4. On the crane with 512 boom elements the predictor misses the
 * index-2 reactions by about 200 tolerances, the iteration then needs 5 or 6 iterations at rates
 * of 0.2 to 0.4, and the cut steps cost 1.23 Jacobians and 22 ms per step against 0.4 and 11 ms
 * with the extension (bench scaling series). */
static int newton_extends(const dae_solver *s, int m, double dn, double rate)
{
    if (!s->jac_current || m < 1 || !(rate <= RATE_EXTEND) || rate <= 0) return 0;
    double need = ceil(log(EPS_NEWT / (s->ss * dn)) / log(rate));
    return m + 1 + need <= NEWTON_EXTEND * s->o.max_newton;
}

/* Newton corrector; y, yp, ee hold the result. Returns NL_* or < 0 fatal (a callback's status).
 * A failure is described in s->note. */
/* Whether the first correction moved an index-1 algebraic unknown by more than half its size,
 * by more than JUMP_TOLS of its tolerances and by more than JUMP_CHANGE times its change over
 * the last step (phi[1]): the predictor missed a jump (an input that switched inside the step),
 * and the linearisation at the predictor says little about where the unknowns that depend on
 * it go. The chain that makes this matter: a reference acceleration jumps, the Newton matrix of
 * a saturated controller has d(out)/d(in) = 0, the first correction moves the input and leaves
 * the output at the predictor's value; the rate of earlier steps (1e-7 on the crane in
 * saturation) then accepts the step with the controller on the wrong side, out of the error
 * test (exclude_alg), and the run goes on silently wrong (the crane's reference kinks without
 * breakpoints, rtol 1e-6: 4.3e4 tolerances at the end). Another iteration evaluates the
 * residual where the first one went and measures the rate there. The last condition keeps
 * unknowns that the steps do not resolve out: beam efforts near zero that the predictor misses
 * by about their change per step (at 512 boom elements, without it, the rule fired at half
 * the steps and cost 10 % more Newton iterations); a source that jumps after constant or slowly
 * varying values has a change per step far below the jump. */
static int first_correction_jumps(const dae_solver *s)
{
    const double *restrict y = s->y, *restrict ee = s->ee, *restrict w = s->ewt,
                           *restrict p1 = s->phi[1];
    for (int k = 0; k < s->na1; k++) {
        int i = s->a1cols[k];
        double d = fabs(ee[i]); /* after one iteration: the correction */
        if (d * w[i] > JUMP_TOLS && d > 0.5 * fmax(fabs(y[i]), fabs(y[i] - ee[i])) &&
            d > JUMP_CHANGE * fabs(p1[i]))
            return 1;
    }
    return 0;
}

static int newton(dae_solver *s, double t)
{
    int n = s->n;
    /* y and yp start at the predictor (predict); ee accumulates the corrections, which keep
     * their own digits. Formed as y - ypred after the iteration instead, it carries the
     * rounding of every update of y (eps |y|) into the history: the crane with a 1000 times
     * stiffer boom then started with steps of 1e-11 at order 1, its Newton iteration stalling
     * at rate 1 on a beam effort, and took over 60 s instead of 0.5 s */
    memset(s->ee, 0, (size_t)n * sizeof(double));
    double ratio = s->cj / (s->cjf != 0 ? s->cjf : s->cj);
    if (s->first || ratio < CJ_LOW || ratio > CJ_HIGH) s->need_setup = 1;
    /* a rate measured at another cj says little about this one: start cautious */
    if (s->cj != s->cjold) s->ss = 100.0;
    s->jac_current = 0;
    double oldnrm = 0, rate = 0;
    for (int m = 0;; m++) {
        int r = daei_call_res(s, t, s->y, s->yp, s->res, 0);
        if (r < 0) return r;
        if (r > 0) return NL_RES_RECOVER;
        if (s->need_setup) {
            r = setup(s, t, s->res);
            if (r < 0) return r;
            if (r == SU_SINGULAR) return NL_SINGULAR;
            if (r == SU_LSFAIL) return NL_LSFAIL;
            if (r == SU_RECOVER) return NL_RES_RECOVER;
        }
        { /* the residual becomes the right-hand side in place: swap the arrays */
            double *sw = s->delta;
            s->delta = s->res;
            s->res = sw;
        }
        if (lsolve(s, s->delta) != BG_OK) {
            daei_note(s, "the linear solve failed at t = %.17g: %s", t,
                      ls_get_error(s->ls)->message);
            return NL_LSFAIL;
        }
        s->st.newton_iters++;
        double dn, dn_diff;
        { /* the update and the weighted norms of the correction (all unknowns; without the
           * index-2 ones) in one pass */
            double *restrict y = s->y, *restrict yp = s->yp, *restrict ee = s->ee, cj = s->cj;
            const double *restrict d = s->delta, *restrict w = s->wnewt, *restrict wd = s->wdiff;
            double q0 = 0, q1 = 0, r0 = 0, r1 = 0;
            int i = 0;
            for (; i + 2 <= n; i += 2) {
                double a0 = d[i] * w[i], a1 = d[i + 1] * w[i + 1];
                double b0 = d[i] * wd[i], b1 = d[i + 1] * wd[i + 1];
                q0 += a0 * a0;
                q1 += a1 * a1;
                r0 += b0 * b0;
                r1 += b1 * b1;
                y[i] -= d[i];
                y[i + 1] -= d[i + 1];
                yp[i] -= cj * d[i];
                yp[i + 1] -= cj * d[i + 1];
                ee[i] -= d[i];
                ee[i + 1] -= d[i + 1];
            }
            for (; i < n; i++) {
                double a0 = d[i] * w[i], b0 = d[i] * wd[i];
                q0 += a0 * a0;
                r0 += b0 * b0;
                y[i] -= d[i];
                yp[i] -= cj * d[i];
                ee[i] -= d[i];
            }
            double nn = n > 0 ? n : 1;
            dn = sqrt((q0 + q1) / nn);
            dn_diff = sqrt((r0 + r1) / nn);
        }
        if (!isfinite(dn)) {
            char nb[32];
            int i = first_nonfinite(s->delta, n);
            daei_note(s, "the Newton correction of %s is %g at t = %.17g",
                      daei_vname(s, i, nb, sizeof nb), i >= 0 ? s->delta[i] : dn, t);
            return NL_RES_RECOVER;
        }
        if (m == 0) {
            oldnrm = dn;
            if (dn <= 1e-4 * EPS_NEWT) return NL_OK;
        } else {
            /* Round-off floor of index-2 unknowns: their corrections carry the rounding errors
             * of the other unknowns amplified by about 1/h^2, so at very small steps they stop
             * decreasing while everything else has converged. Once the corrections of the
             * differential and index-1 unknowns are far below the tolerance, accept: below
             * 1e-6 of it, or at ten times their own rounding (eps |y| against rtol |y|, so
             * 2.2e-5 of the tolerance at rtol 1e-10), which no iteration goes under. The
             * latter lets the crank of the IVP Test Set start at rtol 1e-10 and 1e-11: its
             * steps of 1e-12 s left the multipliers' corrections 1e4 tolerances large while the
             * positions' and velocities' stayed at 2e-6, their round-off, and the steps
             * collapsed at t = 4.5e-12. A fixed floor of 3e-5 instead (10 eps / rtol at rtol
             * 1e-10 and above it at 1e-8) accepts unconverged iterations at 1e-8: the crane's
             * hinge drift after 3 s grew from 1.6e-8 m to 6e-7 m. With rtol = 0 (atol alone)
             * the rounding has no bound relative to the tolerance: 1e-6; and at most 1e-2. */
            double floor_diff =
                s->o.rtol > 0 ? fmin(1e-2, fmax(1e-6, 10 * DBL_EPSILON / s->o.rtol)) : 1e-6;
            if (s->has_alg2 && dn_diff <= floor_diff) return NL_OK;
            rate = pow(dn / oldnrm, 1.0 / m);
            if (rate > RATE_MAX) {
                note_newton(s, t, rate);
                return NL_RECOVER;
            }
            s->ss = rate / (1.0 - rate);
        }
        /* The first iteration is accepted on the rate of earlier ones only as far as that rate
         * applies: the nonlinear part of the contraction grows with the size of the correction,
         * so a first correction larger than the last accepted step's (the predictor missed a
         * jump of an algebraic unknown, e.g. a saturated controller that switches inside the
         * step) has the rate scaled up by the ratio, and usually takes another iteration.
         * Without this, a step over a switch was accepted with the algebraic unknowns of the
         * predictor, out of the error test (exclude_alg), and the run went on silently wrong. */
        if (m == 0) s->dn0 = dn;
        double ssm = m == 0 ? s->ss * fmax(1.0, dn / s->dn0_last) : s->ss;
        if (ssm * dn <= EPS_NEWT && (m > 0 || !first_correction_jumps(s))) return NL_OK;
        if (m + 1 >= s->o.max_newton && !newton_extends(s, m, dn, rate)) break;
    }
    note_newton(s, t, rate);
    return NL_RECOVER;
}

/* Vector kernels on distinct arrays (restrict lets them vectorize: through the solver struct
 * the compiler must assume that every store may change the coefficients it reads). */
static void vadd(int n, double *restrict x, const double *restrict a) /* x += a */
{
    for (int i = 0; i < n; i++)
        x[i] += a[i];
}

/* The weighted RMS norm of a - b. */
static double wrms_diff(const dae_solver *s, const double *restrict a, const double *restrict b,
                        const double *restrict w)
{
    int n = s->n;
    double q0 = 0, q1 = 0;
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
    return sqrt((q0 + q1) / (n > 0 ? n : 1));
}

/* Error test: 0 pass, 1 fail. Sets err_k, err_km1, knew. */
static int test_error(dae_solver *s)
{
    int k = s->kk, n = s->n;
    /* the weighted norms of ee, ee + phi[k] and ee + phi[k] + phi[k-1] in one pass */
    double q[3] = {0, 0, 0};
    {
        const double *restrict e = s->ee, *restrict w = s->werr;
        const double *restrict pk = s->phi[k], *restrict pk1 = s->phi[k > 1 ? k - 1 : k];
        double q0 = 0, q1 = 0, q2 = 0;
        if (k > 2) {
            for (int i = 0; i < n; i++) {
                double a = e[i] * w[i], b = a + pk[i] * w[i], c = b + pk1[i] * w[i];
                q0 += a * a;
                q1 += b * b;
                q2 += c * c;
            }
        } else if (k == 2) {
            for (int i = 0; i < n; i++) {
                double a = e[i] * w[i], b = a + pk[i] * w[i];
                q0 += a * a;
                q1 += b * b;
            }
        } else {
            for (int i = 0; i < n; i++) {
                double a = e[i] * w[i];
                q0 += a * a;
            }
        }
        double nn = n > 0 ? n : 1;
        q[0] = sqrt(q0 / nn);
        q[1] = sqrt(q1 / nn);
        q[2] = sqrt(q2 / nn);
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

/* The smallest step t can take here: a few units of round-off of t. */
static double roundoff_h(const dae_solver *s)
{
    return 4 * DBL_EPSILON * fabs(s->tn);
}

/* phi after an accepted step of order k = kused: phi[k+1] = ee, phi[k] += ee, then phi[j] +=
 * phi[j+1] for j = k-1 .. 0, two levels per pass over the unknowns (the new phi[j+1] is added
 * to phi[j] while it is at hand). */
static void update_history(dae_solver *s)
{
    int n = s->n, k = s->kused;
    if (k < MAXORD) memcpy(s->phi[k + 1], s->ee, (size_t)n * sizeof(double));
    const double *restrict src = s->ee;
    int j = k;
    for (; j >= 1; j -= 2) { /* phi[j] += src; phi[j-1] += phi[j] */
        double *restrict a = s->phi[j], *restrict b = s->phi[j - 1];
        for (int i = 0; i < n; i++) {
            double c = a[i] + src[i];
            a[i] = c;
            b[i] += c;
        }
        src = s->phi[j - 1];
    }
    if (j == 0) vadd(n, s->phi[0], s->phi[1]);
}

static void complete_step(dae_solver *s)
{
    s->st.steps++;
    s->nst_local++;
    s->nautorestart = 0;
    s->ncrawl = fabs(s->hh) < CRAWL_FACTOR * roundoff_h(s) ? s->ncrawl + 1 : 0;
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
    if (s->knew == s->kk - 1 || s->kk == s->o.max_order) s->phase = 1;
    double hmax_inv = s->o.h_max > 0 ? 1.0 / s->o.h_max : 0.0;
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
            err_kp1 = wrms_diff(s, s->ee, s->phi[k + 1], s->werr) / (k + 2);
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
    update_history(s);
}

static void interpolate(const dae_solver *s, double t, double *y, double *yp);

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
    interpolate(s, t, y, yp);
    return BG_OK;
}

/* The history's interpolating polynomial at t (after a step: hused != 0), without the range
 * check of dae_dense. */
static void interpolate(const dae_solver *s, double t, double *y, double *yp)
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
        for (int i = 0; i < n; i++) {
            if (y) y[i] += c * s->phi[j][i];
            if (yp) yp[i] += d * s->phi[j][i];
        }
    }
}

/* -------------------------------------------------------------- stepping ---- */

/* Next time the step must land on (breakpoint or t_stop) beyond tn in direction dir, or NAN. */
static double next_stop(const dae_solver *s, double dir, int *is_bkpt)
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

static void clip_to_stop(dae_solver *s)
{
    int isb;
    double ts = next_stop(s, s->hh > 0 ? 1.0 : -1.0, &isb);
    if (!isnan(ts) && (s->tn + 1.0001 * s->hh - ts) * s->hh >= 0) s->hh = ts - s->tn;
    if (s->o.h_max > 0 && fabs(s->hh) > s->o.h_max) s->hh = copysign(s->o.h_max, s->hh);
}

/* Initial step and history from phi[0] = y, phi[1] = y' (unscaled). dir: the direction of
 * the integration, 0 to take it from tout (a restart keeps the direction it had, and tout may
 * then lie at tn). */
static int first_step(dae_solver *s, double tout, double hpref, double dir)
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
        double ts = next_stop(s, dir, &isb);
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
    clip_to_stop(s);
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

/* Describes an error-test failure by the unknown with the largest weighted local error. */
static void note_error_test(dae_solver *s, double t)
{
    char nb[32];
    int i = largest_weighted(s, s->ee, s->werr);
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
    int i = largest_weighted(s, first ? s->phi[1] : s->ee, s->werr);
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

/* Minimum-norm Gauss-Newton correction of y onto g(t, y) = 0 (at most 3 iterations). */
static int project_vec(dae_solver *s, double t, double *y)
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
static int project_step(dae_solver *s)
{
    int r = s->p.cons(s->p.user, s->tn, s->phi[0], s->gv, NULL);
    if (r != 0)
        return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, "dae_solve_to",
                              "constraint function returned %d at t = %g", r, s->tn);
    double g = 0;
    for (int i = 0; i < s->p.ncons; i++)
        g = fmax(g, fabs(s->gv[i]));
    s->st.max_drift = fmax(s->st.max_drift, g);
    return s->o.projection ? project_vec(s, s->tn, s->phi[0]) : BG_OK;
}

/* Restart at a breakpoint: left value of y, consistent right value of y', order 1. The first
 * step after a breakpoint is sized from y'' just before it (differenced from the interpolant over
 * the last half step): the local error of the order-1 restart is about h^2/2 |y''|, so
 * h = 0.5 sqrt(2 / |y''|) in the error norm, at most the last step. Far larger than IDA's
 * first-step rule, which would restart from h ~ 0.5/|y'| and double up again.
 * jump: a restart at an unannounced jump, made at tn + dt, past a jump that lies within a few
 * units of round-off of tn, with y carried there along y' (a change far below the tolerances).
 * The steps before it collapsed onto the jump, so neither the last step nor y'' from it says
 * anything about the step after: that one follows IDA's first-step rule on the new y' (y changes
 * by half a tolerance unit). Capped by the collapsed step instead, it fell below the step
 * floor at once on the IVP Test Set's pump with atol = 1e-2 rtol: every rtol from 1e-6 to 2e-8
 * stopped with DAE_STEP_TOO_SMALL at 119.9 to 890.1 ns. */
static int restart_at_breakpoint(dae_solver *s, double tout, double dt, int jump)
{
    double hprev = fabs(s->hused), hpref = hprev, dir = s->hused >= 0 ? 1.0 : -1.0;
    double hm = 0.5 * s->hused;
    dae_dense(s, s->tn, s->y, s->yp);
    if (!jump && dae_dense(s, s->tn - hm, NULL, s->tmp) == BG_OK) {
        for (int i = 0; i < s->n; i++)
            s->tmp[i] = (s->yp[i] - s->tmp[i]) / hm;
        s->hh = 0;
        daei_set_weights(s, s->y);
        double ypp = daei_wrms(s, s->tmp, s->werr);
        if (ypp > 0) hpref = fmin(hprev, 0.5 * sqrt(2.0 / ypp));
    }
    if (dt != 0) {
        for (int i = 0; i < s->n; i++)
            if (s->kind[i] == DAE_DIFF) s->y[i] += dt * s->yp[i];
        s->tn += dt;
    }
    memcpy(s->phi[0], s->y, (size_t)s->n * sizeof(double));
    memcpy(s->phi[1], s->yp, (size_t)s->n * sizeof(double));
    double keep = s->st.init_residual;
    s->init_side = s->hused >= 0 ? 1 : -1; /* the right-hand values past the breakpoint */
    int r = daei_consistent_init(s);
    s->init_side = 0;
    s->st.init_residual = keep;
    if (r != BG_OK) return r;
    if (jump) {
        double ypn = daei_wrms(s, s->phi[1], s->werr);
        if (ypn > 0) hpref = 0.5 / ypn;
    }
    s->first = 1;
    return first_step(s, tout, hpref, dir);
}

/* step_once's results besides a failure (< 0) */
enum { STEP_TAKEN = 0, STEP_ON_BREAKPOINT = 1, STEP_JUMP = 2 };

static int step_once(dae_solver *s)
{
    char nb[32];
    int nef = 0, ncf = 0, last_res_fail = 0;
    const char *w = "dae_solve_to";
    clip_to_stop(s);
    daei_set_weights(s, s->phi[0]);
    double tolsf = DBL_EPSILON * daei_wrms(s, s->phi[0], s->ewt);
    if (tolsf > 1) {
        int i = largest_weighted(s, s->phi[0], s->ewt);
        return bg_error_raise(&s->err, DAE_TOO_MUCH_ACC, w,
                              "at t = %.17g the tolerances are below round-off: increase them by "
                              "a factor of at least %.3g (the largest weighted value is %s = "
                              "%.3g against the tolerance %.3g)",
                              s->tn, tolsf, daei_vname(s, i, nb, sizeof nb),
                              i >= 0 ? s->phi[0][i] : 0.0, i >= 0 ? 1.0 / s->ewt[i] : 0.0);
    }
    s->note[0] = '\0';
    /* A crawl: CRAWL_STEPS accepted steps in a row, each within CRAWL_FACTOR of the round-off
     * limit of t, the steps in between failing (a switch in the model that no step crosses). It
     * would otherwise go on until max_steps or the caller's patience. */
    if (s->ncrawl >= CRAWL_STEPS)
        return bg_error_raise(&s->err, DAE_STEP_TOO_SMALL, w,
                              "the step size stayed below %g times the round-off limit of t for %d "
                              "steps at t = %.17g (h = %.3g, %ld Newton and %ld error-test "
                              "failures so far): the solution cannot pass this point (a switch or "
                              "a singularity of the model)%s%.200s",
                              CRAWL_FACTOR, CRAWL_STEPS, s->tn, s->hused, s->st.newton_fails,
                              s->st.rejected_error,
                              s->fail_note[0] ? "; the last Newton failure: " : "", s->fail_note);
    for (;;) {
        int isb;
        double ts = next_stop(s, s->hh > 0 ? 1 : -1, &isb);
        int landing = !isnan(ts) && s->tn + s->hh == ts;
        double hmin = fmax(s->o.h_min, roundoff_h(s));
        if (fabs(s->hh) < hmin && !landing && last_res_fail)
            return bg_error_raise(&s->err, DAE_RES_FAIL, w,
                                  "the residual (or Jacobian) kept failing until the step size "
                                  "fell to %.3g at t = %.17g: %s",
                                  s->hh, s->tn, s->note);
        /* The Newton iteration failed down to the smallest step with the error test never
         * failing: the signature of an input that jumps at tn (a source or a reference that
         * is not given as a breakpoint), which leaves the algebraic unknowns and y' of the
         * history inconsistent on the far side. The same when the last Newton failure ended
         * within JUMP_WINDOW round-off steps of tn: the accepted steps closed in on a point
         * that no step crosses, each step halfway there, until the error test failed on
         * round-off (pump, where a transistor switches off and its charge stops depending on
         * the voltages: stopped at 1079.9 ns at rtol 1e-10 and 2.8e-11 before). Restart once,
         * as at a breakpoint, at the end of the last failed step (past the jump, a few units of
         * round-off further on): right-hand consistent values, order 1. The step collapsing
         * again, with no step accepted since, stops the run. */
        if (fabs(s->hh) < hmin && !landing && s->hused != 0 &&
            s->nautorestart < MAX_AUTO_RESTARTS &&
            ((ncf > 0 && nef == 0) || fabs(s->t_fail - s->tn) <= JUMP_WINDOW * roundoff_h(s)))
            return STEP_JUMP;
        if (fabs(s->hh) < hmin && !landing) {
            if (nef + ncf == 0) note_step_limit(s);
            return bg_error_raise(&s->err, DAE_STEP_TOO_SMALL, w,
                                  "step size %.3g at t = %.17g is below the minimum %.3g (%d "
                                  "error-test and %d Newton failures in this step)%s%s",
                                  s->hh, s->tn, hmin, nef, ncf, s->note[0] ? ": " : "", s->note);
        }
        /* the weights change with h only through the index-2 unknowns' scaling by |h| */
        if (s->has_alg2 && (s->o.index2 == DAE_I2_SCALE_H || s->o.newton_index2_scale_h))
            daei_set_weights(s, s->phi[0]);
        set_coeffs(s);
        predict(s);
        double tnew = landing ? ts : s->tn + s->hh;
        /* a step that lands on a breakpoint sees the inputs' left-hand values there (one unit of
         * round-off short), whichever side the model gives the jump to: the restart takes the
         * right-hand ones */
        int nl = newton(s, landing && isb ? nextafter(ts, s->tn) : tnew);
        if (nl < 0) {
            restore(s);
            return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, w,
                                  "a callback returned the fatal status %d in the step from t = "
                                  "%.17g to %.17g: %s",
                                  nl, s->tn, tnew, s->note);
        }
        if (nl == NL_LSFAIL) {
            restore(s);
            return bg_error_raise(&s->err, DAE_LSETUP_FAIL, w, "at t = %.17g, h = %.3g: %s", s->tn,
                                  s->hh, s->note);
        }
        if (nl == NL_OK) {
            if (s->o.fixed_step || !test_error(s)) {
                complete_step(s);
                s->tn = tnew;
                return landing && isb ? STEP_ON_BREAKPOINT : STEP_TAKEN;
            }
            note_error_test(s, tnew);
            restore(s);
            s->st.rejected_error++;
            s->since_fail = -1;
            nef++;
            s->phase = 1;
            last_res_fail = 0;
            if (nef >= MAX_NEF)
                return bg_error_raise(&s->err, DAE_ERR_FAIL, w,
                                      "error test failed %d times at t = %.17g, h = %.3g: %s", nef,
                                      s->tn, s->hh, s->note);
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
            continue;
        }
        restore(s);
        s->phase = 1;
        if (nl == NL_RECOVER && !s->jac_current) { /* stale Jacobian: refresh, same step */
            s->need_setup = 1;
            continue;
        }
        ncf++;
        s->st.newton_fails++;
        s->t_fail = tnew;
        snprintf(s->fail_note, sizeof s->fail_note, "%s", s->note);
        last_res_fail = nl == NL_RES_RECOVER;
        if (ncf >= MAX_NCF) {
            if (nl == NL_SINGULAR)
                return bg_error_raise(&s->err, DAE_LSETUP_FAIL, w,
                                      "Newton matrix singular %d times at t = %.17g, h = %.3g: %s",
                                      ncf, s->tn, s->hh, s->note);
            if (last_res_fail)
                return bg_error_raise(
                    &s->err, DAE_RES_FAIL, w,
                    "the residual (or Jacobian) failed %d times at t = %.17g, h = "
                    "%.3g: %s",
                    ncf, s->tn, s->hh, s->note);
            return bg_error_raise(&s->err, DAE_CONV_FAIL, w,
                                  "Newton iteration failed %d times at t = %.17g, h = %.3g: %s",
                                  ncf, s->tn, s->hh, s->note);
        }
        s->hh *= 0.25;
        s->need_setup = 1;
    }
}

/* Interpolated output; with projection on, interpolated values are projected as well. */
static void output_state(dae_solver *s, double t, double *tret, double *y, double *yp)
{
    *tret = t;
    if (dae_dense(s, t, y, yp) != BG_OK) {
        if (y) memcpy(y, s->phi[0], (size_t)s->n * sizeof *y);
        if (yp) dae_dense(s, s->tn, NULL, yp);
        *tret = s->tn;
    } else if (y && s->o.projection && t != s->tn) {
        project_vec(s, t, y); /* a failure leaves the interpolated value and the message */
    }
}

/* Illinois search for the earliest sign change of the event functions in (tlo, tn]. */
static int find_root(dae_solver *s)
{
    int nr = s->p.nroots, r;
    dae_dense(s, s->tn, s->y, s->yp);
    if ((r = s->p.roots(s->p.user, s->tn, s->y, s->yp, s->ghi)) != 0)
        return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, "dae_solve_to",
                              "root function returned %d at t = %g", r, s->tn);
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
        if ((r = s->p.roots(s->p.user, tm, s->y, s->yp, gm)) != 0)
            return bg_error_raise(&s->err, DAE_CALLBACK_FAIL, "dae_solve_to",
                                  "root function returned %d at t = %g", r, tm);
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

static int advance_run(dae_solver *s, double tout, double *tret, double *y, double *yp, int one)
{
    const char *w = "dae_solve_to";
    if (!isfinite(tout))
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w, "tout = %g is not finite", tout);
    if (s->first) {
        if (tout == s->tn) {
            output_state(s, s->tn, tret, y, yp);
            return DAE_SUCCESS;
        }
        int r = first_step(s, tout, 0, 0);
        if (r != BG_OK) return r;
    }
    double dir = s->hh >= 0 ? 1.0 : -1.0;
    if (!one && (tout - (s->tn - s->hused)) * dir < 0 && !s->root_pending)
        return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w,
                              "tout = %g lies behind the last step [%g, %g]", tout,
                              s->tn - s->hused, s->tn);
    for (long nsteps = 0;; nsteps++) {
        if (s->root_pending && (s->troot - tout) * dir <= 0) {
            s->root_pending = 0;
            output_state(s, s->troot, tret, y, yp);
            return DAE_ROOT_RETURN;
        }
        if (!one && (s->tn - tout) * dir >= 0) {
            output_state(s, tout, tret, y, yp);
            return DAE_SUCCESS;
        }
        if (s->o.has_t_stop && s->tn == s->o.t_stop) {
            output_state(s, s->tn, tret, y, yp);
            return DAE_TSTOP_RETURN;
        }
        if (one && nsteps == 1) {
            output_state(s, s->tn, tret, y, yp);
            return DAE_SUCCESS;
        }
        if (nsteps >= s->o.max_steps) {
            output_state(s, s->tn, tret, y, yp);
            return bg_error_raise(&s->err, DAE_TOO_MUCH_WORK, w,
                                  "%ld steps taken before reaching tout = %g (t = %g)", nsteps,
                                  tout, s->tn);
        }
        if (s->restart_pending) {
            s->restart_pending = 0;
            int rr = restart_at_breakpoint(s, tout, 0, 0);
            if (rr != BG_OK) {
                output_state(s, s->tn, tret, y, yp);
                return rr;
            }
        }
        int r = step_once(s);
        daei_sync_stats(s);
        if (r < 0) {
            output_state(s, s->tn, tret, y, yp);
            return r;
        }
        if (r == STEP_JUMP) { /* an unannounced jump at tn: restart there (no step was taken) */
            char keep[sizeof s->note];
            snprintf(keep, sizeof keep, "%s", s->note);
            /* past the jump (the end of the last failed step), never behind tn (a stale
             * failure). A tout in (tn, tn + dt] gets the values before the restart, the history
             * extrapolated by less than dt: its left-hand values */
            double dt = (s->t_fail - s->tn) * dir > 0 ? s->t_fail - s->tn : 0.0;
            int out_here = !one && (s->tn + dt - tout) * dir >= 0;
            if (out_here) {
                interpolate(s, tout, y, yp);
                if (y && s->o.projection) project_vec(s, tout, y);
            }
            int rr = restart_at_breakpoint(s, tout, dt, 1);
            if (rr != BG_OK) {
                output_state(s, s->tn, tret, y, yp);
                char m[BG_MESSAGE_SIZE];
                snprintf(m, sizeof m, "%s", s->err.message);
                return bg_error_raise(&s->err, DAE_STEP_TOO_SMALL, w,
                                      "the step size collapsed at t = %.17g with the Newton "
                                      "iteration failing (%.200s), and a restart there with "
                                      "consistent values (as at a breakpoint) failed too: %.300s",
                                      s->tn, keep, m);
            }
            s->st.restarts++;
            s->st.t_last_restart = s->tn;
            s->nautorestart++;
            if (out_here) {
                *tret = tout;
                return DAE_SUCCESS;
            }
            nsteps--;
            continue;
        }
        if (s->p.cons && s->p.ncons > 0 && (r = project_step(s)) < 0) {
            output_state(s, s->tn, tret, y, yp);
            return r;
        }
        if (r == STEP_ON_BREAKPOINT) { /* landed on a breakpoint: restart before the next step
                         (which may be in the next call, when tout is the breakpoint itself) */
            s->ibk++;
            if (s->p.nroots > 0 && (r = find_root(s)) < 0) {
                output_state(s, s->tn, tret, y, yp);
                return r;
            }
            s->restart_pending = 1;
            continue;
        }
        if (s->p.nroots > 0 && (r = find_root(s)) < 0) {
            output_state(s, s->tn, tret, y, yp);
            return r;
        }
    }
}

/* advance_run behind the checks of the call order; a failure stops the integration until
 * dae_init or dae_reinit (DAE_TOO_MUCH_WORK and argument errors do not). */
static int advance(dae_solver *s, double tout, double *tret, double *y, double *yp, int one)
{
    const char *w = one ? "dae_step" : "dae_solve_to";
    if (!s) return BG_ERR_ARGUMENT;
    if (!tret) return bg_error_raise(&s->err, BG_ERR_ARGUMENT, w, "tret is NULL");
    if (!s->initialized)
        return bg_error_raise(&s->err, BG_ERR_STATE, w, "call dae_init before integrating");
    if (s->failed)
        return bg_error_raise(&s->err, BG_ERR_STATE, w,
                              "the integration stopped with %s at t = %.17g: call dae_reinit (or "
                              "dae_init) before integrating again",
                              dae_return_name(s->failed), s->tn);
    int r = advance_run(s, tout, tret, y, yp, one);
    if (r < 0 && r != DAE_TOO_MUCH_WORK && r != BG_ERR_ARGUMENT) s->failed = r;
    return r;
}

int dae_solve_to(dae_solver *s, double tout, double *tret, double *y, double *yp)
{
    return advance(s, tout, tret, y, yp, 0);
}

int dae_step(dae_solver *s, double tout, double *tret, double *y, double *yp)
{
    return advance(s, tout, tret, y, yp, 1);
}

int dae_roots_found(const dae_solver *s, int *found)
{
    if (!s || !found) return BG_ERR_ARGUMENT;
    for (int i = 0; i < s->p.nroots; i++)
        found[i] = s->rfound[i];
    return BG_OK;
}

/* ------------------------------------------------------------ statistics ---- */

/* The fields of dae_stats in the order of the line and CSV formats below. */
#define DAE_STATS_FIELDS(st)                                                                       \
    (st)->steps, (st)->rejected_error, (st)->newton_iters, (st)->newton_fails, (st)->res_evals,    \
        (st)->res_evals_fd, (st)->jac_evals, (st)->factor_symbolic, (st)->factor_full,             \
        (st)->factor_refactor, (st)->linear_solves, (st)->steps_at_order[1],                       \
        (st)->steps_at_order[2], (st)->steps_at_order[3], (st)->steps_at_order[4],                 \
        (st)->steps_at_order[5], (st)->steps ? (st)->h_min_used : 0.0, (st)->h_max_used,           \
        (st)->max_drift, (st)->init_residual, (st)->rcond_min, (st)->t_res, (st)->t_jac,           \
        (st)->t_linalg, (st)->restarts

int dae_stats_line(const dae_stats *st, char *buf, size_t size)
{
    if (!st || (!buf && size > 0)) return BG_ERR_ARGUMENT;
    return snprintf(
        buf, size,
        "steps=%ld rejected=%ld newton=%ld conv_fails=%ld res=%ld res_fd=%ld jac=%ld "
        "symbolic=%ld factor=%ld refactor=%ld solves=%ld orders=%ld/%ld/%ld/%ld/%ld "
        "h=[%.3g,%.3g] drift=%.3g init_res=%.3g rcond_min=%.3g t_res=%.3fs t_jac=%.3fs t_lin=%.3fs "
        "restarts=%ld",
        DAE_STATS_FIELDS(st));
}

int dae_stats_csv_header(char *buf, size_t size)
{
    if (!buf && size > 0) return BG_ERR_ARGUMENT;
    return snprintf(buf, size,
                    "steps,rejected,newton,conv_fails,res,res_fd,jac,symbolic,factor,refactor,"
                    "solves,order1,order2,order3,order4,order5,h_min,h_max,max_drift,"
                    "init_residual,rcond_min,t_res,t_jac,t_linalg,restarts");
}

int dae_stats_csv(const dae_stats *st, char *buf, size_t size)
{
    if (!st || (!buf && size > 0)) return BG_ERR_ARGUMENT;
    return snprintf(buf, size,
                    "%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%.6g,%.6g,"
                    "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld",
                    DAE_STATS_FIELDS(st));
}
