/* Consistent initial values (dae_consistent_init) against closed forms, with analytic and with
 * finite-difference Jacobians:
 *   - a pendulum in the stabilised index-2 form of Gear, Gupta and Leimkuhler (position and
 *     velocity constraints, two index-2 multipliers), whose consistent state at an angle theta
 *     and a rate omega is known in closed form: the values to the tolerance asked for (rtol =
 *     atol = 1e-10) with finite-difference Jacobians, from multipliers guessed 0; the hidden
 *     constraint evaluated independently at the values returned, against the residual the
 *     solver reports; an exactly consistent start returned unchanged; the derivative of the
 *     multiplier, lam' = -3 (g/L) omega sin(theta); a position guess on the far side, which
 *     the position constraint sends to the other half of the circle, warned of (DAE_WARNING,
 *     the unknowns named), a guess slightly off the circle not;
 *   - a manufactured problem with an index-1 unknown z and an index-2 unknown lam whose
 *     solution is known (x1 = sin t, x2 = cos 2t, z = sin^2 t + cos 3t, lam = e^t): z' and lam'
 *     at t0 = 0.3;
 *   - the IVP Test Set's slider crank (bench/problems_testset.c) started from its consistent values
 *     with its accelerations and multipliers set to 0: the consistent state found again, with
 *     no warning (0 stands for "not known");
 *   - an input that jumps at t0: the unknown it moves is not warned about;
 *   - messages: a residual that fails at t0 = 0 is reported at "t = 0 (just after)", not at
 *     the evaluation time 4.94e-324. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg_dae.h"
#include "bg_sparse.h"
#include "problems.h"
#include "tap.h"

/* ---------------------------------------------------------------- pendulum ---- */

/* x' = u - mu x, y' = v - mu y, u' = -lam x, v' = -lam y - g, 0 = x^2 + y^2 - L^2,
 * 0 = x u + y v. Hidden constraints: mu = 0 and lam = (u^2 + v^2 - g y) / L^2. */
enum { PX, PY, PU, PV, PLAM, PMU, PN };
static const double PL = 2.0, PG = 9.81;

static int pend_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[PX] - y[PU] + y[PMU] * y[PX];
    F[1] = yp[PY] - y[PV] + y[PMU] * y[PY];
    F[2] = yp[PU] + y[PLAM] * y[PX];
    F[3] = yp[PV] + y[PLAM] * y[PY] + PG;
    F[4] = y[PX] * y[PX] + y[PY] * y[PY] - PL * PL;
    F[5] = y[PX] * y[PU] + y[PY] * y[PV];
    return 0;
}

static void set(sp_csc *A, int i, int j, double v)
{
    A->val[sp_csc_find(A, i, j)] = v;
}

static int pend_jac(void *user, double t, const double *y, const double *yp, sp_csc *Jy,
                    sp_csc *Jyp)
{
    (void)user, (void)t, (void)yp;
    sp_csc_zero(Jy);
    set(Jy, 0, PU, -1.0);
    set(Jy, 0, PMU, y[PX]);
    set(Jy, 0, PX, y[PMU]);
    set(Jy, 1, PV, -1.0);
    set(Jy, 1, PMU, y[PY]);
    set(Jy, 1, PY, y[PMU]);
    set(Jy, 2, PLAM, y[PX]);
    set(Jy, 2, PX, y[PLAM]);
    set(Jy, 3, PLAM, y[PY]);
    set(Jy, 3, PY, y[PLAM]);
    set(Jy, 4, PX, 2 * y[PX]);
    set(Jy, 4, PY, 2 * y[PY]);
    set(Jy, 5, PX, y[PU]);
    set(Jy, 5, PY, y[PV]);
    set(Jy, 5, PU, y[PX]);
    set(Jy, 5, PV, y[PY]);
    for (int p = 0; p < Jyp->nnz; p++)
        Jyp->val[p] = 1.0;
    return 0;
}

static const int pend_kind[PN] = {DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_DIFF, DAE_ALG2, DAE_ALG2};
static const char *const pend_names[PN] = {"x", "y", "u", "v", "lam", "mu"};

