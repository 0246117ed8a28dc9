/* The solver's newer entry points and options under bad input and misuse: the options of the
 * static solver and of the modal analysis (every field NaN, infinite, 0, negative, huge,
 * denormal), the nominal magnitudes, the regimes callback, the stability guard, the Newton
 * matrix options, the Jacobian check, index reduction, breakpoints and event functions, and
 * calls in the wrong order. Each case expects the documented status and a message naming the
 * field or unknown and its value; none may crash, hang, print or abort (the suite runs under
 * the sanitizers in CI).
 *
 * The problem is a damped spring-mass with a constant load f,
 *   x' = v,   v' = -k x - c v + f,   k = 4, c = 0.4, f = 1,
 * at rest at x = f / k = 0.25, with the modes s = -c/2 +- i sqrt(k - c^2/4) (closed forms the
 * runs that are valid are checked against). */
#include <float.h>
#include <stddef.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_modes.h"
#include "bg_sparse.h"
#include "bg_static.h"
#include "tap.h"

#define K 4.0
#define C 0.4
#define FLOAD 1.0

static const char *const names[2] = {"spring.x", "mass.v"};

typedef struct user {
    int regime_status; /* what the regimes callback returns */
    int res_nan_after; /* > 0: the residual is NaN from this call on */
    int calls;
    int root_mode; /* 0: g = x - 0.1; 1: NaN from t = 0.05 on; 2: status 1; 3: status -1 from
                      t = 0.05 on */
} user;

static int res(void *up, double t, const double *y, const double *yp, double *F)
{
    (void)t;
    user *u = up;
    F[0] = yp[0] - y[1];
    F[1] = yp[1] + K * y[0] + C * y[1] - FLOAD;
    if (u && u->res_nan_after > 0 && ++u->calls >= u->res_nan_after) F[1] = NAN;
    return 0;
}

static int jac(void *up, double t, const double *y, const double *yp, sp_csc *Jy, sp_csc *Jyp)
{
    (void)up, (void)t, (void)y, (void)yp;
    /* Jy: (1,0) = K, (0,1) = -1, (1,1) = C; Jyp: identity */
    Jy->val[sp_csc_find(Jy, 1, 0)] = K;
    Jy->val[sp_csc_find(Jy, 0, 1)] = -1;
    Jy->val[sp_csc_find(Jy, 1, 1)] = C;
    Jyp->val[0] = Jyp->val[1] = 1;
    return 0;
}

static int regimes(void *up, double t, const double *y, int *r)
{
    (void)t;
    r[0] = y[0] > 0.25;
    return ((user *)up)->regime_status;
}

static int roots(void *up, double t, const double *y, const double *yp, double *g)
{
    (void)yp;
    int mode = up ? ((user *)up)->root_mode : 0;
    g[0] = mode == 1 && t >= 0.05 ? NAN : y[0] - 0.1;
    return mode == 2 ? 1 : mode == 3 && t >= 0.05 ? -1 : 0;
}

static sp_csc *Jy_pat, *Jyp_pat;

static void make_patterns(void)
{
    static const double jy[4] = {0, 1, 1, 1}, jyp[4] = {1, 0, 0, 1}; /* column-major */
    Jy_pat = sp_csc_from_dense(2, 2, jy, 0.0);
    Jyp_pat = sp_csc_from_dense(2, 2, jyp, 0.0);
    /* the (0,0) entry of jy is 0 but column 0 needs the (1,0) entry only */
}

static void problem(dae_problem *p, user *u)
{
    memset(p, 0, sizeof *p);
    p->n = 2;
    p->res = res;
    p->jac = jac;
    p->jac_y_pattern = Jy_pat;
    p->jac_yp_pattern = Jyp_pat;
    p->names = names;
    p->user = u;
}

static int has(const char *msg, const char *sub)
{
    return msg && sub && strstr(msg, sub) != NULL;
}

