/* PID controller (ctl_pid) with the trapezoidal reference of the crane paper (sig_sources),
 * a rotating inertia (rot_inertia) and its sensors: tracking against the closed-form solution of
 * the closed loop, the solver's stops at the corners of the profile, smooth output limits, and
 * the analytic Jacobian. The parameter checks: bad gains, filter constants and limits refused
 * with messages naming the controller's path and the parameter. */
#include "bondgraph/param_check.h"
#include "cmptest.h"
#include "ctl_pid.h"
#include "rot_inertia.h"
#include "sensors.h"
#include "sig_sources.h"

typedef struct loop {
    bgr_model *m;
    int ref, rate, in, vel, acc, ang, pid, se;
} loop;

/* Torque actuator (Se = controller output) on a pure inertia J; the controller of the paper:
 * x = Kp err + Kd err' + Ki int err, err = omega_r - omega, err' = omega_r' - T/J. */
static loop build_loop(double J, double kp, double kd, double ki, int use_rate)
{
    loop L;
    L.m = bgr_model_create("loop");
    bgr_model *m = L.m;
    L.ref = sig_trapezoid(m, 0, "omega_r", 0.0, 2.0, 10.0, 12.0, 0.5, SIG_VALUE);
    /* the reference's rate (an algebraic unknown that jumps at the corners) only when used */
    L.rate =
        use_rate ? sig_trapezoid(m, 0, "omega_r_dot", 0.0, 2.0, 10.0, 12.0, 0.5, SIG_RATE) : -1;
    L.in = rot_inertia(m, 0, "platform", J);
    L.vel = rot_sensor(m, 0, "omega", L.in, ROT_VELOCITY);
    L.acc = rot_sensor(m, 0, "alpha", L.in, ROT_ACCELERATION);
    L.ang = rot_sensor(m, 0, "theta", L.in, ROT_ANGLE);
    ctl_pid_spec sp = {.kp = kp,
                       .ki = ki,
                       .kd = kd,
                       .reference = {BGR_OWN, L.ref, 0},
                       .measurement = {BGR_OWN, L.vel, 0},
                       .use_reference_rate = use_rate,
                       .reference_rate = {BGR_OWN, L.rate, 0},
                       .use_measurement_rate = 1,
                       .measurement_rate = {BGR_OWN, L.acc, 0}};
    L.pid = ctl_pid(m, 0, "pid", &sp);
    L.se = bgr_Se_signal(m, 0, "actuator", (bgr_ref){BGR_OWN, L.pid, 0});
    B(m, "drive", L.se, 0, L.in, 0);
    return L;
}

/* Closed form of E = theta_r - theta. With J omega' = x and omega' = omega_r' - E'':
 *   paper's law (err' = omega_r' - omega'):   (J + Kd) E'' + Kp E' + Ki E = J omega_r'(t)
 *   derivative on the measurement only:       (J + Kd) E'' + Kp E' + Ki E = (J + Kd) omega_r'(t)
 * (the forcing factor g is J or J + Kd), E(0) = E'(0) = 0, omega_r' = 0.25, 0, -0.25, 0 on
 * (0,2), (2,10), (10,12), (12,inf); real distinct roots. */
static void loop_exact(double J, double kp, double kd, double ki, double g, double t, double *E,
                       double *Ed)
{
    double a = J + kd, b = kp, c = ki, disc = b * b - 4 * a * c;
    double s1 = (-b + sqrt(disc)) / (2 * a), s2 = (-b - sqrt(disc)) / (2 * a);
    const double tk[5] = {0, 2, 10, 12, INFINITY}, slope[4] = {0.25, 0, -0.25, 0};
    double e0 = 0, e1 = 0;
    for (int k = 0; k < 4; k++) {
        double F = g * slope[k] / c, tau = fmin(t, tk[k + 1]) - tk[k];
        double Bc = (e1 - s1 * (e0 - F)) / (s2 - s1), Ac = e0 - F - Bc;
        double x = F + Ac * exp(s1 * tau) + Bc * exp(s2 * tau);
        double xd = s1 * Ac * exp(s1 * tau) + s2 * Bc * exp(s2 * tau);
        e0 = x;
        e1 = xd;
        if (t <= tk[k + 1]) break;
    }
    *E = e0;
    *Ed = e1;
}