static void pend_patterns(sp_csc **jy, sp_csc **jyp)
{
    static const int ij[][2] = {{0, PU},   {0, PMU}, {0, PX},   {1, PV}, {1, PMU}, {1, PY},
                                {2, PLAM}, {2, PX},  {3, PLAM}, {3, PY}, {4, PX},  {4, PY},
                                {5, PX},   {5, PY},  {5, PU},   {5, PV}};
    sp_builder *by = sp_builder_create(PN, PN, 16), *byp = sp_builder_create(PN, PN, 4);
    for (size_t k = 0; k < sizeof ij / sizeof *ij; k++)
        sp_builder_add(by, ij[k][0], ij[k][1], 0.0);
    for (int i = 0; i < 4; i++)
        sp_builder_add(byp, i, i, 0.0);
    *jy = sp_builder_finish(by, NULL);
    *jyp = sp_builder_finish(byp, NULL);
    sp_builder_free(&by);
    sp_builder_free(&byp);
}

/* The consistent state at angle th (from the downward vertical) and rate om, and y' with
 * lam' = -3 (g/L) om sin(th), mu' = 0. */
static void pend_exact(double th, double om, double *y, double *yp)
{
    double lam = om * om + PG / PL * cos(th);
    y[PX] = PL * sin(th);
    y[PY] = -PL * cos(th);
    y[PU] = PL * om * cos(th);
    y[PV] = PL * om * sin(th);
    y[PLAM] = lam;
    y[PMU] = 0.0;
    yp[PX] = y[PU];
    yp[PY] = y[PV];
    yp[PU] = -lam * y[PX];
    yp[PV] = -lam * y[PY] - PG;
    yp[PLAM] = -3.0 * PG / PL * om * sin(th);
    yp[PMU] = 0.0;
}

typedef struct init_out {
    int rc;
    double y[PN], yp[PN];
    double init_residual, init_error;
    char msg[BG_MESSAGE_SIZE], warn[BG_MESSAGE_SIZE];
} init_out;

/* dae_consistent_init of the pendulum from (y0, yp0) (yp0 NULL: 0) at rtol = atol = tol. */
static init_out pend_init(int analytic, double tol, const double *y0, const double *yp0)
{
    init_out o = {0};
    sp_csc *jy, *jyp;
    pend_patterns(&jy, &jyp);
    dae_problem p = {0};
    p.n = PN;
    p.res = pend_res;
    p.jac = analytic ? pend_jac : NULL;
    p.jac_y_pattern = jy;
    p.jac_yp_pattern = jyp;
    p.kind = pend_kind;
    p.names = pend_names;
    dae_options opt;
    dae_options_default(&opt);
    opt.rtol = opt.atol = tol;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &opt, &err);
    o.rc = s ? dae_init(s, 0.0, y0, yp0) : err.status;
    if (o.rc == 0) o.rc = dae_consistent_init(s);
    if (s && o.rc >= 0) dae_get_consistent(s, o.y, o.yp);
    if (s) {
        o.init_residual = dae_get_stats(s)->init_residual;
        o.init_error = dae_get_stats(s)->init_error;
        snprintf(o.msg, sizeof o.msg, "%s", dae_get_error(s)->message);
        snprintf(o.warn, sizeof o.warn, "%s", dae_get_warning(s));
    } else {
        snprintf(o.msg, sizeof o.msg, "%s", err.message);
    }
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
    return o;
}

/* Largest |got - want| in tolerances rtol |want| + atol. */
static double tol_units(const double *got, const double *want, int n, double tol)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(got[i] - want[i]) / (tol * fabs(want[i]) + tol));
    return m;
}

/* The hidden constraint of the velocity row, d/dt (x u + y v) = x' u + x u' + y' v + y v', at
 * the values returned, in long double, scaled by the size of its terms as the solver scales
 * it (1 + sum of the terms' magnitudes). */
static double pend_hidden(const double *y, const double *yp)
{
    long double a = (long double)yp[PX] * y[PU], b = (long double)y[PX] * yp[PU];
    long double c = (long double)yp[PY] * y[PV], d = (long double)y[PY] * yp[PV];
    long double h = a + b + c + d;
    return (double)(fabsl(h) / (1 + fabsl(a) + fabsl(b) + fabsl(c) + fabsl(d)));
}