/* got == want and every key word in msg (subs NULL-terminated) */
static void expect(int got, int want, const char *msg, const char *what, const char *sub1,
                   const char *sub2)
{
    int ok = got == want && (!sub1 || has(msg, sub1)) && (!sub2 || has(msg, sub2));
    char d[900];
    snprintf(d, sizeof d, "%s: %s (got %s)%s%s%s%s%s", what, bg_status_name(want),
             dae_return_name(got), sub1 ? ", names \"" : "", sub1 ? sub1 : "",
             sub2 ? "\" and \"" : "", sub2 ? sub2 : "", sub1 ? "\"" : "");
    tap_ok(ok, "%s", d);
    if (!ok) tap_diag("message: \"%s\"", msg ? msg : "(null)");
}

/* ------------------------------------------------------------ dae_create ---- */

/* dae_create with options o: its status (BG_OK when created, then a run to t = 5 checked
 * against the closed-form rest state within 1e-3: the run's status) and message into msg. */
static int create_run(const dae_problem *p, const dae_options *o, char *msg, size_t size)
{
    bg_error e = {0};
    dae_solver *s = dae_create(p, o, &e);
    if (!s) {
        snprintf(msg, size, "%s", e.message);
        return e.status;
    }
    const double y0[2] = {0, 0}, yp0[2] = {0, FLOAD};
    double t = 0, y[2] = {0, 0};
    int r = dae_init(s, 0, y0, yp0);
    while (r >= 0 && t < 5 && (r = dae_solve_to(s, 5.0, &t, y, NULL)) >= 0)
        if (r == DAE_ROOT_RETURN || r == DAE_TSTOP_RETURN) r = 0;
    /* at t = 5 the transient has decayed to e^-1 of 0.25: x(5) from the closed form */
    double w = sqrt(K - C * C / 4),
           x5 = 0.25 - 0.25 * exp(-C / 2 * 5) * (cos(w * 5) + C / (2 * w) * sin(w * 5));
    snprintf(msg, size, "%s", r < 0 ? dae_get_error(s)->message : "");
    if (r >= 0 && !(fabs(y[0] - x5) <= 1e-3)) {
        snprintf(msg, size, "x(5) = %.9g, exact %.9g", y[0], x5);
        r = -9999;
    }
    dae_free(&s);
    return r;
}