static void test_tracking(void)
{
    const double J = 1.0, kp = 100.0, kd = 1.0, ki = 1000.0;
    loop L = build_loop(J, kp, kd, ki, 1);
    if (!compile_ok(L.m, "pid loop")) {
        bgr_model_free(&L.m);
        return;
    }
    double bp[8];
    int nb = bgr_breakpoints(L.m, 0.0, 20.0, bp, 8);
    tap_ok(nb == 3 && bp[0] == 2.0 && bp[1] == 10.0 && bp[2] == 12.0,
           "breakpoints of the trapezoid in (0, 20]: %d: 2, 10, 12", nb);
    dae_solver *s = solver_new(L.m, 1e-8, 1e-10, NULL, bp, nb < 8 ? nb : 8, 0.0);
    tap_ok(s != NULL, "pid loop: solver started");
    if (!s) {
        bgr_model_free(&L.m);
        return;
    }
    int n = bgr_n(L.m);
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    memcpy(y, bgr_y0(L.m), (size_t)n * sizeof *y);
    int vth = V(L.m, "loop/platform/angle"), vw = V(L.m, "loop/omega/velocity");
    int vu = V(L.m, "loop/pid/out"), vrate = V(L.m, "loop/omega_r_dot/rate");
    /* no help from the test: the solver evaluates its consistent start and every restart at a
     * corner just after it (right-hand limits), so the rate's jumps are taken in stride */
    int hit[3] = {0, 0, 0}, r = dae_consistent_init(s);
    long steps = 0;
    double t = 0, errmax = 0, raterr = 0, y12[2] = {NAN, NAN};
    while (t < 12.0 && r >= 0) {
        r = dae_step(s, 20.0, &t, y, yp);
        if (r < 0) break;
        steps++;
        double E, Ed;
        loop_exact(J, kp, kd, ki, J, t, &E, &Ed);
        double th_r = t <= 2    ? 0.125 * t * t
                      : t <= 10 ? 0.5 * t - 0.5
                                : 5.0 - 0.125 * (12 - t) * (12 - t);
        errmax = fmax(errmax, fabs(at(y, vth) - (th_r - E)));
        for (int k = 0; k < 3; k++)
            if (t == bp[k]) {
                hit[k] = 1;
                if (k == 2) {
                    y12[0] = at(y, vth);
                    y12[1] = at(y, vw);
                }
            }
        /* the reference's rate as a signal: 0.25 on (0, 2), 0 on (2, 10), -0.25 on (10, 12)
         * (at a corner itself it depends on which side the solver restarted from) */
        double want = t < 2 ? 0.25 : t < 10 ? 0.0 : -0.25;
        if (t != 2.0 && t != 10.0 && t != 12.0) raterr = fmax(raterr, fabs(at(y, vrate) - want));
    }
    if (r < 0) tap_diag("dae_step: %s: %s", dae_return_name(r), dae_get_error(s)->message);
    tap_ok(r >= 0 && hit[0] && hit[1] && hit[2],
           "pid loop: the solver stops at the corners t = 2, 10, 12 s (%ld steps)", steps);
    double E, Ed;
    loop_exact(J, kp, kd, ki, J, 12.0, &E, &Ed);
    tap_close(y12[0], 5.0, 0, 1e-3, "theta(12) within 1e-3 rad of 5 rad (got %.9f)", y12[0]);
    tap_close(y12[0], 5.0 - E, 0, 1e-6, "theta(12) = 5 - E(12) of the closed-form loop (%.9f)",
              5.0 - E);
    tap_close(y12[1], -Ed, 0, 1e-6, "omega(12) = omega_r(12) - E'(12) = %.3g", -Ed);
    tap_ok(errmax < 1e-6, "theta(t) at every step within 1e-6 of the closed form (max %.3g)",
           errmax);
    tap_ok(raterr < 1e-7,
           "the reference's rate signal at every step: 0.25, 0, -0.25 (max error %.3g)", raterr);
    (void)vu;
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&L.m);
}

/* The derivative on the measurement only (no reference rate): the controller output is continuous
 * at the corners, and the solver passes them with its own restart, no help from the test. The
 * loop error is then larger (forcing (J + Kd) omega_r' instead of J omega_r'). */