static void test_pendulum_fd(void)
{
    const double th = 0.7, om = 1.3, tol = 1e-10;
    double ye[PN], ype[PN], y0[PN];
    pend_exact(th, om, ye, ype);
    memcpy(y0, ye, sizeof y0);
    y0[PLAM] = y0[PMU] = 0.0; /* not known */
    init_out o = pend_init(0, tol, y0, NULL);
    tap_ok(o.rc == BG_OK && !o.warn[0],
           "pendulum, finite-difference Jacobians, multipliers guessed 0: BG_OK, no warning "
           "(%d %s %s)",
           o.rc, o.msg, o.warn);
    tap_ok(memcmp(o.y, ye, 4 * sizeof *ye) == 0,
           "pendulum, FD: positions and velocities (consistent) returned as given");
    double ua = tol_units(o.y + PLAM, ye + PLAM, 2, tol), up = tol_units(o.yp, ype, 4, tol);
    tap_diag("pendulum, FD: lam %.17g (exact %.17g), mu %.3g; y' within %.3g tolerances; "
             "init_residual %.3g, init_error %.3g",
             o.y[PLAM], ye[PLAM], o.y[PMU], up, o.init_residual, o.init_error);
    tap_ok(ua <= 1 && up <= 1,
           "pendulum, FD: lam, mu within %.3g and y' within %.3g tolerances (1e-10) of the "
           "closed form",
           ua, up);
    double hid = pend_hidden(o.y, o.yp);
    tap_ok(hid <= 1e-12,
           "pendulum, FD: the hidden constraint x'u + xu' + y'v + yv' holds to "
           "%.3g of its terms",
           hid);
    tap_ok(hid <= 10 * o.init_residual + 1e-14,
           "pendulum, FD: the residual reported (%.3g) is no less than a tenth of the hidden "
           "constraint's, evaluated apart (%.3g)",
           o.init_residual, hid);
    tap_ok(o.init_error <= 1, "pendulum, FD: init_error %.3g <= 1 (consistent to the tolerance)",
           o.init_error);
}

static void test_pendulum_exact_start(void)
{
    const double th = 0.7, om = 1.3, tol = 1e-10;
    double ye[PN], ype[PN];
    pend_exact(th, om, ye, ype);
    for (int analytic = 1; analytic >= 0; analytic--) {
        init_out o = pend_init(analytic, tol, ye, ype);
        int same_y = memcmp(o.y, ye, sizeof ye) == 0,
            same_yp = memcmp(o.yp, ype, 4 * sizeof *ype) == 0;
        double d = 0;
        for (int i = 0; i < PN; i++)
            d = fmax(d, fabs(o.y[i] - ye[i]));
        for (int i = 0; i < 4; i++)
            d = fmax(d, fabs(o.yp[i] - ype[i]));
        tap_ok(o.rc == BG_OK && same_y && same_yp,
               "pendulum, %s Jacobian, exactly consistent start: y and the differential y' "
               "returned unchanged (largest change %.3g, %s)",
               analytic ? "analytic" : "finite-difference", d, o.msg);
    }
}

static void test_pendulum_rates(void)
{
    const double th = 0.7, om = 1.3;
    double ye[PN], ype[PN];
    pend_exact(th, om, ye, ype);
    for (int analytic = 1; analytic >= 0; analytic--) {
        init_out o = pend_init(analytic, 1e-8, ye, NULL);
        tap_diag("pendulum, %s: lam' %.17g (exact %.17g), mu' %.3g", analytic ? "analytic" : "FD",
                 o.yp[PLAM], ype[PLAM], o.yp[PMU]);
        tap_ok(o.rc == BG_OK && fabs(o.yp[PLAM] - ype[PLAM]) <= 1e-6 * fabs(ype[PLAM]) &&
                   fabs(o.yp[PMU]) <= 1e-6 * fabs(ype[PLAM]),
               "pendulum, %s Jacobian: the index-2 rates lam' = -3 (g/L) omega sin(theta) = "
               "%.12g (got %.12g) and mu' = 0 (got %.3g), to 1e-6",
               analytic ? "analytic" : "finite-difference", ype[PLAM], o.yp[PLAM], o.yp[PMU]);
    }
}