static void test_create_options(void)
{
    user u = {0};
    dae_problem p;
    dae_options o;
    char m[BG_MESSAGE_SIZE];
    problem(&p, &u);

    /* stability_guard and check_jacobian are switches: 0/1 and -1/0/1 */
    const int guards[] = {-1, 2, INT_MIN};
    for (int k = 0; k < 3; k++) {
        dae_options_default(&o);
        o.stability_guard = guards[k];
        char w[64];
        snprintf(w, sizeof w, "stability_guard = %d", guards[k]);
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, w, "stability_guard", "0 or 1");
    }
    const int checks[] = {-2, 2, INT_MAX};
    for (int k = 0; k < 3; k++) {
        dae_options_default(&o);
        o.check_jacobian = checks[k];
        char w[64];
        snprintf(w, sizeof w, "check_jacobian = %d", checks[k]);
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, w, "check_jacobian",
               "-1, 0 or 1");
    }
    for (int k = -1; k <= 1; k++) {
        dae_options_default(&o);
        o.check_jacobian = k;
        o.stability_guard = k >= 0 ? k : 0;
        int r = create_run(&p, &o, m, sizeof m);
        tap_ok(r == 0, "check_jacobian = %d, stability_guard = %d: runs to the closed form (%s)", k,
               o.stability_guard, m);
    }

    /* newton_dgmax: [0, 1); a denormal is a valid (tiny) tolerance */
    const double dg[] = {NAN, INFINITY, -1, 1, -DBL_MIN};
    const char *dgn[] = {"NaN", "inf", "-1", "1", "-DBL_MIN"};
    for (int k = 0; k < 5; k++) {
        dae_options_default(&o);
        o.newton_dgmax = dg[k];
        char w[64];
        snprintf(w, sizeof w, "newton_dgmax = %s", dgn[k]);
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, w, "newton_dgmax", NULL);
    }
    dae_options_default(&o);
    o.newton_dgmax = 4.9e-324;
    o.newton_jac_age = INT_MAX;
    expect(create_run(&p, &o, m, sizeof m), 0, m,
           "newton_dgmax = 4.9e-324 with newton_jac_age = INT_MAX: runs", NULL, NULL);
    dae_options_default(&o);
    o.newton_jac_age = -1;
    o.newton_dgmax = 0.3;
    expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "newton_jac_age = -1",
           "newton_jac_age = -1", NULL);

    /* max_newton: huge is the default's "as many as wanted", not an overflow (2 max_newton) */
    dae_options_default(&o);
    o.max_newton = INT_MAX;
    expect(create_run(&p, &o, m, sizeof m), 0, m, "max_newton = INT_MAX: runs", NULL, NULL);

    /* nominal magnitudes: finite and > 0, and not so small that atol * nominal underflows */
    const double nom[] = {NAN, INFINITY, 0, -1, 4.9e-324};
    const char *nomn[] = {"nan", "inf", "is 0", "is -1", "e-324"};
    for (int k = 0; k < 5; k++) {
        double nv[2] = {1, nom[k]};
        dae_options_default(&o);
        p.nominal = nv;
        char w[64];
        snprintf(w, sizeof w, "nominal of mass.v = %s", nomn[k]);
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, w, "mass.v", nomn[k]);
        p.nominal = NULL;
    }
    {
        double nv[2] = {1e-300, 1e300};
        dae_options_default(&o);
        p.nominal = nv;
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m,
               "nominal 1e-300 (atol * nominal underflows to a subnormal)", "spring.x", "1e-300");
        p.nominal = NULL;
        /* a subnormal atol without nominals (the fuzzer's: the message read a NULL nominal) */
        dae_options_default(&o);
        o.atol = 1e-310;
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m,
               "atol = 1e-310 without nominals", "atol", "1e-310");
    }
    {
        double av[2] = {1e-8, 1e-310}, nv[2] = {NAN, 1};
        dae_options_default(&o);
        o.atol_vec = av;
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "atol_vec[1] = 1e-310",
               "atol_vec[1]", "mass.v");
        av[1] = 0;      /* rtol > 0: a relative tolerance alone */
        p.nominal = nv; /* not used with atol_vec (documented) */
        expect(create_run(&p, &o, m, sizeof m), 0, m,
               "atol_vec[1] = 0 with rtol, a NaN nominal beside atol_vec: runs", NULL, NULL);
        p.nominal = NULL;
    }

    /* breakpoints: sorted by dae_create; a time given twice is one breakpoint (before, the
     * second stopped the run: "tout = 5 is too close to t = 1 to choose a first step") */
    {
        const double bad[2] = {2.0, 1.0}, dup[3] = {1.0, 1.0, 0.0};
        dae_options_default(&o);
        o.breakpoints = bad;
        o.nbreakpoints = 2;
        expect(create_run(&p, &o, m, sizeof m), 0, m, "breakpoints 2, 1 (unsorted): runs", NULL,
               NULL);
        o.breakpoints = dup;
        o.nbreakpoints = 3;
        expect(create_run(&p, &o, m, sizeof m), 0, m,
               "breakpoints 1, 1, 0 (repeated, one at t0): runs", NULL, NULL);
        const double inf[1] = {INFINITY};
        o.breakpoints = inf;
        o.nbreakpoints = 1;
        expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "breakpoint inf",
               "breakpoint 0", "inf");
    }

    /* regimes, event functions: negative counts, and a count without its function */
    dae_options_default(&o);
    p.nregimes = -1;
    p.regimes = regimes;
    expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "nregimes = -1", "nregimes = -1",
           NULL);
    p.nregimes = 1;
    p.regimes = NULL;
    expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "nregimes = 1 without a function",
           "regimes NULL", NULL);
    p.nregimes = 0;
    p.nroots = 1;
    expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "nroots = 1 without a function",
           "no root function", NULL);
    p.roots = roots; /* x passes 0.1 on the way to 0.25: a root return, then on to t = 5 */
    expect(create_run(&p, &o, m, sizeof m), 0, m, "nroots = 1: runs through its root", NULL, NULL);
    /* an event function that fails: NaN values (before: no sign change seen, the root at
     * x = 0.1 silently missed), a status 1 at dae_init (before: accepted there, refused in
     * the search), -1 during the run; then stepping is refused until dae_reinit */
    const char *rm[] = {"", "NaN from t = 0.05", "status 1", "status -1 from t = 0.05"};
    const char *key[] = {"", "event function 0 is nan", "status 1", "status -1"};
    for (int mode = 1; mode <= 3; mode++) {
        u.root_mode = mode;
        bg_error e = {0};
        dae_solver *s = dae_create(&p, &o, &e);
        const double y0[2] = {0, 0}, yp0[2] = {0, FLOAD};
        double t = 0, y[2];
        int r = dae_init(s, 0, y0, yp0);
        while (r >= 0 && t < 5)
            r = dae_solve_to(s, 5.0, &t, y, NULL);
        char w[96];
        snprintf(w, sizeof w, "an event function with %s", rm[mode]);
        expect(r, DAE_CALLBACK_FAIL, dae_get_error(s)->message, w, key[mode], NULL);
        if (mode > 1) {
            dae_free(&s);
            continue;
        }
        double t2 = t;
        expect(dae_solve_to(s, 5.0, &t2, y, NULL), BG_ERR_STATE, dae_get_error(s)->message,
               "dae_solve_to after the event function failed", "dae_reinit", NULL);
        dae_free(&s);
    }
    u.root_mode = 0;
    p.nroots = 0;
    p.roots = NULL;

    /* index reduction of a problem without constraints: refused, saying why */
    dae_options_default(&o);
    o.index2 = DAE_I2_REDUCE;
    expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m,
           "index2 = DAE_I2_REDUCE without constraints", "DAE_I2_REDUCE", "index 1");
    o.index2 = (dae_index2_policy)3;
    expect(create_run(&p, &o, m, sizeof m), BG_ERR_ARGUMENT, m, "index2 = 3", "index2 = 3", NULL);
}