static void test_measurement_derivative(void)
{
    const double J = 1.0, kp = 100.0, kd = 1.0, ki = 1000.0;
    loop L = build_loop(J, kp, kd, ki, 0);
    if (!compile_ok(L.m, "derivative on the measurement")) {
        bgr_model_free(&L.m);
        return;
    }
    double bp[8];
    int nb = bgr_breakpoints(L.m, 0.0, 20.0, bp, 8);
    dae_solver *s = solver_new(L.m, 1e-8, 1e-10, NULL, bp, nb, 0.0);
    int n = bgr_n(L.m), vth = V(L.m, "loop/platform/angle");
    double *y = calloc((size_t)n, sizeof *y), *yp = calloc((size_t)n, sizeof *yp);
    double t = 0, errmax = 0, th12 = NAN;
    int r = s ? 0 : -1, hits = 0;
    while (r >= 0 && t < 12.0) {
        r = dae_step(s, 20.0, &t, y, yp);
        if (r < 0) {
            tap_diag("dae_step: %s", dae_get_error(s)->message);
            break;
        }
        double E, Ed;
        loop_exact(J, kp, kd, ki, J + kd, t, &E, &Ed);
        double th_r = t <= 2    ? 0.125 * t * t
                      : t <= 10 ? 0.5 * t - 0.5
                                : 5.0 - 0.125 * (12 - t) * (12 - t);
        errmax = fmax(errmax, fabs(at(y, vth) - (th_r - E)));
        hits += t == 2.0 || t == 10.0 || t == 12.0;
        if (t == 12.0) th12 = at(y, vth);
    }
    double E, Ed;
    loop_exact(J, kp, kd, ki, J + kd, 12.0, &E, &Ed);
    tap_ok(r >= 0 && hits == 3, "measurement derivative: stops at 2, 10, 12 s without help");
    tap_close(th12, 5.0 - E, 0, 1e-6, "measurement derivative: theta(12) = 5 - E(12) = %.9f",
              5.0 - E);
    tap_ok(errmax < 1e-6,
           "measurement derivative: theta(t) within 1e-6 of the closed form (max %.3g)", errmax);
    dae_free(&s);
    free(y);
    free(yp);
    bgr_model_free(&L.m);
}

/* Constant reference 1 and measurement 0.4 (err = 0.6), Kp = 3, Ki = 2, Kd = 0: the unlimited
 * output is v(t) = 1.8 + 1.2 t; with limits [-5, 5] of width eps the output is the smooth clamp of
 * v, within eps ln 2 of min(max(v, -5), 5) and exactly 5 - eps ln 2 (to exp(-1000)) where
 * v = 5, at t = 8/3. */
static void test_limits(void)
{
    const double eps = 0.01;
    bgr_model *m = bgr_model_create("lim");
    int r = sig_constant(m, 0, "r", 1.0, SIG_VALUE), y = sig_constant(m, 0, "y", 0.4, SIG_VALUE);
    ctl_pid_spec sp = {
        .kp = 3.0, .ki = 2.0, .reference = {BGR_OWN, r, 0}, .measurement = {BGR_OWN, y, 0}};
    int free_id = ctl_pid(m, 0, "free", &sp);
    sp.limit = 1;
    sp.out_min = -5.0;
    sp.out_max = 5.0;
    sp.smoothing = eps;
    int lim_id = ctl_pid(m, 0, "limited", &sp);
    tap_ok(free_id >= 0 && lim_id >= 0, "limits: controllers created");
    if (!compile_ok(m, "limits")) {
        bgr_model_free(&m);
        return;
    }
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int n = bgr_n(m);
    double *yv = calloc((size_t)n, sizeof *yv), *ypv = calloc((size_t)n, sizeof *ypv);
    int vf = V(m, "lim/free/out"), vl = V(m, "lim/limited/out"), vI = V(m, "lim/limited/integral");
    double dev = 0, t = 0, lin = 0, corner = NAN, tc = 8.0 / 3.0;
    int rr = s ? 0 : -1;
    double *yc = calloc((size_t)n, sizeof *yc);
    while (s && rr >= 0 && t < 10.0) {
        double tprev = t;
        rr = dae_step(s, 10.0, &t, yv, ypv);
        double v = 1.8 + 1.2 * t, hard = fmin(fmax(v, -5.0), 5.0);
        dev = fmax(dev, fabs(at(yv, vl) - hard));
        lin = fmax(lin, fabs(at(yv, vf) - v));
        if (rr >= 0 && tprev < tc && t >= tc && dae_dense(s, tc, yc, NULL) == BG_OK)
            corner = at(yc, vl);
    }
    if (s && rr >= 0) rr = solve_to(s, 10.0, yv, ypv); /* interpolated back to t = 10 */
    tap_ok(rr >= 0, "limits: integrated to t = 10");
    tap_ok(lin < 1e-8 * 13.8, "unlimited output = 1.8 + 1.2 t at every step (max error %.3g)", lin);
    tap_ok(dev <= eps * log(2.0) + 1e-9,
           "limited output within eps ln 2 = %.4g of the hard clamp (max %.4g)", eps * log(2.0),
           dev);
    tap_close(at(yv, vl), 5.0, 0, 1e-8, "limited output at t = 10 (v = 13.8): 5");
    tap_close(at(yv, vI), 6.0, 1e-7, 0, "integral of the error at t = 10: 0.6 * 10");
    tap_close(corner, 5.0 - eps * log(2.0), 0, 1e-7,
              "limited output where v = 5 (t = 8/3): 5 - eps ln 2");
    free(yc);
    dae_free(&s);
    free(yv);
    free(ypv);
    bgr_model_free(&m);
}