static void test_pendulum_warning(void)
{
    const double th = 0.7, om = 0.0;
    double ye[PN], ype[PN], y0[PN];
    pend_exact(th, om, ye, ype);
    /* the pendulum hangs at (1.29, -1.53); a guess near the centre on the upper side: the
     * constraint x^2 + y^2 = L^2 takes it to the upper half of the circle */
    memcpy(y0, ye, sizeof y0);
    y0[PX] = 0.1;
    y0[PY] = 0.4;
    y0[PLAM] = y0[PMU] = 0.0;
    init_out o = pend_init(1, 1e-8, y0, NULL);
    tap_diag("pendulum from (0.1, 0.4): status %d, (%.6g, %.6g); %s", o.rc, o.y[PX], o.y[PY],
             o.warn);
    tap_ok(o.rc == DAE_WARNING && strstr(o.warn, "ended far from the values given") &&
               strstr(o.warn, "y went from 0.4 to") && strstr(o.warn, "x ") &&
               fabs(o.y[PX] * o.y[PX] + o.y[PY] * o.y[PY] - PL * PL) < 1e-12 && o.y[PY] > 0,
           "pendulum, positions guessed (0.1, 0.4): DAE_WARNING naming y and x (the upper "
           "half of the circle, y = %.6g)",
           o.y[PY]);
    /* a guess slightly off the circle: corrected, no warning */
    memcpy(y0, ye, sizeof y0);
    y0[PX] *= 1.001;
    y0[PLAM] = y0[PMU] = 0.0;
    o = pend_init(1, 1e-8, y0, NULL);
    tap_ok(o.rc == BG_OK && !o.warn[0] &&
               fabs(o.y[PX] * o.y[PX] + o.y[PY] * o.y[PY] - PL * PL) < 1e-12,
           "pendulum, x guessed 0.1 %% off: BG_OK, no warning (%s)", o.warn);
}

/* --------------------------------------------------- index 1 and index 2 rates ---- */

/* x1' = x2 + g1, x2' = -lam + g2, 0 = z - x1^2 - g3, 0 = x2 - s(t), with the solution
 * x1 = sin t, x2 = cos 2t, z = sin^2 t + cos 3t, lam = e^t: g1 = cos t - cos 2t,
 * g2 = -2 sin 2t + e^t, g3 = cos 3t, s = cos 2t. z is index 1, lam index 2. */
enum { MX1, MX2, MZ, MLAM, MN };

static int mfg_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[MX1] - y[MX2] - (cos(t) - cos(2 * t));
    F[1] = yp[MX2] + y[MLAM] - (-2 * sin(2 * t) + exp(t));
    F[2] = y[MZ] - y[MX1] * y[MX1] - cos(3 * t);
    F[3] = y[MX2] - cos(2 * t);
    return 0;
}

static void mfg_exact(double t, double *y, double *yp)
{
    y[MX1] = sin(t);
    y[MX2] = cos(2 * t);
    y[MZ] = sin(t) * sin(t) + cos(3 * t);
    y[MLAM] = exp(t);
    yp[MX1] = cos(t);
    yp[MX2] = -2 * sin(2 * t);
    yp[MZ] = 2 * sin(t) * cos(t) - 3 * sin(3 * t);
    yp[MLAM] = exp(t);
}