/* ------------------------------------------------- callbacks and call order ---- */

static void test_regimes_calls(void)
{
    user u = {0};
    dae_problem p;
    dae_options o;
    char m[BG_MESSAGE_SIZE];
    problem(&p, &u);
    p.nregimes = 1;
    p.regimes = regimes;
    dae_options_default(&o);
    expect(create_run(&p, &o, m, sizeof m), 0, m, "regimes returning 0: runs", NULL, NULL);
    const int st[] = {-1, 1, INT_MIN};
    for (int k = 0; k < 3; k++) {
        u.regime_status = st[k];
        char w[64];
        snprintf(w, sizeof w, "regimes returning %d", st[k]);
        expect(create_run(&p, &o, m, sizeof m), DAE_CALLBACK_FAIL, m, w, "regimes", NULL);
    }
    u.regime_status = 0;

    /* a residual that turns NaN after the start: a failure naming the equation, the results
     * so far kept */
    p.nregimes = 0;
    p.regimes = NULL;
    u.res_nan_after = 40;
    u.calls = 0;
    bg_error e = {0};
    dae_solver *s = dae_create(&p, &o, &e);
    const double y0[2] = {0, 0}, yp0[2] = {0, FLOAD};
    double t = 0, y[2];
    int r = s ? dae_init(s, 0, y0, yp0) : e.status;
    while (r == 0 && t < 5)
        r = dae_solve_to(s, 5.0, &t, y, NULL);
    tap_ok(r < 0 && t > 0 && t < 5 && isfinite(y[0]) && has(dae_get_error(s)->message, "mass.v"),
           "a residual NaN from its 40th call: %s at t = %g with the state kept (x = %g): %s",
           dae_return_name(r), t, y[0], s ? dae_get_error(s)->message : e.message);
    /* after the failure: stepping refused until dae_reinit */
    double t2 = t;
    int r2 = dae_solve_to(s, 5.0, &t2, y, NULL);
    expect(r2, BG_ERR_STATE, dae_get_error(s)->message, "dae_solve_to after a failure",
           "dae_reinit", NULL);
    int r3 = dae_consistent_init(s);
    expect(r3, BG_ERR_STATE, dae_get_error(s)->message, "dae_consistent_init after stepping", NULL,
           NULL);
    dae_free(&s);
    tap_ok(s == NULL, "dae_free sets the handle to NULL");
    expect(dae_solve_to(s, 1.0, &t, y, NULL), BG_ERR_ARGUMENT, NULL, "dae_solve_to after dae_free",
           NULL, NULL);
    expect(dae_consistent_init(s), BG_ERR_ARGUMENT, NULL, "dae_consistent_init after dae_free",
           NULL, NULL);
    tap_ok(dae_get_consistent(NULL, y, y) == BG_ERR_ARGUMENT && !dae_get_warning(NULL) &&
               !dae_get_stats(NULL) && !dae_get_error(NULL),
           "the queries of a NULL solver are refused");
    u.res_nan_after = 0;
}

