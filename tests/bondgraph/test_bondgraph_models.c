/* Unit tests of the bond-graph modelling layer: compiled models solved by bg_dae against
 * independent truths.
 *
 *   2. power balance: at every sample of every model below, each junction, TF and GY has
 *      sum_k s_k e_k f_k = 0, the orientations s_k taken from the test's own record of the bonds
 *      (bond registry), the efforts and flows read by name (bgr_find_var): to rounding (1e-12 of
 *      sum |e f|) at points where the element equations hold (the solver's output made
 *      consistent again), and to 1e-7 at the solver's output itself, where the integrator
 *      satisfies the junction equations only to its Newton tolerance;
 *   3. classic models against closed forms:
 *      - series RLC under a constant voltage: q(t), i(t) (underdamped), the damped frequency from
 *        the zero crossings of i (event location) and the decay rate from successive overshoots;
 *      - mass-spring-damper released from a displacement (spring bond reversed);
 *      - DC motor (Se - 1 - R, I - GY - 1 - I, R) against the exact solution of its linear 2x2
 *        ODE (matrix exponential) and the steady speed k V / (R b + k^2);
 *      - two masses under a rigid velocity constraint (0-junction with Sf(0), index 2): the
 *        constraint efforts are classified index 2, consistent initialisation gives the force
 *        F m2 / (m1 + m2), the common velocity is v0 + F t / (m1 + m2);
 *      - a lever (TF) between a force and a mass in both directions: a = F / (r m) and r F / m,
 *        the source's flow v / r and r v;
 *      - two coupled undamped oscillators: the energy stays constant over several periods;
 *   5. hierarchy: 50 RC cells built by a function (components with exported ports, a nested
 *      sub-component) in a ladder; names like ladder/cell07/C/q; the steady state against a
 *      node analysis of the resistor ladder solved here;
 *   8. nominal magnitudes: a hydraulic RC with pressures of 1e6 Pa solved with rtol = 0, atol =
 *      1e-6 in SI units and with the pressures' nominal 1e6: the pressure's error against the
 *      closed form within the tolerance atol * nominal (1 Pa) with, of the order of 1e-6 Pa
 *      without, and the steps cut by more than 3.
 * Measured numbers are printed as TAP diagnostics. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bgtest.h"

#define PI 3.14159265358979323846

static const char *msg(const bgr_model *m)
{
    return bgr_model_error(m)->message;
}

/* Worst |sum_k s_k e_k f_k| / sum_k |e_k f_k| over the elements ids (0 if all sums vanish). */
static double power_worst(const bgr_model *m, const bond_reg *reg, const int *ids, int nids,
                          const double *y)
{
    double worst = 0;
    for (int k = 0; k < nids; k++) {
        double scale;
        int np;
        double s = power_sum(m, reg, ids[k], y, &scale, &np);
        double ratio = np < 2 ? INFINITY : s == 0 ? 0 : scale > 0 ? fabs(s) / scale : INFINITY;
        if (isnan(ratio)) ratio = INFINITY;
        worst = fmax(worst, ratio);
    }
    return worst;
}

/* Power balance bookkeeping: the worst ratio at the solver's output (junction equations hold
 * there to the Newton tolerance only) and at polished points (element equations to rounding). */
typedef struct pwacc {
    double raw, pol;
    int npol, fail;
} pwacc;

static void power_sample(bgr_model *m, const bond_reg *reg, const int *ids, int nids, double t,
                         const double *y, const double *yp, pwacc *acc)
{
    int n = bgr_n(m);
    acc->raw = fmax(acc->raw, power_worst(m, reg, ids, nids, y));
    double *z = malloc((size_t)n * sizeof *z), *zp = malloc((size_t)n * sizeof *zp);
    memcpy(z, y, (size_t)n * sizeof *z);
    memcpy(zp, yp, (size_t)n * sizeof *zp);
    if (polish(m, t, z, zp) != BG_OK)
        acc->fail++;
    else {
        acc->pol = fmax(acc->pol, power_worst(m, reg, ids, nids, z));
        acc->npol++;
    }
    free(z);
    free(zp);
}

static void power_report(const char *what, const char *where, const pwacc *a)
{
    tap_diag("%s: power balance at %s: worst |sum s e f| / sum |e f| = %.2g at the solver's "
             "output, %.2g at %d consistent points",
             what, where, a->raw, a->pol, a->npol);
    tap_ok(a->fail == 0 && a->npol > 0 && a->pol <= 1e-12,
           "%s: power balance at %s to rounding where the element equations hold (%d points, "
           "worst %.2g)",
           what, where, a->npol, a->pol);
    tap_ok(a->raw <= 1e-7, "%s: power balance at %s at the solver's output (worst %.2g <= 1e-7)",
           what, where, a->raw);
}