static void test_manufactured_rates(void)
{
    static const double dy[MN * MN] = {/* column-major: rows depending on x1, x2, z, lam */
                                       0, 0, 1, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
    static const double dyp[MN * MN] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    static const char *const names[MN] = {"x1", "x2", "z", "lam"};
    sp_csc *jy = sp_csc_from_dense(MN, MN, dy, 0.0), *jyp = sp_csc_from_dense(MN, MN, dyp, 0.0);
    const double t0 = 0.3, tol = 1e-10;
    double ye[MN], ype[MN];
    mfg_exact(t0, ye, ype);
    dae_problem p = {0};
    p.n = MN;
    p.res = mfg_res;
    p.jac_y_pattern = jy; /* no Jacobian: finite differences; kinds classified */
    p.jac_yp_pattern = jyp;
    p.names = names;
    dae_options o;
    dae_options_default(&o);
    o.rtol = o.atol = tol;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    double y0[MN] = {ye[MX1], ye[MX2] + 0.01, 0.0, 0.0}, y[MN] = {0}, yp[MN] = {0};
    int r = s ? dae_init(s, t0, y0, NULL) : err.status;
    if (r == 0) r = dae_consistent_init(s);
    if (r >= 0 && s) dae_get_consistent(s, y, yp);
    const int *kind = s ? dae_get_kinds(s) : NULL;
    tap_ok(kind && kind[MZ] == DAE_ALG && kind[MLAM] == DAE_ALG2,
           "manufactured: z is index 1, lam index 2");
    tap_diag("manufactured at t0 = 0.3: status %d; x2 %.17g (%.17g), z %.17g (%.17g), z' %.17g "
             "(%.17g), lam %.17g (%.17g), lam' %.17g (%.17g); init_error %.3g",
             r, y[MX2], ye[MX2], y[MZ], ye[MZ], yp[MZ], ype[MZ], y[MLAM], ye[MLAM], yp[MLAM],
             ype[MLAM], s ? dae_get_stats(s)->init_error : NAN);
    tap_ok(r == BG_OK && tol_units(y, ye, MN, tol) <= 1 && dae_get_stats(s)->init_error <= 1,
           "manufactured, FD Jacobian: x2 onto its constraint, z and lam to the tolerance "
           "(%.3g tolerances), init_error <= 1",
           tol_units(y, ye, MN, tol));
    tap_ok(r == BG_OK && fabs(yp[MZ] - ype[MZ]) <= tol * fabs(ype[MZ]) + tol &&
               fabs(yp[MX1] - ype[MX1]) <= tol * fabs(ype[MX1]) + tol,
           "manufactured, FD Jacobian: the index-1 rate z' = 2 sin t cos t - 3 sin 3t = %.12g "
           "to the tolerance (got %.12g), and x1'",
           ype[MZ], yp[MZ]);
    tap_ok(r == BG_OK && fabs(yp[MLAM] - ype[MLAM]) <= 1e-6 * ype[MLAM],
           "manufactured, FD Jacobian: the index-2 rate lam' = e^t0 = %.12g to 1e-6 (got %.12g)",
           ype[MLAM], yp[MLAM]);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
}

/* ------------------------------------------------------------------- crank ---- */

static void test_crank_multipliers_zero(void)
{
    const bp_problem *bp = bp_find("crank");
    for (int analytic = 1; analytic >= 0; analytic--) {
        bp_instance in = {0};
        bp_instance_init(&in, bp);
        dae_problem dp = in.dp;
        if (!analytic) dp.jac = NULL;
        dae_options o;
        dae_options_default(&o);
        o.rtol = o.atol = 1e-8;
        o.has_t_stop = 1;
        o.t_stop = bp->tend;
        bg_error err = {0};
        dae_solver *s = dae_create(&dp, &o, &err);
        double y0[24], y[24] = {0}, yp[24] = {0};
        memcpy(y0, bp->y0, sizeof y0);
        for (int i = 0; i < bp->n; i++)
            if (bp->kind[i] == DAE_ALG2) y0[i] = 0.0; /* w and lam not known */
        int r = s ? dae_init(s, bp->t0, y0, NULL) : err.status;
        if (r == 0) r = dae_consistent_init(s);
        if (r >= 0 && s) dae_get_consistent(s, y, yp);
        double u = tol_units(y, bp->y0, bp->n, 1e-8), up = tol_units(yp, bp->yp0, 14, 1e-8);
        tap_ok(r == BG_OK && s && !*dae_get_warning(s) && u <= 1 && up <= 1,
               "crank, %s Jacobian, accelerations and multipliers guessed 0: the stored "
               "consistent state found again (y within %.3g, y' within %.3g tolerances), no "
               "warning (status %d)",
               analytic ? "analytic" : "finite-difference", u, up, r);
        dae_free(&s);
        bp_instance_free(&in);
    }
}

/* ------------------------------------------------------------ a jump at t0 ---- */

/* x' = -x, 0 = z - 1 - 4 H(t) with H(t) = 1 for t > 0, 0 at t = 0: z is 1 at t0 = 0 and 5
 * just after. */
static int jump_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user;
    F[0] = yp[0] + y[0];
    F[1] = y[1] - 1.0 - (t > 0 ? 4.0 : 0.0);
    return 0;
}