/* Derivative filter: measurement y = sin(w t), reference 0, Kd = 1 only, filter tau, z(0) = 0.
 * z' = (y - z) / tau has the closed form
 *   z(t) = (sin wt - w tau cos wt + w tau exp(-t / tau)) / (1 + w^2 tau^2),
 * and the output is u = -(y - z) / tau (the filtered derivative of -y). A second controller on
 * the same signal carries limits, for the Jacobian check of the filtered law through sat. */
static void test_derivative_filter(void)
{
    const double w = 2.0, tau = 0.1;
    bgr_model *m = bgr_model_create("filt");
    int r = sig_constant(m, 0, "r", 0.0, SIG_VALUE);
    int y = sig_sine(m, 0, "y", 1.0, w, 0.0, 0.0, SIG_VALUE);
    ctl_pid_spec sp = {.kd = 1.0,
                       .reference = {BGR_OWN, r, 0},
                       .measurement = {BGR_OWN, y, 0},
                       .derivative_filter = tau};
    int id = ctl_pid(m, 0, "pid", &sp);
    sp.kp = 0.5;
    sp.ki = 0.2;
    sp.limit = 1;
    sp.out_min = -1;
    sp.out_max = 1;
    sp.smoothing = 0.2;
    int id2 = ctl_pid(m, 0, "pid_lim", &sp);
    tap_ok(id >= 0 && id2 >= 0, "derivative filter: controllers created");
    if (!compile_ok(m, "derivative filter")) {
        bgr_model_free(&m);
        return;
    }
    int n = bgr_n(m);
    double *yv = calloc((size_t)n, sizeof *yv), *ypv = calloc((size_t)n, sizeof *ypv);
    random_point(n, NULL, 11, yv, ypv);
    check_jac(m, 0.7, yv, ypv, 1e-6, "filtered PID with and without limits");
    dae_solver *s = solver_new(m, 1e-10, 1e-12, NULL, NULL, 0, 0.0);
    int vu = V(m, "filt/pid/out"), vz = V(m, "filt/pid/filter");
    double dev = 0, t = 0;
    int rr = s ? 0 : -1;
    while (s && rr >= 0 && t < 3.0) {
        rr = dae_step(s, 3.0, &t, yv, ypv);
        double z =
            (sin(w * t) - w * tau * cos(w * t) + w * tau * exp(-t / tau)) / (1 + w * w * tau * tau);
        dev = fmax(dev, fabs(at(yv, vz) - z) + fabs(at(yv, vu) + (sin(w * t) - z) / tau));
    }
    tap_ok(rr >= 0 && t >= 3.0, "derivative filter: integrated to t = 3");
    tap_ok(dev < 1e-7, "filter state and output follow the closed form (max error %.3g)", dev);
    dae_free(&s);
    free(yv);
    free(ypv);
    bgr_model_free(&m);
}

/* Argument checks: the constructor refuses a derivative term without the measured rate and
 * limits without a width, with a message. */
