/* The PID's extensions (ctl_pid.h): setpoint weighting, anti-windup by back-calculation, the
 * feedforward input, against closed forms; the analytic Jacobians of the new elements
 * (ctl_pid with them all, ctl_state_feedback's integral form, ctl_sway) against differences.
 *
 * Setpoint weighting: an inertia J omega' = u under u = Kp (b r - omega) + Ki I, I' = r - omega,
 * r = 1 from t = 0, at rest: z = (omega, I) solves z' = M z + c with M = [-Kp/J, Ki/J; -1, 0],
 * c = (Kp b r / J, r); its equilibrium z* = (r, Kp r (1 - b) / Ki) (the integral holds what the
 * weighted proportional term lacks) and z = z* + e^(M t)(z0 - z*), e^(M t) by Sylvester's
 * formula for M's distinct eigenvalues (Kp = 3, Ki = 2, J = 1: -1 and -2).
 * Anti-windup: an integrator alone (Kp = 0, Ki = 1) on the constant error 1, output limited to
 * [-0.5, 0.5]: I = t until the limit at t = 0.5, then I' = 1 + (0.5 - I) / Tt, so
 * I = 0.5 + Tt (1 - exp(-(t - 0.5) / Tt)) and the integral stops at 0.5 + Tt instead of
 * growing as t (the windup); the smooth limit's eps = 1e-7 keeps the difference at 1e-6. */
#include "cmptest.h"
#include "ctl_lqr.h"
#include "ctl_pid.h"
#include "ctl_sway.h"
#include "rot_inertia.h"
#include "sensors.h"
#include "sig_sources.h"

static void test_weighting(void)
{
    const double J = 1, kp = 3, ki = 2, b = 0.3, r = 1;
    bgr_model *m = bgr_model_create("w");
    int ref = sig_constant(m, 0, "r", r, SIG_VALUE);
    int in = rot_inertia(m, 0, "body", J), vel = rot_sensor(m, 0, "omega", in, ROT_VELOCITY);
    ctl_pid_spec sp = {.kp = kp,
                       .ki = ki,
                       .reference = {BGR_OWN, ref, 0},
                       .measurement = {BGR_OWN, vel, 0},
                       .weighted = 1,
                       .b = b,
                       .c = 0};
    int pid = ctl_pid(m, 0, "pid", &sp);
    int se = bgr_Se_signal(m, 0, "torque", (bgr_ref){BGR_OWN, pid, 0});
    B(m, "drive", se, 0, in, 0);
    if (!compile_ok(m, "weighted PI loop")) {
        bgr_model_free(&m);
        return;
    }
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_nvars(m), vw = bgr_ref_var(m, (bgr_ref){BGR_OWN, vel, 0}),
        vI = bgr_ref_var(m, (bgr_ref){BGR_STATE, pid, 0});
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double M[4] = {-kp / J, ki / J, -1, 0}; /* row-major */
    double l1 = -1, l2 = -2, zs[2] = {r, kp * r * (1 - b) / ki}, d0[2] = {-zs[0], -zs[1]};
    double worst = 0;
    int ok = s != NULL;
    for (int k = 1; k <= 12 && ok; k++) {
        double t = 0.5 * k, e1 = exp(l1 * t), e2 = exp(l2 * t), z[2];
        for (int i = 0; i < 2; i++) {
            double s1 = 0, s2 = 0;
            for (int j = 0; j < 2; j++) {
                double Mij = M[2 * i + j], Iij = i == j;
                s1 += (Mij - l2 * Iij) * d0[j];
                s2 += (Mij - l1 * Iij) * d0[j];
            }
            z[i] = zs[i] + s1 * e1 / (l1 - l2) + s2 * e2 / (l2 - l1);
        }
        ok = solve_to(s, t, y, yp) >= 0;
        worst = fmax(worst, fmax(fabs(y[vw] - z[0]), fabs(y[vI] - z[1])));
    }
    tap_ok(ok && worst < 1e-7, "setpoint weight b = 0.3: omega and I against the closed form, "
                               "largest error %.1e; I -> Kp r (1 - b) / Ki = %.2f",
           worst, zs[1]);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&m);
}

static void test_antiwindup(void)
{
    const double Tt = 2, eps = 1e-7;
    for (int aw = 0; aw <= 1; aw++) {
        bgr_model *m = bgr_model_create("aw");
        int one = sig_constant(m, 0, "one", 1, SIG_VALUE), zero = sig_constant(m, 0, "zero", 0, SIG_VALUE);
        ctl_pid_spec sp = {.kp = 0,
                           .ki = 1,
                           .reference = {BGR_OWN, one, 0},
                           .measurement = {BGR_OWN, zero, 0},
                           .limit = 1,
                           .out_min = -0.5,
                           .out_max = 0.5,
                           .smoothing = eps,
                           .tracking_time = aw ? Tt : 0};
        int pid = ctl_pid(m, 0, "pid", &sp);
        if (!compile_ok(m, aw ? "integrator with anti-windup" : "integrator without")) {
            bgr_model_free(&m);
            return;
        }
        dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
        int n = bgr_nvars(m), vI = bgr_ref_var(m, (bgr_ref){BGR_STATE, pid, 0});
        double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
        double worst = 0;
        int ok = s != NULL;
        for (int k = 1; k <= 16 && ok; k++) {
            double t = 0.5 * k;
            double I = !aw || t <= 0.5 ? t : 0.5 + Tt * (1 - exp(-(t - 0.5) / Tt));
            ok = solve_to(s, t, y, yp) >= 0;
            worst = fmax(worst, fabs(y[vI] - I));
        }
        tap_ok(ok && worst < 2e-6, "%s: the integral against %s, largest error %.1e (I(8) = %.6f)",
               aw ? "back-calculation, Tt = 2" : "no anti-windup",
               aw ? "0.5 + Tt (1 - exp(-(t - 0.5) / Tt))" : "t", worst, y[vI]);
        dae_free(&s);
        free(y);
        free(yp);
        bgr_model_free(&m);
    }
}