static void test_jump_at_t0(void)
{
    static const double dy[4] = {1, 0, 0, 1}, dyp[4] = {1, 0, 0, 0};
    sp_csc *jy = sp_csc_from_dense(2, 2, dy, 0.0), *jyp = sp_csc_from_dense(2, 2, dyp, 0.0);
    dae_problem p = {0};
    p.n = 2;
    p.res = jump_res;
    p.jac_y_pattern = jy;
    p.jac_yp_pattern = jyp;
    dae_options o;
    dae_options_default(&o);
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    double y0[2] = {1.0, 1.0}, y[2] = {0};
    int r = s ? dae_init(s, 0.0, y0, NULL) : err.status;
    if (r == 0) r = dae_consistent_init(s);
    if (r >= 0 && s) dae_get_consistent(s, y, NULL);
    tap_ok(r == BG_OK && s && !*dae_get_warning(s) && y[1] == 5.0,
           "input jumping at t0: z from its left value 1 to its right value 5 (got %g) without "
           "a warning (status %d, %s)",
           y[1], r, s ? dae_get_warning(s) : err.message);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
}

/* ---------------------------------------------------------------- messages ---- */

static int failing_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t, (void)y, (void)yp, (void)F;
    return -3;
}

static void test_message_times(void)
{
    sp_csc *jy, *jyp;
    pend_patterns(&jy, &jyp);
    dae_problem p = {0};
    p.n = PN;
    p.res = failing_res;
    p.jac = pend_jac;
    p.jac_y_pattern = jy;
    p.jac_yp_pattern = jyp;
    p.kind = pend_kind;
    dae_options o;
    dae_options_default(&o);
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    double ye[PN], ype[PN];
    pend_exact(0.7, 1.3, ye, ype);
    int r = s ? dae_init(s, 0.0, ye, ype) : err.status;
    if (r == 0) r = dae_consistent_init(s);
    const char *m = s ? dae_get_error(s)->message : err.message;
    tap_ok(r == DAE_CALLBACK_FAIL && strstr(m, "t = 0 (just after)") && !strstr(m, "e-324"),
           "a residual failing at t0 = 0: DAE_CALLBACK_FAIL at \"t = 0 (just after)\", not at "
           "4.94e-324 (%s)",
           m);
    dae_free(&s);
    sp_csc_free(&jy);
    sp_csc_free(&jyp);
}

/* ------------------------------------------------------ a tiny stop time ---- */

/* The pendulum of examples/residual_only.c (length 1, velocity level, a residual alone). */
static int rpend_res(void *user, double t, const double *y, const double *yp, double *F)
{
    (void)user, (void)t;
    F[0] = yp[0] - y[2];
    F[1] = yp[1] - y[3];
    F[2] = yp[2] + y[4] * y[0];
    F[3] = yp[3] + y[4] * y[1] + PG;
    F[4] = y[0] * y[2] + y[1] * y[3];
    return 0;
}

/* Consistent values of rpend at t0 with t_stop: the status, y and y' into y, yp. */
static int rpend_init_at(double t0, double t_stop, double *y, double *yp, char *msg, size_t size)
{
    dae_problem p = {0};
    p.n = 5;
    p.res = rpend_res;
    dae_options o;
    dae_options_default(&o);
    o.rtol = o.atol = 1e-8;
    o.has_t_stop = 1;
    o.t_stop = t_stop;
    bg_error err = {0};
    dae_solver *s = dae_create(&p, &o, &err);
    const double th = 0.5, om = 1.0;
    double y0[5] = {sin(th), -cos(th), om * cos(th), om * sin(th), 0};
    int r = s ? dae_init(s, t0, y0, NULL) : err.status;
    if (r == 0) r = dae_consistent_init(s);
    if (r >= 0) dae_get_consistent(s, y, yp);
    snprintf(msg, size, "%s", s ? dae_get_error(s)->message : err.message);
    dae_free(&s);
    return r;
}