static void test_arguments(void)
{
    bgr_model *m = bgr_model_create("args");
    int r = sig_constant(m, 0, "r", 1.0, SIG_VALUE);
    ctl_pid_spec sp = {
        .kp = 1, .kd = 2, .reference = {BGR_OWN, r, 0}, .measurement = {BGR_OWN, r, 0}};
    int id = ctl_pid(m, 0, "a", &sp);
    tap_ok(id < 0 && strstr(bgr_model_error(m)->message, "measured rate"),
           "Kd without the measured rate refused: %s", bgr_model_error(m)->message);
    sp.kd = 0;
    sp.limit = 1;
    sp.out_min = 0;
    sp.out_max = 1;
    id = ctl_pid(m, 0, "b", &sp);
    tap_ok(id < 0 && strstr(bgr_model_error(m)->message, "smoothing"),
           "limits without a width refused: %s", bgr_model_error(m)->message);
    sp.limit = 0;
    sp.kd = 1;
    sp.derivative_filter = -0.1;
    id = ctl_pid(m, 0, "c", &sp);
    tap_ok(id < 0 && strstr(bgr_model_error(m)->message, "derivative_filter"),
           "negative derivative filter refused: %s", bgr_model_error(m)->message);
    sp.derivative_filter = 0.1;
    sp.use_measurement_rate = 1;
    sp.measurement_rate = (bgr_ref){BGR_OWN, r, 0};
    id = ctl_pid(m, 0, "d", &sp);
    tap_ok(id < 0 && strstr(bgr_model_error(m)->message, "not both"),
           "measured rate and filter together refused: %s", bgr_model_error(m)->message);
    bgr_model_free(&m);
}

/* Every partial derivative of the loop (PID with limits near a corner, sensors, inertia,
 * trapezoid sources) against central differences. */
static void test_jacobian(void)
{
    loop L = build_loop(2.0, 5.0, 50.0, 2.0, 1);
    bgr_model *m = L.m;
    int in2 = rot_inertia(m, 0, "wheel", 0.5);
    int vel2 = rot_sensor(m, 0, "omega2", in2, ROT_VELOCITY);
    int acc2 = rot_sensor(m, 0, "alpha2", in2, ROT_ACCELERATION);
    ctl_pid_spec sp = {.kp = 0.7,
                       .ki = 0.3,
                       .kd = 0.4,
                       .reference = {BGR_OWN, L.ref, 0},
                       .measurement = {BGR_OWN, vel2, 0},
                       .use_reference_rate = 1,
                       .reference_rate = {BGR_OWN, L.rate, 0},
                       .use_measurement_rate = 1,
                       .measurement_rate = {BGR_OWN, acc2, 0},
                       .limit = 1,
                       .out_min = -0.5,
                       .out_max = 0.5,
                       .smoothing = 0.3};
    int pid2 = ctl_pid(m, 0, "pid2", &sp);
    int se2 = bgr_Se_signal(m, 0, "actuator2", (bgr_ref){BGR_OWN, pid2, 0});
    B(m, "drive2", in2, 0, se2, 0); /* reversed bond: the inertia sees its flow with sign -1 */
    if (!compile_ok(m, "jacobian model")) {
        bgr_model_free(&L.m);
        return;
    }
    int n = bgr_n(m);
    double *y = malloc((size_t)n * sizeof *y), *yp = malloc((size_t)n * sizeof *yp);
    random_point(n, NULL, 7, y, yp);
    check_jac(m, 1.3, y, yp, 1e-6, "pid, sensors, inertia, sources");
    random_point(n, NULL, 8, y, yp);
    check_jac(m, 11.0, y, yp, 1e-6, "same at another point");
    free(y);
    free(yp);
    bgr_model_free(&L.m);
}

/* Nominal magnitudes (ctl_pid.h): with limits [-0.5, 2] and Ki = 4 the output's scale is the
 * range 2 and the integral's 2 / 4 = 0.5; without limits, and for the filter state, nothing
 * (1). */
static void test_nominals(void)
{
    bgr_model *m = bgr_model_create("nom");
    int r = sig_step(m, 0, "r", 1.0, 0.0, 1.0, SIG_VALUE), y = sig_constant(m, 0, "y", 0.4, SIG_VALUE);
    ctl_pid_spec sp = {.kp = 3.0,
                       .ki = 4.0,
                       .kd = 0.5,
                       .reference = {BGR_OWN, r, 0},
                       .measurement = {BGR_OWN, y, 0},
                       .derivative_filter = 0.1};
    int a = ctl_pid(m, 0, "free", &sp);
    sp.limit = 1;
    sp.out_min = -0.5;
    sp.out_max = 2.0;
    sp.smoothing = 0.01;
    int b = ctl_pid(m, 0, "limited", &sp);
    tap_ok(a >= 0 && b >= 0, "nominals: controllers created");
    if (!compile_ok(m, "nominals")) {
        bgr_model_free(&m);
        return;
    }
    const double *nom = bgr_nominals(m);
    int lu = V(m, "nom/limited/out"), li = V(m, "nom/limited/integral");
    int lz = V(m, "nom/limited/filter"), fu = V(m, "nom/free/out"), fi = V(m, "nom/free/integral");
    tap_ok(lu >= 0 && nom[lu] == 2.0, "limited output: nominal max(|-0.5|, |2|) = 2 (%g)",
           lu >= 0 ? nom[lu] : NAN);
    tap_ok(li >= 0 && nom[li] == 0.5, "limited integral: nominal 2 / Ki = 0.5 (%g)",
           li >= 0 ? nom[li] : NAN);
    tap_ok(lz >= 0 && fu >= 0 && fi >= 0 && nom[lz] == 1.0 && nom[fu] == 1.0 && nom[fi] == 1.0,
           "filter state and the unlimited controller's output and integral: 1");
    bgr_model_free(&m);
}

