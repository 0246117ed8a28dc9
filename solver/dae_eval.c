/* The integrator's contact with the problem and with its user: the residual and Jacobian
 * callbacks (timing, counting, NaN and Inf detection, coloured finite differences where no
 * Jacobian is given), names of unknowns and equations for messages, and the statistics. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bg_dae_impl.h"

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

void daei_warn(dae_solver *s, const char *where, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    s->warn.handler = s->err.handler;
    s->warn.user = s->err.user;
    bg_error_vraise(&s->warn, DAE_WARNING, where, fmt, ap);
    va_end(ap);
    s->st.warnings++;
}

/* ---------------------------------------------------------------- callbacks ---- */

int daei_first_nonfinite(const double *v, int n)
{
    /* One branch-free pass, then the search only when something is not finite. With GCC, two
     * unknowns at a time as vectors (DAEI_VFOR): x - x is +0 (no bit set) for a finite x and
     * NaN for Inf or NaN, and the bits of all of them or-ed together are 0 or not. Then in
     * integers: Inf and NaN have all exponent bits set */
    const uint64_t expo = 0x7ff0000000000000u;
    uint64_t bad = 0;
    int i = 0;
#if defined(__GNUC__)
    daei_v2i acc = {0, 0}, acc2 = {0, 0}; /* two: one chain waits on the other domain's result */
    for (; i + 4 <= n; i += 4) {
        daei_v2 x = *(const daei_v2 *)&v[i], x2 = *(const daei_v2 *)&v[i + 2];
        acc |= (daei_v2i)(x - x);
        acc2 |= (daei_v2i)(x2 - x2);
    }
    acc |= acc2;
    bad = (acc[0] | acc[1]) != 0;
#endif
    for (; i < n; i++) {
        uint64_t b;
        memcpy(&b, &v[i], sizeof b);
        bad |= (b & expo) == expo;
    }
    if (!bad) return -1;
    for (i = 0; i < n; i++)
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
    int bad = daei_first_nonfinite(F, s->n);
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

/* options.check_jacobian: the analytic Jy, Jyp just evaluated against central differences of
 * the residual; a relative disagreement above 1e-3 (against |fd| + 1e-8 times the largest
 * entry) is a warning that names the worst entry, and the Newton rate that called for the
 * check when it was the automatic one (s->jac_suspect_rate > 0, dae_nls.c). */
static void check_jacobian(dae_solver *s, double t, const double *y, const double *yp)
{
    s->jac_checked = 1;
    s->fd_t = t;
    s->fd_y = y;
    s->fd_yp = yp;
    double worst = 0;
    sp_jac_entry we = {0};
    int wm = -1;
    for (int m = 0; m < 2; m++) {
        const sp_csc *J = m ? s->Jyp : s->Jy;
        double big = 0, err = 0;
        for (int p = 0; p < J->nnz; p++)
            big = fmax(big, fabs(J->val[p]));
        sp_jac_entry e;
        int r = sp_jac_check(J, m ? fd_res_yp : fd_res_y, s, s->n, m ? yp : y,
                             1e-8 * (big > 0 ? big : 1.0), 1e-3, &e, 1, &err);
        if (r > 0 && err > worst) {
            worst = err;
            we = e;
            wm = m;
        }
    }
    if (wm >= 0) {
        char eb[192], nb[32], tb[96];
        char why[160] = "";
        if (s->jac_suspect_rate > 0)
            snprintf(why, sizeof why,
                     "; checked because the Newton iteration contracted at the rate %.2g on a "
                     "Jacobian evaluated at its step (t = %.9g)",
                     s->jac_suspect_rate, s->jac_suspect_t);
        daei_warn(s, "dae_solve_to",
                  "the analytic Jacobian disagrees with central differences of the residual at %s: "
                  "d(%s)/d(%s%s) is %.6g, the differences give %.6g (relative error %.2g)%s",
                  daei_when(s, t, tb, sizeof tb), daei_ename(s, we.row, eb, sizeof eb),
                  daei_vname(s, we.col, nb, sizeof nb), wm ? "'" : "", we.analytic, we.fd, worst,
                  why);
    }
}

/* Jy, Jyp at (t, y, yp); F = F(t, y, yp) must be given (used by finite differences). */
int daei_eval_jac(dae_solver *s, double t, const double *y, const double *yp, const double *F)
{
    double t0 = daei_clock(s);
    int r;
    s->st.jac_evals++;
    s->reg_failed = 0;
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
    if (r == 0 && s->p.jac && !s->jac_checked &&
        (s->o.check_jacobian > 0 || (s->o.check_jacobian == 0 && s->jac_suspect_rate > 0)))
        check_jacobian(s, t, y, yp);
    if (r == 0) {
        for (int m = 0; m < 2 && r == 0; m++) {
            const sp_csc *J = m ? s->Jyp : s->Jy;
            int p = daei_first_nonfinite(J->val, J->nnz);
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
    if (r == 0 && s->p.nregimes > 0) { /* the regimes this Jacobian belongs to (dae_nls.c) */
        s->reg_valid = 0;
        r = daei_call_regimes(s, t, y, s->reg_jac);
        s->reg_valid = r == 0;
    }
    return r;
}

int daei_call_regimes(dae_solver *s, double t, const double *y, int *reg)
{
    s->reg_failed = 0;
    int r = s->p.regimes(s->p.user, t, y, reg);
    if (r == 0) return 0;
    /* > 0 is fatal too: the regimes are a classification of a state the residual accepts (the
     * predictor, a converged iterate, the point of a Jacobian), which a smaller step cannot
     * make succeed */
    s->reg_failed = 1;
    char tb[96];
    daei_note(s,
              "the regimes callback (dae_problem.regimes) returned %d at %s (0 is success, "
              "any other status is fatal%s)",
              r, daei_when(s, t, tb, sizeof tb), r > 0 ? ": reported as BG_ERR_CALLBACK" : "");
    return r < 0 ? r : BG_ERR_CALLBACK;
}

/* ------------------------------------------------------------- statistics ---- */

void daei_sync_stats(dae_solver *s)
{
    ls_solver *all[3] = {s->ls, s->kls, s->kktls};
    s->st.factor_symbolic = s->fact_off[0];
    s->st.factor_full = s->fact_off[1];
    s->st.factor_refactor = s->fact_off[2];
    for (int k = 0; k < 3; k++) {
        if (!all[k]) continue;
        const ls_stats *a = ls_get_stats(all[k]);
        s->st.factor_symbolic += a->symbolic;
        s->st.factor_full += a->factor;
        s->st.factor_refactor += a->refactor;
    }
}

int daei_largest_weighted(const dae_solver *s, const double *v, const double *w)
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

/* ------------------------------------------------------------- statistics ---- */

/* The fields of dae_stats in the order of the CSV format below (MEBDF's orders 6, 7 last, so
 * that the earlier columns keep their places). */
#define DAE_STATS_FIELDS(st)                                                                       \
    (st)->steps, (st)->rejected_error, (st)->newton_iters, (st)->newton_fails, (st)->res_evals,    \
        (st)->res_evals_fd, (st)->jac_evals, (st)->factor_symbolic, (st)->factor_full,             \
        (st)->factor_refactor, (st)->linear_solves, (st)->steps_at_order[1],                       \
        (st)->steps_at_order[2], (st)->steps_at_order[3], (st)->steps_at_order[4],                 \
        (st)->steps_at_order[5], (st)->steps ? (st)->h_min_used : 0.0, (st)->h_max_used,           \
        (st)->max_drift, (st)->init_residual, (st)->rcond_min, (st)->t_res, (st)->t_jac,           \
        (st)->t_linalg, (st)->restarts, (st)->newton_fails_stale, (st)->stab_lowered,              \
        (st)->steps_at_order[6], (st)->steps_at_order[7]

int dae_stats_line(const dae_stats *st, char *buf, size_t size)
{
    if (!st || (!buf && size > 0)) return BG_ERR_ARGUMENT;
    /* the orders 1 .. 5 always, then up to the highest one used (MEBDF's k = 6, 7), so that the
     * steps at the orders add up to the steps (with those at k = 0 of a run that took none) */
    char ord[160];
    int kmax = 5, nk = (int)(sizeof st->steps_at_order / sizeof *st->steps_at_order);
    for (int k = 6; k < nk; k++)
        if (st->steps_at_order[k]) kmax = k;
    size_t len = 0;
    for (int k = 1; k <= kmax && len < sizeof ord; k++)
        len += (size_t)snprintf(ord + len, sizeof ord - len, "%s%ld", k > 1 ? "/" : "",
                                st->steps_at_order[k]);
    return snprintf(
        buf, size,
        "steps=%ld rejected=%ld newton=%ld conv_fails=%ld res=%ld res_fd=%ld jac=%ld "
        "symbolic=%ld factor=%ld refactor=%ld solves=%ld orders=%s "
        "h=[%.3g,%.3g] drift=%.3g init_res=%.3g rcond_min=%.3g t_res=%.3fs t_jac=%.3fs t_lin=%.3fs "
        "restarts=%ld stale_fails=%ld stab_lowered=%ld",
        st->steps, st->rejected_error, st->newton_iters, st->newton_fails, st->res_evals,
        st->res_evals_fd, st->jac_evals, st->factor_symbolic, st->factor_full, st->factor_refactor,
        st->linear_solves, ord, st->steps ? st->h_min_used : 0.0, st->h_max_used, st->max_drift,
        st->init_residual, st->rcond_min, st->t_res, st->t_jac, st->t_linalg, st->restarts,
        st->newton_fails_stale, st->stab_lowered);
}

int dae_stats_csv_header(char *buf, size_t size)
{
    if (!buf && size > 0) return BG_ERR_ARGUMENT;
    return snprintf(buf, size,
                    "steps,rejected,newton,conv_fails,res,res_fd,jac,symbolic,factor,refactor,"
                    "solves,order1,order2,order3,order4,order5,h_min,h_max,max_drift,"
                    "init_residual,rcond_min,t_res,t_jac,t_linalg,restarts,stale_fails,"
                    "stab_lowered,order6,order7");
}

int dae_stats_csv(const dae_stats *st, char *buf, size_t size)
{
    if (!st || (!buf && size > 0)) return BG_ERR_ARGUMENT;
    return snprintf(buf, size,
                    "%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%.6g,%.6g,"
                    "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%ld,%ld,%ld,%ld",
                    DAE_STATS_FIELDS(st));
}

const char *dae_return_name(int code)
{
    return bg_status_name(code);
}

/* The shortest of %.15g .. %.17g that reads back as t. */
static void fmt_time(double t, char *buf, size_t sz)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, sz, "%.*g", prec, t);
        if (strtod(buf, NULL) == t) return;
    }
}

const char *daei_when(const dae_solver *s, double t, char *buf, size_t sz)
{
    char a[32];
    double t0 = s->tn;
    fmt_time(t0, a, sizeof a);
    if (t == t0)
        snprintf(buf, sz, "t = %s", a);
    else if (t == nextafter(t0, INFINITY))
        snprintf(buf, sz, "t = %s (just after)", a);
    else if (t == nextafter(t0, -INFINITY))
        snprintf(buf, sz, "t = %s (just before)", a);
    else
        snprintf(buf, sz, "t = %s %c %.3g", a, t > t0 ? '+' : '-', fabs(t - t0));
    return buf;
}