static int rpend_init(double t_stop, double *y, double *yp, char *msg, size_t size)
{
    return rpend_init_at(0.0, t_stop, y, yp, msg, size);
}

/* A run to t_stop = 1e-300 (the crane program's --t-end 1e-300) initialises as one to 1: the
 * differences in t keep a time scale of sqrt(eps) time units at least (IC_TSCALE_MIN; before,
 * they were taken from 1e-300 and every point failed: "the residual failed at every point of
 * the differences ... at t = 0: " with nothing after the colon). */
static void test_tiny_t_stop(void)
{
    double y1[5], yp1[5], y2[5], yp2[5];
    char m1[BG_MESSAGE_SIZE], m2[BG_MESSAGE_SIZE];
    int r1 = rpend_init(1e-300, y1, yp1, m1, sizeof m1), r2 = rpend_init(1.0, y2, yp2, m2, sizeof m2);
    const double lam = 1.0 + PG * cos(0.5), dlam = -3 * PG * sin(0.5); /* om^2 - g y; -3 g v */
    double dmax = 0;
    for (int i = 0; i < 5; i++)
        dmax = fmax(dmax, fmax(fabs(y1[i] - y2[i]), fabs(yp1[i] - yp2[i]) / (1 + fabs(yp2[i]))));
    tap_ok(r1 == BG_OK && r2 == BG_OK && fabs(y1[4] - lam) <= 1e-6 * lam &&
               fabs(yp1[4] - dlam) <= 1e-6 * fabs(dlam) && dmax <= 1e-8,
           "t_stop = 1e-300: consistent values as with t_stop = 1 (status %d, %d; lam %.10g, "
           "exact %.10g; lam' %.10g, exact %.10g; largest difference %.3g) %s",
           r1, r2, r1 >= 0 ? y1[4] : NAN, lam, r1 >= 0 ? yp1[4] : NAN, dlam,
           r1 >= 0 ? dmax : NAN, r1 < 0 ? m1 : "");
}

/* Short runs and tiny start times: the rate of the multiplier, lam' = -3 g v (closed form),
 * to 1e-6 whatever the span of the run or the start time. The span bounds the steps in t;
 * before, a run of 1.6e-8 to 1e-5 time units returned lam' = -4.70 (a third) or 0, the second
 * differences of the velocity constraint at steps of 1e-2 of the span being round-off that
 * Ridders' estimate called exact (all equal), and a start at t0 = 1e-300 failed as the run to
 * 1e-300 did ("the difference ... at the step 6.1e-307 is -nan"). */
static void test_short_runs(void)
{
    const double dlam = -3 * PG * sin(0.5), lam = 1.0 + PG * cos(0.5);
    const double t0s[] = {0, 0, 0, 0, 0, 1e-300, 1e-9, 1e-6};
    const double spans[] = {1.6e-8, 3e-8, 1e-7, 1e-6, 1e-5, 1, 1, 1e-6};
    for (size_t k = 0; k < sizeof spans / sizeof *spans; k++) {
        double y[5] = {0}, yp[5] = {0};
        char m[BG_MESSAGE_SIZE];
        int r = rpend_init_at(t0s[k], t0s[k] + spans[k], y, yp, m, sizeof m);
        tap_ok(r == BG_OK && fabs(y[4] - lam) <= 1e-6 * lam &&
                   fabs(yp[4] - dlam) <= 1e-6 * fabs(dlam),
               "t0 = %g, span %g: lam %.10g (exact %.10g), lam' %.10g (exact %.10g) %s",
               t0s[k], spans[k], y[4], lam, yp[4], dlam, r < 0 ? m : "");
    }
}

int main(void)
{
    test_pendulum_fd();
    test_pendulum_exact_start();
    test_pendulum_rates();
    test_pendulum_warning();
    test_manufactured_rates();
    test_crank_multipliers_zero();
    test_jump_at_t0();
    test_message_times();
    test_tiny_t_stop();
    test_short_runs();
    return tap_done();
}