/* The parameters of the controller (ctl_pid.h: the accepted ranges): NaN and infinite gains,
 * filter time constants < 0, not finite or with an overflowing inverse, limits that are not
 * finite or not ordered, smoothing widths <= 0; one test point each (param_check.h). */
static int mk_pid(bgr_model *m, bgr_comp c, const char *name, int which, double x)
{
    ctl_pid_spec sp = {.kp = 2.0,
                       .ki = 0.5,
                       .kd = 0.1,
                       .reference = {BGR_OWN, 0, 0},
                       .measurement = {BGR_OWN, 0, 0},
                       .derivative_filter = 0.05,
                       .limit = 1,
                       .out_min = -1.0,
                       .out_max = 1.0,
                       .smoothing = 0.01};
    double *field[7] = {&sp.kp,      &sp.ki,      &sp.kd,      &sp.derivative_filter,
                        &sp.out_min, &sp.out_max, &sp.smoothing};
    if (which >= 0 && which < 7) *field[which] = x;
    return ctl_pid(m, c, name, &sp);
}

static void test_param_checks(void)
{
    const double nan = NAN, inf = INFINITY;
    const char *POS = "expected a finite number > 0", *NNEG = "expected a finite number >= 0";
    const char *FIN = "expected a finite number";
    const pc_case cases[] = {
        {"ctl_pid", mk_pid, 0, nan, "kp = ", FIN},
        {"ctl_pid", mk_pid, 0, inf, "kp = ", FIN},
        {"ctl_pid", mk_pid, 1, nan, "ki = ", FIN},
        {"ctl_pid", mk_pid, 1, -inf, "ki = ", FIN},
        {"ctl_pid", mk_pid, 2, nan, "kd = ", FIN},
        {"ctl_pid", mk_pid, 2, inf, "kd = ", FIN},
        {"ctl_pid", mk_pid, 3, nan, "derivative_filter = ", NNEG},
        {"ctl_pid", mk_pid, 3, inf, "derivative_filter = ", NNEG},
        {"ctl_pid", mk_pid, 3, -0.05, "derivative_filter = ", NNEG},
        {"ctl_pid", mk_pid, 3, 1e-310, "derivative_filter = ", "finite 1 / derivative_filter"},
        {"ctl_pid", mk_pid, 4, nan, "out_min = ", FIN},
        {"ctl_pid", mk_pid, 4, -inf, "out_min = ", FIN},
        {"ctl_pid", mk_pid, 4, 1.0, "out_max = 1", "expected > out_min = 1"},
        {"ctl_pid", mk_pid, 5, inf, "out_max = ", FIN},
        {"ctl_pid", mk_pid, 5, -2.0, "out_max = -2", "expected > out_min = -1"},
        {"ctl_pid", mk_pid, 6, nan, "smoothing = ", POS},
        {"ctl_pid", mk_pid, 6, inf, "smoothing = ", POS},
        {"ctl_pid", mk_pid, 6, 0.0, "smoothing = ", POS},
        {"ctl_pid", mk_pid, 6, -0.01, "smoothing = ", POS},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    bgr_model *m = bgr_model_create("params");
    bgr_comp c = bgr_component(m, bgr_component(m, 0, "control"), "bad");
    int passed = pc_run(m, c, "x", cases, n);
    tap_diag("%d of %d refusals as required", passed, n);
    bgr_model_free(&m);
}

int main(void)
{
    test_tracking();
    test_measurement_derivative();
    test_limits();
    test_derivative_filter();
    test_arguments();
    test_jacobian();
    test_nominals();
    test_param_checks();
    return tap_done();
}