/* ------------------------------------------------------------- static ---- */

typedef struct sfield {
    const char *name;
    size_t off;
    int is_int;
} sfield;

#define SD(f)                                                                                      \
    {                                                                                              \
#f, offsetof(dae_static_options, f), 0                                                     \
    }
#define SI(f)                                                                                      \
    {                                                                                              \
#f, offsetof(dae_static_options, f), 1                                                     \
    }

static int load_status;
static int load_fn(void *up, double lambda)
{
    (void)up, (void)lambda;
    return load_status;
}

static void test_static(void)
{
    user u = {0};
    dae_problem p;
    problem(&p, &u);
    bg_error err = {0};
    dae_static_options so;
    dae_static_result r;
    double y[2], yp[2];

    /* the valid run first: x = f / k */
    dae_static_options_default(&so);
    y[0] = y[1] = 0;
    int rc = dae_static_solve(&p, &so, 0, y, yp, &r, &err);
    tap_ok(rc == BG_OK && fabs(y[0] - FLOAD / K) <= 1e-7 && fabs(y[1]) <= 1e-7,
           "static: the spring rests at f/k = 0.25 (x = %.10g, %s)", y[0], err.message);

    const sfield fields[] = {SD(rtol),        SD(atol), SI(max_newton), SD(dlambda),
                             SD(dlambda_min), SD(h0),   SD(h_max)};
    const double bad[] = {NAN, INFINITY, -1, 0, 4.9e-324, 1e300};
    const char *badn[] = {"NaN", "inf", "-1", "0", "4.9e-324", "1e300"};
    for (size_t f = 0; f < sizeof fields / sizeof *fields; f++)
        for (int k = 0; k < 6; k++) {
            dae_static_options_default(&so);
            char *base = (char *)&so + fields[f].off;
            int valid; /* the documented ranges */
            const char *fn = fields[f].name;
            double v = bad[k];
            if (fields[f].is_int) {
                if (isnan(v) || isinf(v) || v == 4.9e-324) continue;
                *(int *)base = v > INT_MAX ? INT_MAX : (int)v;
                valid = *(int *)base >= 1 && *(int *)base <= 10000; /* max_newton's range */
            } else {
                *(double *)base = v;
                valid = isfinite(v) && v > 0;
                if (!strcmp(fn, "rtol")) valid = isfinite(v) && v >= 0 && v < 1;
                if (!strcmp(fn, "atol")) valid = isfinite(v) && v >= 0;
                if (!strcmp(fn, "dlambda") || !strcmp(fn, "dlambda_min"))
                    valid = valid && v <= 1 && v >= (!strcmp(fn, "dlambda") ? so.dlambda_min : 0);
                if (!strcmp(fn, "h0")) valid = valid && v <= so.h_max;
                if (!strcmp(fn, "h_max")) valid = valid && v >= so.h0;
            }
            y[0] = y[1] = 0;
            memset(&err, 0, sizeof err);
            rc = dae_static_solve(&p, &so, 0, y, yp, &r, &err);
            char w[96];
            snprintf(w, sizeof w, "static: %s = %s", fn, badn[k]);
            if (valid) {
                /* a valid value: the equilibrium, or a failure that says why; never a wrong
                 * equilibrium with BG_OK */
                int good = rc == BG_OK ? fabs(y[0] - FLOAD / K) <= 1e-4 : err.message[0] != 0;
                tap_ok(good, "%s (valid): %s, x = %.6g %s", w, bg_status_name(rc), y[0],
                       err.message);
            } else {
                expect(rc, BG_ERR_ARGUMENT, err.message, w, fn, NULL);
            }
        }
    dae_static_options_default(&so);
    so.continuation = 2;
    y[0] = y[1] = 0;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: continuation = 2", "continuation", NULL);
    dae_static_options_default(&so);
    so.max_steps = 0;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: max_steps = 0", "max_steps", NULL);
    dae_static_options_default(&so);
    so.linsol = (ls_kind)7;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: linsol = 7", "linsol", NULL);
    dae_static_options_default(&so);
    double ys[2] = {0, NAN};
    so.yp_steady = ys;
    y[0] = y[1] = 0;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: yp_steady NaN", "mass.v", "nan");
    dae_static_options_default(&so);
    expect(dae_static_solve(&p, &so, INFINITY, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: t = inf", "t", NULL);
    /* the model's load callback failing */
    const int ls[] = {-1, 1};
    for (int k = 0; k < 2; k++) {
        dae_static_options_default(&so);
        so.load = load_fn;
        load_status = ls[k];
        y[0] = y[1] = 0;
        memset(&err, 0, sizeof err);
        rc = dae_static_solve(&p, &so, 0, y, yp, &r, &err);
        char w[64];
        snprintf(w, sizeof w, "static: the load callback returning %d", ls[k]);
        /* the callback's status other than 0 is a failure (as a regimes callback's) */
        expect(rc, BG_ERR_CALLBACK, err.message, w, "load", NULL);
    }
    /* a residual NaN at the start: named, not BG_OK */
    u.res_nan_after = 1;
    u.calls = 0;
    dae_static_options_default(&so);
    y[0] = y[1] = 0;
    memset(&err, 0, sizeof err);
    rc = dae_static_solve(&p, &so, 0, y, yp, &r, &err);
    /* named by the unknown whose rate it holds ("equation 1 (with the rate of mass.v)") */
    expect(rc, BG_ERR_NONFINITE, err.message,
           "static: a residual NaN at the start names the equation", "mass.v", NULL);
    u.res_nan_after = 0;
    /* n = 0, a residual missing */
    p.n = 0;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: n = 0", "n", NULL);
    p.n = 2;
    p.res = NULL;
    expect(dae_static_solve(&p, &so, 0, y, yp, &r, &err), BG_ERR_ARGUMENT, err.message,
           "static: no residual", "resid", NULL);
}

/* -------------------------------------------------------------- modes ---- */

static void test_modes(void)
{
    user u = {0};
    dae_problem p;
    problem(&p, &u);
    bg_error err = {0};
    dae_modes *M = NULL;
    double y[2] = {0.25, 0};
    int rc = dae_modes_compute(&p, 0, y, NULL, NULL, &M, &err);
    const dae_mode *md = dae_modes_get(M, 0);
    double w = sqrt(K - C * C / 4);
    tap_ok(rc == BG_OK && md && fabs(md->re + C / 2) <= 1e-9 && fabs(md->im - w) <= 1e-9,
           "modes: s = %.10g + %.10g i, exact %.10g + %.10g i (%s)", md ? md->re : NAN,
           md ? md->im : NAN, -C / 2, w, err.message);
    dae_modes_free(&M);

    dae_modes_options mo;
    struct {
        const char *name;
        double v;
        int is_int;
        size_t off;
    } cases[] = {
        {"sigma", NAN, 0, offsetof(dae_modes_options, sigma)},
        {"sigma", INFINITY, 0, offsetof(dae_modes_options, sigma)},
        {"tol", NAN, 0, offsetof(dae_modes_options, tol)},
        {"tol", -1, 0, offsetof(dae_modes_options, tol)},
        {"zero_tol", NAN, 0, offsetof(dae_modes_options, zero_tol)},
        {"zero_tol", -1, 0, offsetof(dae_modes_options, zero_tol)},
        {"inf_tol", NAN, 0, offsetof(dae_modes_options, inf_tol)},
        {"inf_tol", -1, 0, offsetof(dae_modes_options, inf_tol)},
        {"inf_tol", INFINITY, 0, offsetof(dae_modes_options, inf_tol)},
        {"zero_tol", INFINITY, 0, offsetof(dae_modes_options, zero_tol)},
        {"tol", INFINITY, 0, offsetof(dae_modes_options, tol)},
        {"nev", -1, 1, offsetof(dae_modes_options, nev)},
        {"ncv", -5, 1, offsetof(dae_modes_options, ncv)},
        {"maxiter", -1, 1, offsetof(dae_modes_options, maxiter)},
        {"dense_max", 0, 1, offsetof(dae_modes_options, dense_max)},
        {"method", 99, 1, offsetof(dae_modes_options, method)},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        dae_modes_options_default(&mo);
        char *base = (char *)&mo + cases[k].off;
        if (cases[k].is_int)
            *(int *)base = (int)cases[k].v;
        else
            *(double *)base = cases[k].v;
        memset(&err, 0, sizeof err);
        rc = dae_modes_compute(&p, 0, y, NULL, &mo, &M, &err);
        char wd[64];
        snprintf(wd, sizeof wd, "modes: %s = %g", cases[k].name, cases[k].v);
        /* infinite tolerances refused too (zero_tol = inf would call every mode rigid,
         * inf_tol = inf every one a constraint) */
        expect(rc, BG_ERR_ARGUMENT, err.message, wd, cases[k].name, NULL);
        dae_modes_free(&M);
    }
    /* a NaN rate (yp), t not finite, the nominals */
    double ypb[2] = {0, NAN};
    memset(&err, 0, sizeof err);
    rc = dae_modes_compute(&p, 0, y, ypb, NULL, &M, &err);
    expect(rc, BG_ERR_NONFINITE, err.message, "modes: yp NaN", "mass.v", NULL);
    dae_modes_free(&M);
    memset(&err, 0, sizeof err);
    rc = dae_modes_compute(&p, NAN, y, NULL, NULL, &M, &err);
    expect(rc, BG_ERR_ARGUMENT, err.message, "modes: t NaN", "t", NULL);
    dae_modes_free(&M);
    double nv[2] = {1, 0};
    p.nominal = nv;
    memset(&err, 0, sizeof err);
    rc = dae_modes_compute(&p, 0, y, NULL, NULL, &M, &err);
    expect(rc, BG_ERR_ARGUMENT, err.message, "modes: nominal 0", "mass.v", NULL);
    dae_modes_free(&M);
    p.nominal = NULL;
    expect(dae_modes_compute(&p, 0, NULL, NULL, NULL, &M, &err), BG_ERR_ARGUMENT, err.message,
           "modes: y NULL", "y", NULL);
}

int main(void)
{
    make_patterns();
    test_create_options();
    test_regimes_calls();
    test_static();
    test_modes();
    sp_csc_free(&Jy_pat);
    sp_csc_free(&Jyp_pat);
    return tap_done();
}