/* Compiles m and checks its Jacobian at a random point. */
static int compile_ok(bgr_model *m, const char *what)
{
    static tap_rng rng = {12345};
    if (!m) return tap_ok(0, "%s: builds", what);
    int st = bgr_compile(m);
    if (!tap_ok(st == BG_OK, "%s: compiles", what)) {
        tap_diag("%s", msg(m));
        return 0;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    for (int i = 0; i < n; i++) {
        y[i] = tap_rng_range(&rng, -1, 1);
        yp[i] = tap_rng_range(&rng, -1, 1);
    }
    char report[512] = "";
    int mm = bgr_check_jacobian(m, 0.5, y, yp, 1e-6, report, sizeof report);
    if (!tap_ok(mm == 0, "%s: bgr_check_jacobian at a random point: %d mismatches", what, mm))
        tap_diag("%s", report);
    free(y);
    free(yp);
    return 1;
}

/* ------------------------------------------------------------------- RLC ---- */

static int root_var = -1;

/* Event: the current (flow of the inductor's bond) crosses zero. */
static int current_root(void *user, double t, const double *y, const double *yp, double *g)
{
    (void)user, (void)t, (void)yp;
    g[0] = y[root_var];
    return 0;
}

static void test_rlc(void)
{
    const double V = 2.0, L = 0.5, Cap = 0.02, R = 1.0;
    bond_reg reg = {0};
    rlc_ids id = {-1, -1, -1, -1, -1};
    bgr_model *m = build_rlc(V, L, Cap, R, &reg, &id);
    if (!compile_ok(m, "RLC")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    /* L q'' + R q' + q / Cap = V, q(0) = q'(0) = 0:
     * q = Cap V (1 - e^{-a t} (cos wd t + a/wd sin wd t)), i = V / (L wd) e^{-a t} sin wd t */
    const double a = R / (2 * L), w0 = 1 / sqrt(L * Cap), wd = sqrt(w0 * w0 - a * a), Q = Cap * V;
    int vq = vid(m, "rlc/C/q"), vi = vid(m, "rlc/bL/f"), vp = vid(m, "rlc/L/p");
    root_var = vi;
    dae_solver *s = start_solver(m, 1e-8, 1e-10, 0.0, current_root);
    if (!tap_ok(s != NULL && vq >= 0 && vi >= 0 && vp >= 0, "RLC: solver starts")) {
        dae_free(&s);
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    static const double ts[] = {0.05, 0.1, 0.2, 0.35, 0.6, 1.0, 1.7, 2.5};
    const int ns = (int)(sizeof ts / sizeof ts[0]);
    double eq = 0, ei = 0, ep = 0, troot[8], qroot[8];
    int nroot = 0, ok = 1;
    int junction[1] = {id.J};
    pwacc pw = {0, 0, 0, 0};
    dae_dense(s, 0.0, y, yp);
    power_sample(m, &reg, junction, 1, 0.0, y, yp, &pw);
    for (int k = 0; k < ns && ok; k++) {
        double tret;
        int r;
        while ((r = dae_solve_to(s, ts[k], &tret, y, yp)) == DAE_ROOT_RETURN)
            if (nroot < 8) {
                troot[nroot] = tret;
                qroot[nroot++] = y[vq];
            }
        if (r != DAE_SUCCESS) {
            tap_diag("RLC: dae_solve_to: %s: %s", dae_return_name(r), dae_get_error(s)->message);
            ok = 0;
            break;
        }
        double t = ts[k], ex = exp(-a * t);
        double qx = Q * (1 - ex * (cos(wd * t) + a / wd * sin(wd * t)));
        double ix = V / (L * wd) * ex * sin(wd * t);
        eq = fmax(eq, fabs(y[vq] - qx) / Q);
        ei = fmax(ei, fabs(y[vi] - ix) / (V / (L * wd)));
        ep = fmax(ep, fabs(y[vp] - L * ix) / (V / wd));
        power_sample(m, &reg, junction, 1, t, y, yp, &pw);
    }
    tap_diag("RLC: max error q %.3g (of Cap V), i %.3g (of V/(L wd)), p %.3g; %d zero crossings "
             "of i",
             eq, ei, ep, nroot);
    tap_ok(ok && eq < 2e-6, "RLC: q(t) = closed form at %d times (max rel err %.2g < 2e-6)", ns,
           eq);
    tap_ok(ok && ei < 2e-6, "RLC: i(t) = closed form (max rel err %.2g < 2e-6)", ei);
    tap_ok(ok && ep < 2e-6, "RLC: inductor momentum p = L i (max rel err %.2g < 2e-6)", ep);
    power_report("RLC", "the 1-junction", &pw);
    /* zero crossings of i at t_k = k pi / wd; overshoots q(t_k) - Q = -Q e^{-a t_k} (-1)^k */
    if (tap_ok(nroot >= 4, "RLC: at least 4 zero crossings of the current located (%d)", nroot)) {
        double wd_est = PI * (nroot - 1) / (troot[nroot - 1] - troot[0]);
        double dmax = 0;
        for (int k = 0; k < nroot; k++)
            dmax = fmax(dmax, fabs(troot[k] - (k + 1) * PI / wd));
        double a_est = log(fabs(qroot[0] - Q) / fabs(qroot[2] - Q)) * wd_est / (2 * PI);
        int alt = 1;
        for (int k = 0; k < nroot; k++)
            alt = alt && ((qroot[k] - Q) * ((k % 2) ? -1 : 1) > 0); /* k = 0 is t_1: above Q */
        tap_diag("RLC: wd = %.12g (exact %.12g), decay %.12g (exact %.12g), crossing times off "
                 "by %.2g at most",
                 wd_est, wd, a_est, a, dmax);
        tap_close(wd_est, wd, 1e-6, 0, "RLC: damped frequency from the zero crossings of i");
        tap_ok(dmax < 1e-6, "RLC: crossing k at k pi / wd (max |dt| %.2g < 1e-6)", dmax);
        tap_close(a_est, a, 1e-5, 0, "RLC: decay rate R / 2L from successive overshoots");
        tap_ok(alt, "RLC: the overshoots alternate in sign (q above Q at the first crossing)");
    }
    const dae_stats *st = dae_get_stats(s);
    tap_diag("RLC: %ld steps, %ld rejected, %ld Newton iterations, %ld Jacobians", st->steps,
             st->rejected_error, st->newton_iters, st->jac_evals);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* ------------------------------------------------------ mass-spring-damper ---- */

static void test_msd(void)
{
    const double mass = 2.0, k = 50.0, b = 0.8, x0 = 0.1;
    bond_reg reg = {0};
    bgr_model *m = bgr_model_create("msd");
    int F = bgr_Se(m, 0, "force", 1, NULL), J = bgr_one(m, 0, "J", 4, 1);
    int M = bgr_I(m, 0, "mass", 1, mass), K = bgr_C(m, 0, "spring", 1, k);
    int D = bgr_R(m, 0, "damper", 1, b);
    int ok = F >= 0 && J >= 0 && M >= 0 && K >= 0 && D >= 0 &&
             reg_bond(m, &reg, 0, "bF", 1, P(m, F, 0), P(m, J, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "bm", 1, P(m, J, 1), P(m, M, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "bk", 1, P(m, K, 0), P(m, J, 2)) >= 0 && /* reversed */
             reg_bond(m, &reg, 0, "bb", 1, P(m, J, 3), P(m, D, 0)) >= 0;
    if (!ok) bgr_model_free(&m);
    if (!compile_ok(m, "mass-spring-damper")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    /* The spring's bond points into the junction: q' = -v, so q = -x. m x'' + b x' + k x = 0. */
    int vq = vid(m, "msd/spring/q"), vpm = vid(m, "msd/mass/p"), vv = vid(m, "msd/bm/f");
    if (vq >= 0) bgr_y0(m)[vq] = -x0;
    dae_solver *s = start_solver(m, 1e-8, 1e-10, 0.0, NULL);
    if (!tap_ok(s != NULL && vq >= 0 && vpm >= 0 && vv >= 0, "mass-spring-damper: solver starts")) {
        dae_free(&s);
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    const double a = b / (2 * mass), w0 = sqrt(k / mass), wd = sqrt(w0 * w0 - a * a);
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    double ex_ = 0, ev = 0, tret;
    int jun[1] = {J}, r = DAE_SUCCESS;
    pwacc pw = {0, 0, 0, 0};
    /* consistent start: the states are kept (nothing constrains them), the spring force k x0
     * decelerates the mass: p' = -k x0 */
    dae_dense(s, 0.0, y, yp);
    tap_diag("mass-spring-damper: after dae_consistent_init q = %.17g (set %.17g), p = %.3g, "
             "p' = %.17g (exact %.17g)",
             y[vq], -x0, y[vpm], yp[vpm], -k * x0);
    tap_ok(y[vq] == -x0 && y[vpm] == 0 && fabs(yp[vpm] + k * x0) <= 1e-12 * k * x0,
           "mass-spring-damper: consistent init keeps q = -x0, p = 0 and gives p' = -k x0");
    for (int i = 1; i <= 12 && r == DAE_SUCCESS; i++) {
        double t = 0.25 * i;
        r = dae_solve_to(s, t, &tret, y, yp);
        double e = exp(-a * t);
        double x = x0 * e * (cos(wd * t) + a / wd * sin(wd * t));
        double v = -x0 * w0 * w0 / wd * e * sin(wd * t);
        ex_ = fmax(ex_, fabs(-y[vq] - x) / x0);
        ev = fmax(ev, fmax(fabs(y[vv] - v), fabs(y[vpm] / mass - v)) / (x0 * w0));
        power_sample(m, &reg, jun, 1, t, y, yp, &pw);
    }
    tap_diag("mass-spring-damper: max error x %.3g (of x0), v %.3g (of x0 w0)", ex_, ev);
    tap_ok(r == DAE_SUCCESS && ex_ < 2e-6,
           "mass-spring-damper: x(t) = -q(t) = closed form at 12 times (max rel err %.2g)", ex_);
    tap_ok(r == DAE_SUCCESS && ev < 2e-6,
           "mass-spring-damper: v = p/m = bond flow = closed form (max rel err %.2g)", ev);
    power_report("mass-spring-damper", "the 1-junction", &pw);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* ------------------------------------------------------------- DC motor ---- */

/* E = exp(A t) for a real 2x2 A (row-major), from its eigenvalues tau +- sqrt(tau^2 - det). */
static void expm2(const double A[4], double t, double E[4])
{
    double tau = 0.5 * (A[0] + A[3]), det = A[0] * A[3] - A[1] * A[2], D = tau * tau - det;
    double c, s; /* E = e^{tau t} (c I + s (A - tau I)) */
    if (D < 0) {
        double mu = sqrt(-D);
        c = cos(mu * t);
        s = sin(mu * t) / mu;
    } else if (D > 0) {
        double mu = sqrt(D);
        c = cosh(mu * t);
        s = sinh(mu * t) / mu;
    } else {
        c = 1;
        s = t;
    }
    double e = exp(tau * t);
    E[0] = e * (c + s * (A[0] - tau));
    E[1] = e * s * A[1];
    E[2] = e * s * A[2];
    E[3] = e * (c + s * (A[3] - tau));
}

static void test_motor(void)
{
    const double V = 12.0, R = 2.0, L = 0.1, k = 0.5, Jr = 0.02, b = 0.1;
    bond_reg reg = {0};
    bgr_model *m = bgr_model_create("motor");
    int S = bgr_Se(m, 0, "V", 1, &V), Ja = bgr_one(m, 0, "Ja", 4, 1);
    int Ra = bgr_R(m, 0, "Ra", 1, R), La = bgr_I(m, 0, "La", 1, L);
    int G = bgr_GY(m, 0, "K", 1, k), Jw = bgr_one(m, 0, "Jw", 3, 1);
    int rot = bgr_I(m, 0, "rotor", 1, Jr), fr = bgr_R(m, 0, "friction", 1, b);
    int ok = S >= 0 && Ja >= 0 && Ra >= 0 && La >= 0 && G >= 0 && Jw >= 0 && rot >= 0 && fr >= 0 &&
             reg_bond(m, &reg, 0, "b1", 1, P(m, S, 0), P(m, Ja, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b2", 1, P(m, Ja, 1), P(m, Ra, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b3", 1, P(m, Ja, 2), P(m, La, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b4", 1, P(m, Ja, 3), P(m, G, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b5", 1, P(m, G, 1), P(m, Jw, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b6", 1, P(m, Jw, 1), P(m, rot, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b7", 1, P(m, Jw, 2), P(m, fr, 0)) >= 0;
    if (!ok) bgr_model_free(&m);
    if (!compile_ok(m, "DC motor")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int vi = vid(m, "motor/b3/f"), vw = vid(m, "motor/b6/f"), vT = vid(m, "motor/b5/e");
    dae_solver *s = start_solver(m, 1e-8, 1e-10, 0.0, NULL);
    if (!tap_ok(s != NULL && vi >= 0 && vw >= 0 && vT >= 0, "DC motor: solver starts")) {
        dae_free(&s);
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    /* L i' = V - R i - k w,  J w' = k i - b w:  x' = A x + u, x = (i, w) */
    const double A[4] = {-R / L, -k / L, k / Jr, -b / Jr};
    const double wss = k * V / (R * b + k * k), iss = b * V / (R * b + k * k);
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    static const double ts[] = {0.01, 0.03, 0.06, 0.1, 0.15, 0.25, 0.4};
    double err = 0, tret, E[4];
    int ids[3] = {Ja, G, Jw}, r = DAE_SUCCESS;
    pwacc pw = {0, 0, 0, 0};
    for (size_t q = 0; q < sizeof ts / sizeof ts[0] && r == DAE_SUCCESS; q++) {
        r = dae_solve_to(s, ts[q], &tret, y, yp);
        expm2(A, ts[q], E); /* x = x_ss + E (x0 - x_ss), x0 = 0 */
        double ix = iss - (E[0] * iss + E[1] * wss), wx = wss - (E[2] * iss + E[3] * wss);
        err = fmax(err, fmax(fabs(y[vi] - ix) / (V / R), fabs(y[vw] - wx) / wss));
        power_sample(m, &reg, ids, 3, ts[q], y, yp, &pw);
    }
    tap_diag("DC motor: max error vs exp(At): %.3g (of V/R, w_ss = %.6g)", err, wss);
    tap_ok(r == DAE_SUCCESS && err < 2e-6,
           "DC motor: i(t), w(t) = exact solution of the 2x2 ODE at 7 times (max rel err %.2g)",
           err);
    tap_ok(fabs(y[vT] - k * y[vi]) <= 1e-12 * fabs(k * y[vi]),
           "DC motor: GY torque e = k i (%.15g vs %.15g)", y[vT], k * y[vi]);
    r = dae_solve_to(s, 5.0, &tret, y, yp);
    power_sample(m, &reg, ids, 3, 5.0, y, yp, &pw);
    tap_diag("DC motor: w(5) = %.15g, k V / (R b + k^2) = %.15g; i(5) = %.15g", y[vw], wss, y[vi]);
    tap_close(r == DAE_SUCCESS ? y[vw] : NAN, wss, 1e-7, 0,
              "DC motor: steady speed w = k V / (R b + k^2)");
    tap_close(y[vi], iss, 1e-7, 0, "DC motor: steady current i = b V / (R b + k^2)");
    power_report("DC motor", "Ja, GY, Jw", &pw);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* ---------------------------------------------- two masses, rigid constraint ---- */

static void test_two_masses(void)
{
    const double F = 3.0, m1 = 1.0, m2 = 2.0, v0 = 0.5;
    bond_reg reg = {0};
    bgr_model *m = bgr_model_create("twomass");
    int S = bgr_Se(m, 0, "F", 1, &F), J1 = bgr_one(m, 0, "J1", 3, 1);
    int M1 = bgr_I(m, 0, "m1", 1, m1), Z = bgr_zero(m, 0, "Z", 3, 1);
    int Sf = bgr_Sf(m, 0, "rigid", 1, NULL), J2 = bgr_one(m, 0, "J2", 2, 1);
    int M2 = bgr_I(m, 0, "m2", 1, m2);
    int ok = S >= 0 && J1 >= 0 && M1 >= 0 && Z >= 0 && Sf >= 0 && J2 >= 0 && M2 >= 0 &&
             reg_bond(m, &reg, 0, "bF", 1, P(m, S, 0), P(m, J1, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b1", 1, P(m, J1, 1), P(m, M1, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "bz1", 1, P(m, J1, 2), P(m, Z, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "bz2", 1, P(m, Z, 1), P(m, J2, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "bs", 1, P(m, Sf, 0), P(m, Z, 2)) >= 0 &&
             reg_bond(m, &reg, 0, "b2", 1, P(m, J2, 1), P(m, M2, 0)) >= 0;
    if (!ok) bgr_model_free(&m);
    if (!compile_ok(m, "two masses")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    /* Z: common effort lambda, f_bz1 + f_bs - f_bz2 = 0 with f_bs = 0: v1 = v2 (p1/m1 = p2/m2, a
     * constraint on the states only). J1: F - p1' - lambda = 0, J2: lambda - p2' = 0.
     * Index 2 by hand (Dulmage-Mendelsohn of the algebraic rows, states known): the flows are
     * over-determined (6 flows, 7 rows: J1 x2, I1, Z sum, Sf, J2, I2), the efforts lambda (bz1,
     * bz2, bs) and the mass efforts e_b1 = F - lambda, e_b2 = lambda under-determined (5
     * unknowns, 4 rows: Z x2, J1 sum, J2 sum): 5 index-2 unknowns; e_bF = F is index 1. */
    const int *kind = bgr_kinds(m);
    int ebs = vid(m, "twomass/bs/e"), ebz1 = vid(m, "twomass/bz1/e"),
        ebz2 = vid(m, "twomass/bz2/e");
    int eb1 = vid(m, "twomass/b1/e"), eb2 = vid(m, "twomass/b2/e"), ebF = vid(m, "twomass/bF/e");
    int vp1 = vid(m, "twomass/m1/p"), vp2 = vid(m, "twomass/m2/p");
    int fb1 = vid(m, "twomass/b1/f"), fb2 = vid(m, "twomass/b2/f"), fbs = vid(m, "twomass/bs/f");
    if (!tap_ok(kind && ebs >= 0 && ebz1 >= 0 && ebz2 >= 0 && eb1 >= 0 && eb2 >= 0 && ebF >= 0 &&
                    vp1 >= 0 && vp2 >= 0 && fb1 >= 0 && fb2 >= 0 && fbs >= 0,
                "two masses: unknowns found by name")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    bgr_stats st;
    bgr_get_stats(m, &st);
    char alg2[512] = "";
    for (int v = 0; v < bgr_n(m); v++)
        if (kind[v] == DAE_ALG2) {
            strncat(alg2, " ", sizeof alg2 - strlen(alg2) - 1);
            strncat(alg2, bgr_var_name(m, v), sizeof alg2 - strlen(alg2) - 1);
        }
    tap_diag("two masses: index-2 unknowns:%s", alg2);
    tap_ok(kind[ebs] == DAE_ALG2, "two masses: the constraint effort twomass/bs/e is DAE_ALG2");
    tap_ok(kind[ebz1] == DAE_ALG2 && kind[ebz2] == DAE_ALG2 && kind[eb1] == DAE_ALG2 &&
               kind[eb2] == DAE_ALG2,
           "two masses: the efforts equal to or fixed by lambda are DAE_ALG2");
    tap_ok(kind[vp1] == DAE_DIFF && kind[vp2] == DAE_DIFF && kind[ebF] == DAE_ALG &&
               kind[fb1] == DAE_ALG && kind[fb2] == DAE_ALG && kind[fbs] == DAE_ALG,
           "two masses: momenta differential, source effort and flows index 1");
    tap_ok(st.index2 == 5 && st.differential == 2 && st.equations == 14,
           "two masses: 14 equations, 2 differential, 5 index 2 (got %d, %d, %d)", st.equations,
           st.differential, st.index2);
    double *y0 = bgr_y0(m);
    y0[vp1] = m1 * v0;
    y0[vp2] = m2 * v0;
    dae_solver *s = start_solver(m, 1e-8, 1e-10, 0.0, NULL);
    if (!tap_ok(s != NULL, "two masses: solver starts (consistent init)")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    int ids[3] = {J1, Z, J2};
    const double lam = F * m2 / (m1 + m2), acc = F / (m1 + m2);
    dae_dense(s, 0.0, y, yp);
    tap_diag("two masses: consistent init lambda = %.17g (F m2/(m1+m2) = %.17g), p1' = %.17g, "
             "p2' = %.17g",
             y[ebs], lam, yp[vp1], yp[vp2]);
    tap_close(y[ebs], lam, 1e-10, 0, "two masses: consistent init: constraint force F m2/(m1+m2)");
    tap_close(yp[vp1], m1 * acc, 1e-10, 0, "two masses: consistent init: p1' = m1 F/(m1+m2)");
    tap_close(yp[vp2], m2 * acc, 1e-10, 0, "two masses: consistent init: p2' = m2 F/(m1+m2)");
    double ev = 0, el = 0, tret;
    int r = DAE_SUCCESS;
    pwacc pw = {0, 0, 0, 0};
    power_sample(m, &reg, ids, 3, 0.0, y, yp, &pw);
    for (int i = 1; i <= 4 && r == DAE_SUCCESS; i++) {
        double t = 0.5 * i, v = v0 + acc * t;
        r = dae_solve_to(s, t, &tret, y, yp);
        ev = fmax(ev, fmax(fabs(y[fb1] - v), fabs(y[fb2] - v)) / v);
        ev = fmax(ev, fmax(fabs(y[vp1] / m1 - v), fabs(y[vp2] / m2 - v)) / v);
        el = fmax(el,
                  fmax(fabs(y[ebs] - lam), fmax(fabs(y[ebz1] - lam), fabs(y[ebz2] - lam))) / lam);
        power_sample(m, &reg, ids, 3, t, y, yp, &pw);
    }
    tap_diag("two masses: max rel error v %.3g, lambda %.3g", ev, el);
    tap_ok(r == DAE_SUCCESS && ev < 1e-8,
           "two masses: v1 = v2 = v0 + F t/(m1+m2) at 4 times (max rel err %.2g)", ev);
    tap_ok(r == DAE_SUCCESS && el < 1e-6,
           "two masses: the constraint force stays F m2/(m1+m2) (max rel err %.2g)", el);
    power_report("two masses", "J1, Z, J2", &pw);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* ------------------------------------------------------------------ lever ---- */

/* reverse = 0: Se -> TF port 0, TF port 1 -> mass: e0 = r e1, so the mass feels F / r and the
 * source moves at v / r.  reverse = 1: Se -> TF port 1 (the bond points into port 1), TF port 0 ->
 * mass: the mass feels r F and the source moves at r v. */
static void test_lever(int reverse)
{
    const double F = 2.0, mass = 4.0, r = 3.0, v0 = 0.5;
    const char *what = reverse ? "lever (source on port 1)" : "lever (source on port 0)";
    bond_reg reg = {0};
    bgr_model *m = bgr_model_create("lever");
    int S = bgr_Se(m, 0, "F", 1, &F), T = bgr_TF(m, 0, "T", 1, r), M = bgr_I(m, 0, "mass", 1, mass);
    int ok = S >= 0 && T >= 0 && M >= 0 &&
             reg_bond(m, &reg, 0, "bF", 1, P(m, S, 0), P(m, T, reverse ? 1 : 0)) >= 0 &&
             reg_bond(m, &reg, 0, "bm", 1, P(m, T, reverse ? 0 : 1), P(m, M, 0)) >= 0;
    if (!ok) bgr_model_free(&m);
    if (!compile_ok(m, what)) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int vp = vid(m, "lever/mass/p"), fF = vid(m, "lever/bF/f"), em = vid(m, "lever/bm/e");
    if (vp >= 0) bgr_y0(m)[vp] = mass * v0;
    dae_solver *s = start_solver(m, 1e-8, 1e-10, 0.0, NULL);
    if (!tap_ok(s != NULL && vp >= 0 && fF >= 0 && em >= 0, "%s: solver starts", what)) {
        dae_free(&s);
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    const double acc = reverse ? r * F / mass : F / (r * mass);
    const double ratio = reverse ? r : 1 / r; /* source flow / mass velocity */
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    int ids[1] = {T};
    double ev = 0, ef = 0, tret;
    int rc = DAE_SUCCESS;
    pwacc pw = {0, 0, 0, 0};
    dae_dense(s, 0.0, y, yp);
    tap_close(yp[vp] / mass, acc, 1e-12, 0, "%s: acceleration %s at t = 0", what,
              reverse ? "r F / m" : "F / (r m)");
    tap_close(y[em], reverse ? r * F : F / r, 1e-12, 0, "%s: effort on the mass %s", what,
              reverse ? "r F" : "F / r");
    for (int i = 1; i <= 3 && rc == DAE_SUCCESS; i++) {
        double t = 1.0 * i, v = v0 + acc * t;
        rc = dae_solve_to(s, t, &tret, y, yp);
        ev = fmax(ev, fabs(y[vp] / mass - v) / v);
        ef = fmax(ef, fabs(y[fF] - ratio * v) / (ratio * v));
        power_sample(m, &reg, ids, 1, t, y, yp, &pw);
    }
    tap_ok(rc == DAE_SUCCESS && ev < 1e-8, "%s: v = v0 + a t at 3 times (max rel err %.2g)", what,
           ev);
    tap_ok(rc == DAE_SUCCESS && ef < 1e-8, "%s: source flow = %s (max rel err %.2g)", what,
           reverse ? "r v" : "v / r", ef);
    power_report(what, "the TF", &pw);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* --------------------------------------------- two coupled oscillators: energy ---- */

static void test_oscillators(void)
{
    const double m1 = 1.0, m2 = 2.0, k1 = 4.0, k2 = 3.0, k12 = 1.5, q10 = 0.1, p20 = 0.05;
    bond_reg reg = {0};
    bgr_model *m = bgr_model_create("osc");
    int A = bgr_one(m, 0, "A", 3, 1), B = bgr_one(m, 0, "B", 3, 1), Z = bgr_zero(m, 0, "Z", 3, 1);
    int M1 = bgr_I(m, 0, "m1", 1, m1), M2 = bgr_I(m, 0, "m2", 1, m2);
    int K1 = bgr_C(m, 0, "k1", 1, k1), K2 = bgr_C(m, 0, "k2", 1, k2),
        K12 = bgr_C(m, 0, "k12", 1, k12);
    int ok = A >= 0 && B >= 0 && Z >= 0 && M1 >= 0 && M2 >= 0 && K1 >= 0 && K2 >= 0 && K12 >= 0 &&
             reg_bond(m, &reg, 0, "a1", 1, P(m, A, 0), P(m, M1, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "a2", 1, P(m, A, 1), P(m, K1, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "az", 1, P(m, A, 2), P(m, Z, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "zk", 1, P(m, Z, 1), P(m, K12, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "zb", 1, P(m, Z, 2), P(m, B, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b1", 1, P(m, B, 1), P(m, M2, 0)) >= 0 &&
             reg_bond(m, &reg, 0, "b2", 1, P(m, K2, 0), P(m, B, 2)) >= 0; /* reversed */
    if (!ok) bgr_model_free(&m);
    if (!compile_ok(m, "coupled oscillators")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int vp1 = vid(m, "osc/m1/p"), vp2 = vid(m, "osc/m2/p"), vq1 = vid(m, "osc/k1/q"),
        vq2 = vid(m, "osc/k2/q"), vq12 = vid(m, "osc/k12/q");
    if (vp1 < 0 || vp2 < 0 || vq1 < 0 || vq2 < 0 || vq12 < 0) {
        tap_ok(0, "coupled oscillators: states found by name");
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    bgr_y0(m)[vq1] = q10;
    bgr_y0(m)[vp2] = p20;
    dae_solver *s = start_solver(m, 1e-9, 1e-12, 0.0, NULL);
    if (!tap_ok(s != NULL, "coupled oscillators: solver starts")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
#define ENERGY(y)                                                                                  \
    ((y)[vp1] * (y)[vp1] / (2 * m1) + (y)[vp2] * (y)[vp2] / (2 * m2) +                             \
     0.5 * (k1 * (y)[vq1] * (y)[vq1] + k2 * (y)[vq2] * (y)[vq2] + k12 * (y)[vq12] * (y)[vq12]))
    const double E0 = p20 * p20 / (2 * m2) + 0.5 * k1 * q10 * q10;
    int ids[3] = {A, Z, B}, rc = DAE_SUCCESS;
    double drift = 0, tret, T = 30.0, ptr = 0;
    pwacc pw = {0, 0, 0, 0};
    dae_dense(s, 0.0, y, yp);
    double Ei = ENERGY(y);
    /* the slowest normal mode has period 2 pi / w with w^2 the smaller eigenvalue of M^-1 K */
    double kk[4] = {(k1 + k12) / m1, -k12 / m1, -k12 / m2, (k2 + k12) / m2};
    double tr = kk[0] + kk[3], dt = kk[0] * kk[3] - kk[1] * kk[2];
    double wslow = sqrt(0.5 * (tr - sqrt(tr * tr - 4 * dt)));
    for (int i = 1; i <= 600 && rc == DAE_SUCCESS; i++) {
        rc = dae_solve_to(s, T * i / 600, &tret, y, yp);
        drift = fmax(drift, fabs(ENERGY(y) - E0) / E0);
        if (i % 60) continue;
        power_sample(m, &reg, ids, 3, tret, y, yp, &pw);
        /* at a consistent point, the powers into the storage elements sum to zero too */
        double *z = malloc((size_t)n * sizeof *z), *zp = malloc((size_t)n * sizeof *zp);
        memcpy(z, y, (size_t)n * sizeof *z);
        memcpy(zp, yp, (size_t)n * sizeof *zp);
        if (polish(m, tret, z, zp) != BG_OK) ptr = INFINITY;
        double pin = z[vid(m, "osc/a1/e")] * z[vid(m, "osc/a1/f")] +
                     z[vid(m, "osc/a2/e")] * z[vid(m, "osc/a2/f")] +
                     z[vid(m, "osc/zk/e")] * z[vid(m, "osc/zk/f")] +
                     z[vid(m, "osc/b1/e")] * z[vid(m, "osc/b1/f")] -
                     z[vid(m, "osc/b2/e")] * z[vid(m, "osc/b2/f")];
        ptr = fmax(ptr, fabs(pin) / (E0 * wslow));
        free(z);
        free(zp);
    }
#undef ENERGY
    const dae_stats *st = dae_get_stats(s);
    tap_diag("coupled oscillators: %.1f slow periods, E0 = %.6g, initial energy off by %.2g, max "
             "relative energy drift %.3g at rtol 1e-9 (%ld steps)",
             T * wslow / (2 * PI), E0, fabs(Ei - E0) / E0, drift, st->steps);
    tap_ok(
        rc == DAE_SUCCESS && drift < 1e-6,
        "coupled oscillators: energy constant over %.1f slow periods (max rel drift %.2g < 1e-6)",
        T * wslow / (2 * PI), drift);
    tap_ok(ptr < 1e-12,
           "coupled oscillators: the powers into the storage elements sum to zero at "
           "10 consistent points (max %.2g of E0 w)",
           ptr);
    power_report("coupled oscillators", "A, Z, B", &pw);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* ----------------------------------------------------------- 5. hierarchy ---- */

typedef struct cell_par {
    double Rs, Rg, Cap;
} cell_par;

/* An RC cell in component parent/name: a series resistor (1-junction "s" with R "Rs"), a node
 * (0-junction "n") with a capacitor "C" and a leak resistor in the sub-component "leak"
 * (exported there as "p"). The cell exports "in" (s port 0) and "out" (n port 3). Returns the
 * component or < 0. ids (may be NULL) receives s and n. */
static bgr_comp build_cell(bgr_model *m, bond_reg *reg, bgr_comp parent, const char *name,
                           const cell_par *cp, int ids[2])
{
    bgr_comp c = bgr_component(m, parent, name);
    if (c < 0) return c;
    bgr_comp lk = bgr_component(m, c, "leak");
    if (lk < 0) return lk;
    int Rg = bgr_R(m, lk, "R", 1, cp->Rg);
    if (Rg < 0 || bgr_export(m, lk, "p", P(m, Rg, 0)) != BG_OK) return -1;
    int s = bgr_one(m, c, "s", 3, 1), Rs = bgr_R(m, c, "Rs", 1, cp->Rs);
    int nd = bgr_zero(m, c, "n", 4, 1), C = bgr_C(m, c, "C", 1, 1.0 / cp->Cap);
    if (s < 0 || Rs < 0 || nd < 0 || C < 0 ||
        reg_bond(m, reg, c, "bs", 1, P(m, s, 1), P(m, Rs, 0)) < 0 ||
        reg_bond(m, reg, c, "bn", 1, P(m, s, 2), P(m, nd, 0)) < 0 ||
        reg_bond(m, reg, c, "bc", 1, P(m, nd, 1), P(m, C, 0)) < 0 ||
        reg_bond(m, reg, c, "bg", 1, P(m, nd, 2), bgr_comp_port(m, lk, "p")) < 0 ||
        bgr_export(m, c, "in", P(m, s, 0)) != BG_OK ||
        bgr_export(m, c, "out", P(m, nd, 3)) != BG_OK)
        return -1;
    if (ids) {
        ids[0] = s;
        ids[1] = nd;
    }
    return c;
}

static void test_ladder(void)
{
    enum { NC = 50 };
    const double V = 1.0, Rload = 5.0;
    const cell_par cp = {1.0, 20.0, 0.01};
    bond_reg reg = {0};
    bgr_model *m = bgr_model_create("ladder");
    int S = bgr_Se(m, 0, "V", 1, &V), load = bgr_R(m, 0, "load", 1, Rload);
    int jids[2 * NC], ok = S >= 0 && load >= 0;
    bgr_comp cells[NC];
    bgr_port prev = P(m, S, 0);
    for (int k = 0; k < NC && ok; k++) {
        char nm[16], bn[16];
        snprintf(nm, sizeof nm, "cell%02d", k);
        snprintf(bn, sizeof bn, "b%02d", k);
        cells[k] = build_cell(m, &reg, 0, nm, &cp, jids + 2 * k);
        ok = cells[k] >= 0 &&
             reg_bond(m, &reg, 0, bn, 1, prev, bgr_comp_port(m, cells[k], "in")) >= 0;
        prev = bgr_comp_port(m, cells[k], "out");
    }
    ok = ok && reg_bond(m, &reg, 0, "bend", 1, prev, P(m, load, 0)) >= 0;
    if (!ok) {
        tap_diag("building the ladder: %s", msg(m));
        bgr_model_free(&m);
    }
    if (!compile_ok(m, "ladder of 50 RC cells")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    bgr_stats st;
    bgr_get_stats(m, &st);
    /* hand count: components 1 + 2 x 50; elements 2 + 5 x 50; bonds 4 x 50 internal + 51
     * joining; unknowns 2 x bonds + 50 charges */
    tap_ok(st.components == 1 + 2 * NC && st.elements == 2 + 5 * NC && st.bonds == 5 * NC + 1 &&
               st.equations == 2 * (5 * NC + 1) + NC && st.differential == NC,
           "ladder: %d components, %d elements, %d bonds, %d equations, %d differential",
           st.components, st.elements, st.bonds, st.equations, st.differential);
    int found = 0;
    int vq[NC], ve[NC];
    for (int k = 0; k < NC; k++) {
        vq[k] = vid(m, "ladder/cell%02d/C/q", k);
        ve[k] = vid(m, "ladder/cell%02d/bc/e", k);
        found += vq[k] >= 0 && ve[k] >= 0 && vid(m, "ladder/cell%02d/bg/f", k) >= 0 &&
                 eqid(m, "ladder/cell%02d/leak/R/resistance", k) >= 0;
    }
    tap_ok(found == NC && bgr_find_var(m, "ladder/cell07/C/q") >= 0 &&
               !strcmp(bgr_var_name(m, bgr_find_var(m, "ladder/cell07/C/q")), "ladder/cell07/C/q"),
           "ladder: ladder/cellKK/C/q, .../bc/e, .../bg/f and .../leak/R/resistance found for all "
           "%d cells (%d)",
           NC, found);
    tap_ok(!strcmp(bgr_component_path(m, cells[7]), "ladder/cell07") &&
               bgr_comp_port(m, cells[7], "in").elem == jids[14] &&
               bgr_comp_port(m, cells[7], "in").port == 0 &&
               bgr_comp_port(m, cells[7], "out").elem == jids[15] &&
               bgr_comp_port(m, cells[7], "out").port == 3,
           "ladder: component path and exported ports of cell07");
    if (found != NC) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    /* independent steady state: node voltages u_k of the resistor ladder (capacitors open),
     * (u_{k-1} - u_k)/Rs = u_k/Rg + (u_k - u_{k+1})/Rs, u_{-1} = V, last node loaded by Rload:
     * tridiagonal, Thomas algorithm */
    double a[NC], bd[NC], c[NC], d[NC], u[NC];
    for (int k = 0; k < NC; k++) {
        a[k] = k ? -1 / cp.Rs : 0;
        c[k] = k < NC - 1 ? -1 / cp.Rs : 0;
        bd[k] = 1 / cp.Rs + 1 / cp.Rg + (k < NC - 1 ? 1 / cp.Rs : 1 / Rload);
        d[k] = k ? 0 : V / cp.Rs;
    }
    for (int k = 1; k < NC; k++) {
        double w = a[k] / bd[k - 1];
        bd[k] -= w * c[k - 1];
        d[k] -= w * d[k - 1];
    }
    u[NC - 1] = d[NC - 1] / bd[NC - 1];
    for (int k = NC - 2; k >= 0; k--)
        u[k] = (d[k] - c[k] * u[k + 1]) / bd[k];
    /* slowest time constant <= Rg Cap = 0.2 (conductance matrix >= 1/Rg) */
    dae_solver *s = start_solver(m, 1e-8, 1e-10, 0.0, NULL);
    if (!tap_ok(s != NULL, "ladder: solver starts")) {
        bgr_model_free(&m);
        reg_free(&reg);
        return;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp), tret;
    double mono = 0;
    pwacc pw = {0, 0, 0, 0};
    int r = dae_solve_to(s, 0.05, &tret, y, yp);
    /* during the charge every node voltage lies between 0 and its steady value */
    for (int k = 0; k < NC; k++)
        mono = fmax(mono, fmax(-y[ve[k]], y[ve[k]] - u[k]));
    power_sample(m, &reg, jids, 2 * NC, 0.05, y, yp, &pw);
    if (r == DAE_SUCCESS) r = dae_solve_to(s, 8.0, &tret, y, yp);
    double eu = 0, eq = 0, eqp = 0;
    for (int k = 0; k < NC; k++) {
        eu = fmax(eu, fabs(y[ve[k]] - u[k]));
        eq = fmax(eq, fabs(y[vq[k]] - cp.Cap * u[k]) / cp.Cap);
        eqp = fmax(eqp, fabs(yp[vq[k]]));
    }
    power_sample(m, &reg, jids, 2 * NC, 8.0, y, yp, &pw);
    const dae_stats *ds = dae_get_stats(s);
    tap_diag("ladder: u0 = %.12g, u49 = %.6g; max |u - u_node analysis| %.3g, charge %.3g, |q'| "
             "%.3g (%ld steps)",
             y[ve[0]], y[ve[NC - 1]], eu, eq, eqp, ds->steps);
    tap_ok(r == DAE_SUCCESS && eu < 1e-7,
           "ladder: steady node voltages = node analysis of the resistor ladder (max err %.2g)",
           eu);
    tap_ok(r == DAE_SUCCESS && eq < 1e-7 && eqp < 1e-6,
           "ladder: steady charges q = Cap u (err %.2g), q' = 0 (%.2g)", eq, eqp);
    tap_ok(mono <= 1e-9, "ladder: at t = 0.05 every node voltage lies in [0, u_steady] (%.2g)",
           mono);
    power_report("ladder", "all 100 junctions", &pw);
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    reg_free(&reg);
}

/* ----------------------------------------------------- nominal magnitudes ---- */

/* A hydraulic RC: a pressure source V = 1e6 Pa (Se) charges an accumulator (C, stiffness
 * k = 1e6 Pa/m^3) through a restriction (R, r = 1e6 Pa s/m^3) on a 1-junction:
 * r q' + k q = V, so the accumulator's pressure is p_C(t) = k q = V (1 - exp(-t k / r)),
 * time constant 1 s; the pressures are of size 1e6, the volume and the flow of size 1. Solved
 * with rtol = 0 and atol = 1e-6 twice: in SI units (dae_problem.nominal = NULL: 1e-6 Pa on the
 * pressures, a relative 1e-12) and with the pressures' nominal magnitude 1e6 (the Se declares it
 * for its own effort, bgr_set_nominal states it for the R's and the C's: 1 Pa). Returns the
 * steps and the largest error of p_C at t = 0.25 .. 5 against the closed form. */
static int rc_nominal_run(int scaled, long *steps, long *newton, double *err)
{
    const double V = 1e6, r = 1e6, k = 1e6;
    bgr_model *m = bgr_model_create("hrc");
    int S = bgr_Se(m, 0, "V", 1, &V), J = bgr_one(m, 0, "J", 3, 1);
    int R = bgr_R(m, 0, "R", 1, r), C = bgr_C(m, 0, "C", 1, k);
    if (S < 0 || J < 0 || R < 0 || C < 0 ||
        bgr_bond(m, 0, "bse", 1, P(m, S, 0), P(m, J, 0), NULL, NULL) < 0 ||
        bgr_bond(m, 0, "bR", 1, P(m, J, 1), P(m, R, 0), NULL, NULL) < 0 ||
        bgr_bond(m, 0, "bC", 1, P(m, J, 2), P(m, C, 0), NULL, NULL) < 0 || bgr_compile(m) != BG_OK) {
        tap_diag("hydraulic RC: %s", msg(m));
        bgr_model_free(&m);
        return 0;
    }
    int vse = vid(m, "hrc/bse/e"), vr = vid(m, "hrc/bR/e"), vc = vid(m, "hrc/bC/e");
    const double *nom = bgr_nominals(m);
    if (scaled && (bgr_set_nominal(m, vr, 1e6) != BG_OK || bgr_set_nominal(m, vc, 1e6) != BG_OK)) {
        bgr_model_free(&m);
        return 0;
    }
    tap_ok(nom[vse] == 1e6, "hydraulic RC (%s): the Se declares its pressure's nominal 1e6 (%g)",
           scaled ? "scaled" : "SI", nom[vse]);
    dae_problem p;
    dae_options o;
    bg_error e = {0};
    bgr_dae_problem(m, &p);
    if (!scaled) p.nominal = NULL;
    dae_options_default(&o);
    o.rtol = 0;
    o.atol = 1e-6;
    o.max_steps = 1000000;
    dae_solver *s = dae_create(&p, &o, &e);
    int n = bgr_n(m), r_ = s ? dae_init(s, 0.0, bgr_y0(m), bgr_yp0(m)) : BG_ERR_ARGUMENT;
    if (r_ == BG_OK) r_ = dae_consistent_init(s);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp), tret;
    *err = 0;
    for (int i = 1; i <= 20 && r_ >= 0; i++) {
        double t = 0.25 * i;
        r_ = dae_solve_to(s, t, &tret, y, yp);
        *err = fmax(*err, fabs(y[vc] - V * (1 - exp(-t * k / r))));
    }
    int ok = r_ >= 0;
    if (!ok) tap_diag("hydraulic RC: %s", s ? dae_get_error(s)->message : e.message);
    *steps = s ? dae_get_stats(s)->steps : 0;
    *newton = s ? dae_get_stats(s)->newton_iters : 0;
    free(y);
    free(yp);
    dae_free(&s);
    bgr_model_free(&m);
    return ok;
}

static void test_nominal_tolerance(void)
{
    long st_si = 0, st_nom = 0, nw_si = 0, nw_nom = 0;
    double err_si = NAN, err_nom = NAN;
    int ok_si = rc_nominal_run(0, &st_si, &nw_si, &err_si);
    int ok_nom = rc_nominal_run(1, &st_nom, &nw_nom, &err_nom);
    tap_diag("hydraulic RC, rtol 0, atol 1e-6: SI units %ld steps, %ld Newton iterations, max "
             "error of p_C %.3g Pa; pressures' nominal 1e6: %ld steps, %ld Newton iterations, "
             "max error %.3g Pa",
             st_si, nw_si, err_si, st_nom, nw_nom, err_nom);
    tap_ok(ok_si && ok_nom, "hydraulic RC: both runs reach t = 5 s");
    /* the nominal makes the pressures' tolerance atol * 1e6 = 1 Pa: the error stays within a few
     * of it, and the run needs a fraction of the steps that 1e-6 Pa (a relative 1e-12) takes */
    tap_ok(ok_nom && err_nom <= 5.0,
           "with the nominal 1e6 the pressure error is within the tolerance atol * nominal = 1 Pa "
           "(max %.3g Pa over 20 times, bound 5 Pa)",
           err_nom);
    tap_ok(ok_si && err_si <= 1e-4,
           "in SI units the pressure error is of the order of atol = 1e-6 Pa, a relative 1e-12 "
           "(max %.3g Pa, bound 1e-4: the global error of 500 steps near round-off)",
           err_si);
    tap_ok(ok_si && ok_nom && err_nom > 1e3 * err_si,
           "the error follows the tolerance: more than 1e3 times larger with the 1e6 times looser "
           "one (%.3g against %.3g Pa)",
           err_nom, err_si);
    tap_ok(ok_si && ok_nom && 3 * st_nom < st_si,
           "the nominal cuts the steps by more than 3x (%ld against %ld)", st_nom, st_si);
}

int main(void)
{
    tap_diag("3. classic models against closed forms; 2. power balance in each");
    test_rlc();
    test_msd();
    test_motor();
    test_two_masses();
    test_lever(0);
    test_lever(1);
    test_oscillators();
    tap_diag("5. hierarchy");
    test_ladder();
    tap_diag("8. nominal magnitudes set the absolute tolerance");
    test_nominal_tolerance();
    return tap_done();
}