static void test_feedforward_and_checks(void)
{
    bgr_model *m = bgr_model_create("ff");
    int r = sig_constant(m, 0, "r", 0.2, SIG_VALUE), y = sig_constant(m, 0, "y", 0.1, SIG_VALUE),
        f = sig_constant(m, 0, "f", 0.3, SIG_VALUE);
    ctl_pid_spec sp = {.kp = 2,
                       .reference = {BGR_OWN, r, 0},
                       .measurement = {BGR_OWN, y, 0},
                       .use_feedforward = 1,
                       .feedforward = {BGR_OWN, f, 0}};
    int pid = ctl_pid(m, 0, "pid", &sp);
    if (compile_ok(m, "P with feedforward")) {
        dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
        int n = bgr_nvars(m), vu = bgr_ref_var(m, (bgr_ref){BGR_OWN, pid, 0});
        double *yy = calloc((size_t)n, sizeof *yy), *yp = calloc((size_t)n, sizeof *yp);
        int ok = s && solve_to(s, 1.0, yy, yp) >= 0;
        tap_ok(ok && fabs(yy[vu] - 0.5) < 1e-12, "u = Kp (r - y) + f = 2 * 0.1 + 0.3 = %.15g",
               yy[vu]);
        dae_free(&s);
        free(yy);
        free(yp);
    }
    bgr_model_free(&m);
    m = bgr_model_create("bad");
    ctl_pid_spec bad = {.kp = 1, .ki = 1, .tracking_time = 1};
    int st = ctl_pid(m, 0, "pid", &bad);
    tap_ok(st == BG_ERR_ARGUMENT && strstr(bgr_model_error(m)->message, "tracking_time"),
           "anti-windup without limits refused: %s", bgr_model_error(m)->message);
    bgr_model_free(&m);
}

static void test_jacobians(void)
{
    bgr_model *m = bgr_model_create("jac");
    int s[8];
    for (int i = 0; i < 8; i++) {
        char nm[8];
        snprintf(nm, sizeof nm, "s%d", i);
        s[i] = sig_constant(m, 0, nm, 0.1 * (i + 1), SIG_VALUE);
    }
#define S(i) ((bgr_ref){BGR_OWN, s[i], 0})
    ctl_pid_spec pp = {.kp = 2,
                       .ki = 0.7,
                       .kd = 0.3,
                       .reference = S(0),
                       .measurement = S(1),
                       .use_reference_rate = 1,
                       .reference_rate = S(2),
                       .derivative_filter = 0.05,
                       .limit = 1,
                       .out_min = -1,
                       .out_max = 1,
                       .smoothing = 0.05,
                       .weighted = 1,
                       .b = 0.4,
                       .c = 0.6,
                       .use_feedforward = 1,
                       .feedforward = S(3),
                       .tracking_time = 1.5};
    ctl_pid(m, 0, "pid", &pp);
    ctl_sf_spec sf = {.n = 3,
                      .gain = {1.5, -0.7, 2.2},
                      .x = {S(0), S(1), S(4)},
                      .use_ref = {1, 0, 1},
                      .r = {S(5), S(0), S(6)},
                      .integrate = 1,
                      .use_bias = 1,
                      .bias = S(7),
                      .use_bias_rate = 1,
                      .bias_rate = S(2)};
    ctl_state_feedback(m, 0, "sf", &sf);
    sf.integrate = 0;
    sf.use_bias_rate = 0;
    ctl_state_feedback(m, 0, "sf_value", &sf);
    ctl_sway_spec sw = {.x = S(0), .y = S(1), .vx = S(2), .vy = S(3), .theta = S(4),
                        .omega = S(5), .cx = 0.3, .cy = -0.2};
    ctl_sway(m, 0, "sway", &sw);
    if (compile_ok(m, "the new elements")) {
        int n = bgr_nvars(m);
        double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
        for (int seed = 1; seed <= 3; seed++) {
            random_point(n, NULL, (uint64_t)seed, y, yp);
            check_jac(m, 0.0, y, yp, 1e-6, "PID (all options), state feedback, sway sensor");
        }
        free(y);
        free(yp);
    }
    bgr_model_free(&m);
}

int main(void)
{
    test_weighting();
    test_antiwindup();
    test_feedforward_and_checks();
    test_jacobians();
    return tap_done();
}
